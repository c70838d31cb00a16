#pragma once
/// The projected solid angle of an intersection of spherical caps, in closed form by a contour
/// integral (docs/lights.md, "Exact penumbrae"). Directions are unit vectors; a cap is the set
/// of directions ω with ω · axis ≥ cos h, of half-angle h ≤ π/2 (h = π/2 is a hemisphere, i.e.
/// the side of a great circle: the edges of a convex spherical polygon).
#include "core/math.h"

#include <cstddef>

namespace kasumi {

/// An aggregate with no default member values (always built as {axis, cos_h, sin_h}): the exact
/// penumbra code keeps arrays of ~60 of them on the stack per shading point, and default values
/// made every call fill 2.4 KB before looking at a single occluder (2/3 of its time).
struct SphericalCap {
    DVec3 axis;    ///< unit
    double cos_h;  ///< cos of the half-angle, in [0, 1)
    double sin_h;  ///< sin of the half-angle, √(1 − cos_h²)
};

/// ∫ n · ω dω over the directions inside every one of `count` caps (signed: the caller keeps
/// the region above n's horizon when it wants the illuminance-like measure). By Stokes'
/// theorem on the unit sphere, ∫_A n · ω dω = ½ ∮_∂A n · (ω × dω) with ∂A counter-clockwise
/// seen from outside the sphere (Lambert's polygon formula is the great-circle case). The
/// boundary of an intersection of caps is made of arcs of their circles: the parts of circle i
/// inside every other cap, found in closed form per cap (an interval of azimuth), and a small
/// circle of axis a, half-angle h, frame (e1, e2, a) right-handed, from azimuth φ0 to φ1
/// contributes ½ sin h [sin h (n·a)(φ1 − φ0) − cos h ((n·e1)(sin φ1 − sin φ0) −
/// (n·e2)(cos φ1 − cos φ0))]. NaN when the arcs are too many for the fixed buffer (not
/// reached by convex regions of fewer than 16 circles).
double cap_intersection_projected_solid_angle(const SphericalCap* caps, size_t count,
                                              const DVec3& n);

}  // namespace kasumi
