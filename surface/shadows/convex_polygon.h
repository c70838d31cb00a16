#pragma once
/// Convex polygons in a face's plane and their split by a half-plane: the clipping step of the
/// object-space shadow method (Atherton, Weiler & Greenberg 1978, "Polygon shadow generation").
/// A polygon split by every edge line of a convex shadow keeps both sides (the Sutherland–
/// Hodgman clip, Sutherland & Hodgman 1974, returning the outside too), so the pieces partition
/// the polygon: their areas sum to its area up to rounding, with no cracks. Double precision:
/// the pieces of one face are cut again and again, and their area sum is a tested invariant.
#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include <vector>

namespace kasumi {

using DVec2 = glm::dvec2;

/// Vertices counter-clockwise, metres in the face's plane frame.
struct ConvexPolygon {
    std::vector<DVec2> vertices;
};

/// The closed half-plane dot(normal, p) + offset >= 0; |normal| = 1, so the value is the
/// signed distance in metres.
struct HalfPlane {
    DVec2 normal{0.0, 1.0};
    double offset = 0.0;
};

inline double signed_distance(const HalfPlane& h, const DVec2& p) {
    return h.normal.x * p.x + h.normal.y * p.y + h.offset;
}

/// Area in m² (shoelace formula; positive for counter-clockwise vertices).
double area(const ConvexPolygon& polygon);

/// The two sides of a split; a side the polygon does not reach is empty (no vertices).
struct PolygonSplit {
    ConvexPolygon inside;   ///< signed distance >= 0
    ConvexPolygon outside;  ///< signed distance <= 0
};

/// Splits `polygon` by the line of `h`. Vertices within `tolerance` metres of the line count as
/// on it (they go to both sides and no new vertex is made next to them), which keeps slivers
/// thinner than the tolerance from being made; the two sides still share the cut exactly.
PolygonSplit split(const ConvexPolygon& polygon, const HalfPlane& h, double tolerance);

/// True when p lies in the polygon or within `tolerance` metres outside an edge.
bool contains(const ConvexPolygon& polygon, const DVec2& p, double tolerance);

}  // namespace kasumi
