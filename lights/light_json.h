#pragma once
/// Reads lights from a scene's JSON.
#include "core/json_node.h"
#include "lights/light.h"

namespace kasumi {

/// Parses one entry of `lights` (every key is in docs/scene-format.md):
///   {"type": "directional", "direction", "illuminance_lux"}
///   {"type": "point", "position", "intensity_cd" | "flux_lm"}
///   {"type": "spot", "position", "direction", "intensity_cd" | "flux_lm", "cone_deg",
///    "falloff_deg"?}
///   {"type": "goniometric", "position", "ies", "rotation_deg"?, "flux_lm"?}
///   {"type": "line", "from", "to", "intensity_cd_per_m" | "flux_lm"}
///   {"type": "polygon", "vertices", "luminance_cd_m2", "two_sided"?}
///   {"type": "sphere", "center", "radius", "luminance_cd_m2"}
/// each with "name"?, "color"?, "shadows"? ("ray" | "none") and, for line, polygon and sphere
/// lights, "samples"?. `color` is an RGB chromaticity rescaled to unit luminance, so the
/// photometric amount is exactly the one given. `index` names unnamed lights ("light0", ...).
/// Relative IES paths resolve against the directory of node.file().
Light parse_light(const JsonNode& node, size_t index);

}  // namespace kasumi
