#pragma once
/// The sun as seen from a point inside the atmosphere: its irradiance at the top of the
/// atmosphere attenuated by the air between the point and the sun, with the fraction of its
/// disc above the planet's horizon (Earth's shadow once it has set for that point). The
/// scene's sun light (make_sun_light) holds this value at the origin; media far from the
/// origin (clouds kilometres up or away) take it at their own scattering points.
#include "lights/light.h"
#include "sky/sky_renderer.h"

#include <optional>
#include <vector>

namespace kasumi {

/// Transmittance of the air from world point x (metres) toward the sun, per band, with the
/// visible fraction of its disc: the transmittance table in fast mode, the reference
/// quadrature (render.sky.sun_steps nodes) otherwise.
Bands sun_transmittance_at(const SkyRenderer& renderer, const DVec3& x);

/// Illuminance of the sun at world point x on a surface facing it, working RGB (lux):
/// SkyScene::to_rgb of sun_transmittance_at(x), the value make_sun_light gives the origin.
Rgb sun_illuminance_at(const SkyRenderer& renderer, const DVec3& x);

/// Index in `lights` of the directional light that parse_sky_keys made for the sun of `sky`
/// (named "sun", pointing along -sun_direction); empty when the scene has none.
std::optional<size_t> find_sun_light(const SkyScene& sky, const std::vector<Light>& lights);

}  // namespace kasumi
