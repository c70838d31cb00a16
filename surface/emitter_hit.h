#pragma once
/// Area lights seen directly: camera and Whitted rays that meet a polygon or sphere light see
/// its luminance (cd/m²), so a mirror shows the panel that lights the room. Point, spot,
/// goniometric and directional lights have no area and stay invisible; a line light is
/// treated as infinitely thin (zero area) and is invisible too.
#include "core/color.h"
#include "core/math.h"
#include "lights/light.h"

#include <optional>
#include <vector>

namespace kasumi {

struct EmitterHit {
    float t = 0.0f;      ///< metres along the ray
    Rgb radiance{0.0f};  ///< cd/m²: the light's luminance, 0 behind a one-sided polygon
    size_t light = 0;    ///< index into the light list
};

/// The nearest polygon or sphere light the ray meets with t in (ray.t_min, ray.t_max). A ray
/// starting inside a sphere light does not see it (spheres emit outward only).
std::optional<EmitterHit> intersect_emitters(const std::vector<Light>& lights, const Ray& ray);

/// True if any light in the list can be seen (has area).
bool has_visible_emitters(const std::vector<Light>& lights);

}  // namespace kasumi
