#pragma once
/// Reads media from a scene's JSON.
#include "core/json_node.h"
#include "volume/medium.h"

namespace kasumi {

/// Parses one entry of `media` (see docs/scene-format.md): `homogeneous` boxes and `vdb` grids.
/// `index` names unnamed media; a relative `file` resolves against `base_dir`. Grid files are
/// loaded here, so load errors are input errors naming the file and the JSON path.
Medium parse_medium(const JsonNode& node, size_t index, const std::string& base_dir = "");

}  // namespace kasumi
