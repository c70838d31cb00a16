#pragma once
/// Brute-force sky: quadrature along rays in double precision, single scattering of sunlight
/// exactly (up to the quadrature), higher orders by Monte Carlo continuation. The ground truth
/// the fast tables are measured against. Radiance per unit solar irradiance at the top of the
/// atmosphere (1/sr), per band; positions in metres with the ground at the origin, +y up.
#include "core/rng.h"
#include "sky/sky_scene.h"

namespace kasumi {

/// Optical depth tau of the atmosphere along p + t d over [t0, t1] by the midpoint rule in a
/// variable u with t quadratic in u on each side of the point closest to the planet centre,
/// so nodes crowd where the air is densest. `steps` nodes in all.
Bands atmosphere_optical_depth(const Atmosphere& a, const DVec3& p, const DVec3& d, double t0,
                               double t1, int steps);

/// Transmittance from p to the top of the atmosphere toward the sun, times the fraction of the
/// sun's disc above the planet's horizon (0 in the Earth's shadow).
Bands sun_transmittance(const SkyScene& sky, const DVec3& p, int steps);

/// Fraction of a disc of angular radius `radius_rad` whose centre is `offset_rad` above a
/// straight horizon: (acos(-x) + x sqrt(1 - x²)) / pi with x = offset / radius clamped to ±1.
double disc_fraction_above(double offset_rad, double radius_rad);

struct SkySample {
    Bands radiance{};       ///< per unit TOA solar irradiance, 1/sr
    Bands transmittance{};  ///< along the ray over [0, t_max] (or to the ground / space)
};

/// What a ray from p along d (unit) meets up to distance t_max: in-scattered light of `orders`
/// scattering events (ground reflections count as events), the ground beyond if the ray hits
/// it within t_max, and the sun's disc if `sun_disc` and the ray leaves the atmosphere.
SkySample reference_sky(const SkyScene& sky, const DVec3& p, const DVec3& d, double t_max,
                        bool sun_disc, int orders, Pcg32& rng);

}  // namespace kasumi
