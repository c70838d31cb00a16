#pragma once
/// Reads media from a scene's JSON.
#include "core/json_node.h"
#include "volume/medium.h"

namespace kasumi {

/// Parses one entry of `media`: {"type": "homogeneous", "bounds"?: [min, max], "sigma_a",
/// "sigma_s" (1/m, scalar or RGB, >= 0), "phase"?: {...}, "name"?}. `index` names unnamed media.
Medium parse_medium(const JsonNode& node, size_t index);

}  // namespace kasumi
