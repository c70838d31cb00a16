#pragma once
/// Equiangular sampling of distances along a ray toward a point (Kulla & Fajardo 2012,
/// "Importance Sampling Techniques for Path Tracing in Participating Media", EGSR): the density
/// in t is proportional to 1/d(t)², the inverse-square falloff of a point light, which removes
/// the singularity of single scattering near the light.
#include "core/math.h"

namespace kasumi {

/// The parametrisation of segment [t_a, t_b] of a ray by the angle seen from point c.
struct EquiangularSegment {
    float delta = 0.0f;    ///< t of the ray's closest approach to c
    float d = 0.0f;        ///< distance of closest approach, > 0
    float theta_a = 0.0f;  ///< angle of t_a, radians in (-π/2, π/2)
    float theta_b = 0.0f;  ///< angle of t_b

    /// ∫ dt / d(t)² over the segment, in 1/m: (theta_b - theta_a) / d.
    float inverse_square_integral() const { return (theta_b - theta_a) / d; }
    /// Distance along the ray for u in [0, 1).
    float sample(float u) const;
    /// Density of t per unit length: d / ((theta_b - theta_a) (d² + (t - delta)²)).
    float pdf(float t) const;
};

/// Prepares sampling of [t_a, t_b] on the ray (origin o, unit direction dir) toward c. A ray
/// through c itself gets a tiny positive closest distance so the density stays finite.
EquiangularSegment make_equiangular(const Vec3& o, const Vec3& dir, const Vec3& c, float t_a,
                                    float t_b);

}  // namespace kasumi
