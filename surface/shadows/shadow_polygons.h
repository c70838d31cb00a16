#pragma once
/// Pass 1 of the two-pass object-space shadow method (Atherton, Weiler & Greenberg 1978,
/// "Polygon shadow generation", SIGGRAPH '78): seen from the light, every polygon is clipped
/// against the polygons in front of it, which splits each face into lit and shadowed
/// "surface-detail polygons" stored with the face. Pass 2 (surface/shadows/
/// object_space_shadows.h) shades a point by the detail polygon that contains it.
///
/// The clip is done in each receiving face's plane. An occluder triangle T, cut to the slab
/// strictly between the receiver's plane and the light (0 < height < the light's height; a
/// parallel light has no upper bound), shadows exactly the points p of the plane whose ray
/// toward the light crosses T: the intersection of the planes through the light and each edge
/// of T with the receiver's plane bound that region (a convex polygon, the projection of T
/// from the light). Working with these edge planes rather than projected vertices keeps a
/// receiver that reaches behind the light, or an occluder nearly level with the light, finite:
/// no perspective division happens. Each lit piece is split by the region's edge lines in turn
/// (surface/shadows/convex_polygon.h) to the part of the face it covers; these convex pieces
/// are united into the whole shadow on the face (concave, with holes, when the occluders are),
/// and the face is clipped against it once by Weiler–Atherton clipping (surface/shadows/
/// weiler_atherton.h): the inside result is the shadowed detail polygons, the outside the lit
/// ones, each a polygon with holes. (The convex decomposition of the first version, each lit
/// piece split by every occluder's edge lines in turn, is kept as ShadowClipper::ConvexSplit for
/// comparison: it gives the same lit/unlit answer with many more pieces.) Faces are triangles
/// (quads and boxes split as in the Embree scene), so concave meshes and coplanar faces need no
/// special case: a coplanar occluder lies in no slab, and a concave mesh is its triangles.
///
/// Occluders: the light-facing triangles of closed meshes (boxes, closed OBJ meshes; a ray
/// through the solid enters by one of them) and every triangle of open ones (quads, open
/// meshes). Spheres are not polygons: they receive and cast shadows by shadow rays (pass 2).
#include "core/math.h"
#include "surface/shadows/convex_polygon.h"
#include "surface/shadows/light_centre.h"
#include "surface/shadows/polygon_region.h"
#include "surface/shadows/shadow_projection.h"
#include "surface/shape.h"

#include <vector>

namespace kasumi {

/// The surface-detail polygons of one triangle face: `lit` and `shadowed` (polygons with
/// holes) together partition `face` (the triangle in its frame).
struct FaceDetail {
    FaceFrame frame;
    ConvexPolygon face;
    std::vector<PolygonRegion> lit;
    std::vector<PolygonRegion> shadowed;
    /// False when the light is in the face's plane (to 1e-9 of the face's size), so that no
    /// point of it is lit: the face is one shadowed piece.
    bool faces_light = true;
};

/// The detail polygons of a scene for one light.
struct ShadowPolygons {
    /// faces[shape][primitive]: the shape's triangles in the Embree scene's order (spheres:
    /// none).
    std::vector<std::vector<FaceDetail>> faces;
    size_t clipped_pairs = 0;  ///< occluder–receiver pairs whose shadow reached the receiver
};

/// How pass 1 clips a face against its shadow.
enum class ShadowClipper {
    WeilerAtherton,  ///< the face against the united shadow, once: lit and shadowed polygons
    ConvexSplit,     ///< each lit convex piece split by each occluder's shadow edges in turn
};

/// Pass 1: clips every face of `shapes` against the occluders in front of it from `light`.
/// Deterministic (faces are independent; each one's occluders are taken in scene order).
ShadowPolygons build_shadow_polygons(const std::vector<Shape>& shapes, const LightCentre& light,
                                     ShadowClipper clipper = ShadowClipper::WeilerAtherton);

}  // namespace kasumi
