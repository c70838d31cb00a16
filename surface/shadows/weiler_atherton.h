#pragma once
/// Weiler–Atherton polygon clipping (Weiler & Atherton 1977, "Hidden surface removal using
/// polygon area sorting", SIGGRAPH '77), in the graph form of Weiler (1980, "Polygon comparison
/// using a graph representation", SIGGRAPH '80): a subject region (concave polygons with
/// holes, surface/shadows/polygon_region.h) is clipped against a clip region, giving both the
/// part inside the clip region and the part outside it, each as polygons with holes. This is
/// the clip of pass 1 of the object-space shadow method (Atherton, Weiler & Greenberg 1978):
/// a face against the whole shadow falling on it, concave or not, in one piece.
///
/// 1. Intersection lists. Each crossing of a subject edge with a clip edge is inserted into
///    both boundaries as one shared vertex, so the two lists are linked through it. The
///    degenerate cases are first reduced to shared vertices by one distance, `epsilon`
///    (metres; callers pass 1e-9 of the face's size, kOnLine): a clip vertex within epsilon of
///    a subject vertex becomes that vertex; one within epsilon of a subject edge moves onto the
///    edge and is inserted into it (a T-junction); a subject vertex within epsilon of a clip
///    edge is inserted into it. Overlapping collinear edges thus become the same edges,
///    touching vertices the same vertex, and slivers thinner than epsilon collapse. Subject
///    vertices never move and vertices inserted into subject edges lie on them, so the inside
///    and outside results together are the subject exactly: they share every cut edge, and
///    their areas sum to the subject's up to rounding (no cracks, no overlaps).
/// 2. Entry and exit. Each edge of the two lists between consecutive vertices is inside or
///    outside the other region (by the winding number of its midpoint), or lies on an edge of
///    it in the same or the opposite direction (coincident edges). An intersection vertex is
///    an entry of the subject list when the subject edge leaving it is inside the clip region
///    and an exit when it is outside; carrying the flag on the edge leaving each vertex rather
///    than on the vertex is Weiler's (1980) fix for vertices that touch without crossing and
///    for coincident edges, where the classic alternation of entries and exits fails.
/// 3. Traversal. The inside result follows the subject list from an entry to the next exit,
///    then the clip list from there to its next exit, and so on back to the start; the outside
///    result follows subject edges outside the clip and clip edges inside the subject,
///    backwards. Rings with no intersection (holes, islands, nested polygons) come out whole
///    by the same rule. Where several selected edges leave one vertex (results touching at a
///    point) the traversal takes the leftmost turn, so every result ring is simple.
/// Double precision throughout; no step divides by a length below epsilon.
#include "surface/shadows/polygon_region.h"

#include <cstddef>

namespace kasumi {

/// Both results of a clip: `inside` = subject ∩ clip, `outside` = subject \ clip.
struct RegionClip {
    PolygonRegion inside;
    PolygonRegion outside;
    size_t intersections = 0;  ///< crossings inserted into both lists (touches not counted)
};

/// Clips `subject` against `clip` (each: outer rings counter-clockwise, holes clockwise, no
/// ring crossing another of its own region). `epsilon`: metres, as above.
RegionClip weiler_atherton(const PolygonRegion& subject, const PolygonRegion& clip, double epsilon);

/// The union of a and b by the same traversal (edges of each outside the other, and one copy
/// of edges they share in the same direction); a's vertices never move.
PolygonRegion unite(const PolygonRegion& a, const PolygonRegion& b, double epsilon);

}  // namespace kasumi
