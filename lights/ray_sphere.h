#pragma once
/// Ray-sphere intersection in double precision (world space, metres).
#include "core/math.h"

#include <optional>

namespace kasumi {

/// The smallest root t in [t_near, t_far] of |origin + t direction - center| = radius, or none.
/// `direction` need not be unit length (t is then in its units). Uses the form of Haines et
/// al., "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7, 2019):
/// the discriminant r² - |f - (f·d/|d|²) d|² comes from the centre's perpendicular offset,
/// avoiding the cancellation of b² - c for small or distant spheres, and the root nearer the
/// origin is c / q, avoiding the cancellation of -b ± sqrt(Δ) for origins near the surface.
/// In double, a float ray and a sphere of any radius up to planet size give t to float
/// precision.
std::optional<double> intersect_sphere(const DVec3& center, double radius, const DVec3& origin,
                                       const DVec3& direction, double t_near, double t_far);

}  // namespace kasumi
