#pragma once
/// Plane regions bounded by polygons with holes: the operands and results of Weiler–Atherton
/// clipping (surface/shadows/weiler_atherton.h) and the surface-detail polygons of the
/// object-space shadow method. A region is a set of closed rings, outer boundaries
/// counter-clockwise and holes clockwise, so that the region lies to the left of every edge; a
/// point is inside when its winding number over all rings is nonzero (Sunday 2001, "Inclusion
/// of a point in a polygon"), which needs no pairing of holes with their outer rings.
#include "surface/shadows/convex_polygon.h"

#include <vector>

namespace kasumi {

/// A closed ring: vertices in order, the last joined to the first (metres, a plane frame).
using Ring = std::vector<DVec2>;

/// Rings whose union with their orientations bounds a region (outer rings counter-clockwise,
/// holes clockwise).
struct PolygonRegion {
    std::vector<Ring> rings;
};

/// Signed area in m² (shoelace formula; positive for a counter-clockwise ring).
double signed_area(const Ring& ring);

/// Area in m²: the sum of the rings' signed areas (holes subtract).
double area(const PolygonRegion& region);

/// Winding number of p about the region's rings (1 inside, 0 outside; a point on an edge
/// takes either side's value).
int winding_number(const PolygonRegion& region, const DVec2& p);

inline bool contains(const PolygonRegion& region, const DVec2& p) {
    return winding_number(region, p) != 0;
}

/// Distance in metres from p to the nearest edge of the region's rings.
double distance_to_boundary(const PolygonRegion& region, const DVec2& p);

/// The region of one convex polygon (counter-clockwise).
PolygonRegion region_of(const ConvexPolygon& polygon);

/// The region's polygons with holes: one region per counter-clockwise ring, holding that ring
/// first and then the clockwise rings whose nearest enclosing outer ring it is.
std::vector<PolygonRegion> polygons_with_holes(const PolygonRegion& region);

}  // namespace kasumi
