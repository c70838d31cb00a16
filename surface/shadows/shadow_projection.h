#pragma once
/// The shadow of one polygon on another's plane, from a light's centre of projection: the
/// geometry shared by the object-space method (surface/shadows/shadow_polygons.h, all faces
/// clipped once) and the scanline method (surface/scanline/, per span). An occluder triangle
/// T, cut to the slab strictly between the receiver's plane and the light (heights in
/// (kSlab s, (1 - kSlab) h_L), s the receiver's size, h_L the light's height above its plane;
/// no upper bound for a parallel light), shadows exactly the points of the plane whose ray
/// toward the light crosses T: the region bounded by the lines where the planes through the
/// light and each edge of T meet the receiver's plane (for a parallel light, the planes through
/// each edge containing its direction). No perspective division is made, so a receiver that
/// reaches behind the light, or an occluder nearly level with it, stays finite.
#include "core/math.h"
#include "surface/shadows/convex_polygon.h"
#include "surface/shadows/light_centre.h"
#include "surface/shape.h"

#include <array>
#include <vector>

namespace kasumi {

/// Relative tolerances, as fractions of the receiving face's size: vertices closer than
/// kOnLine to a cut line count as on it, and occluders closer than kSlab to the receiver's
/// plane (or to the light's level, for a point light) are cut off there.
inline constexpr double kOnLine = 1e-9;
inline constexpr double kSlab = 1e-6;

/// A face's plane frame: p = origin + u e_u + v e_v (world space, metres); `normal` = e_u × e_v
/// points to the light's side.
struct FaceFrame {
    DVec3 origin{0.0};
    DVec3 e_u{1.0, 0.0, 0.0};
    DVec3 e_v{0.0, 1.0, 0.0};
    DVec3 normal{0.0, 0.0, 1.0};
};

/// (u, v) of a world point in the frame (its projection onto the plane).
DVec2 to_frame(const FaceFrame& frame, const DVec3& p);

/// A receiving triangle seen from the light.
struct Receiver {
    FaceFrame frame;
    double light_height = 0.0;  ///< > 0: metres (point light) or cosine (parallel light)
    double size = 0.0;          ///< longest edge, metres
    bool degenerate = false;    ///< zero area: receives nothing
    /// False when the light is in the face's plane (to kOnLine of its size): no point is lit.
    bool faces_light = true;
};

/// The frame of triangle v (origin v[0], e_u along v[1] - v[0]) with its normal turned to the
/// light's side.
Receiver make_receiver(const std::array<DVec3, 3>& v, const LightCentre& light);

/// A triangle's bounding sphere as seen from the light: for a point light the cone from the
/// light around it (unit axis, half-angle; a light inside the sphere gives a half-angle of π
/// that culls nothing), for a parallel light the sphere's centre and radius (compared in the
/// plane across the light's direction).
struct LightView {
    DVec3 centre{0.0};
    double radius = 0.0;
    DVec3 axis{0.0, 0.0, 1.0};
    double half_angle = 0.0;
};
LightView light_view(const std::array<DVec3, 3>& v, const LightCentre& light);

/// False when no ray from the light can meet both triangles (their light views are apart).
bool may_overlap(const LightView& a, const LightView& b, const LightCentre& light);

/// A triangle that may cast a shadow, with where it comes from.
struct PolygonOccluder {
    std::array<DVec3, 3> vertices;
    uint32_t shape = 0;
    uint32_t primitive = 0;
    LightView view;
};

/// The triangles of every box, quad and mesh: all of them into triangles[shape][primitive]
/// (the Embree scene's order), and as occluders the light-facing ones of closed meshes (a ray
/// through the solid enters by one of them) and every one of open meshes and quads.
std::vector<PolygonOccluder> collect_occluders(
    const std::vector<Shape>& shapes, const LightCentre& light,
    std::vector<std::vector<std::array<DVec3, 3>>>& triangles);

/// The edge lines, in the receiver's frame, of the shadow `occluder` casts on the receiver's
/// plane: a point is shadowed when it lies inside all of them. Empty when it casts none there.
std::vector<HalfPlane> shadow_on_plane(const PolygonOccluder& occluder, const Receiver& receiver,
                                       const LightCentre& light);

}  // namespace kasumi
