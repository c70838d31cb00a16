#pragma once
/// Reads lights from a scene's JSON.
#include "core/json_node.h"
#include "lights/light.h"

namespace kasumi {

/// Parses one entry of `lights`:
///   {"type": "directional", "direction", "illuminance_lux", "color"?, "name"?}
///   {"type": "point", "position", "intensity_cd" | "flux_lm", "color"?, "name"?}
/// `color` is an RGB chromaticity rescaled to unit luminance, so the photometric amount is
/// exactly the one given. `index` names unnamed lights ("light0", ...).
Light parse_light(const JsonNode& node, size_t index);

}  // namespace kasumi
