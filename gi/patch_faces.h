#pragma once
/// The planar faces of the scene's shapes, the raw material of radiosity patches and of the
/// emissive-surface sampler: quads, the six faces of boxes and mesh triangles, each with the
/// front normal the surface scene reports for it (surface/surface_scene.h).
#include "surface/shape.h"

#include <array>
#include <cstdint>
#include <vector>

namespace kasumi {

/// A convex planar face (a triangle or a quadrilateral) wound counter-clockwise about `normal`.
struct ShapeFace {
    std::array<Vec3, 4> vertices{};
    int vertex_count = 3;   ///< 3 or 4
    Vec3 normal{0.0f};      ///< unit, the front side (the hit's geometric normal there)
    float area = 0.0f;      ///< m²
    uint32_t shape = 0;     ///< index of the shape in the scene
    uint32_t material = 0;  ///< the shape's material
    /// Mesh triangles reversed to face their authored normals: vertices (p0, p2, p1), so the
    /// face's barycentric (u, v) is Embree's (v, u).
    bool swapped = false;
};

/// The faces of one shape (none for spheres), in the order face_index numbers them: a quad's one
/// face; a box's faces x-min, x-max, y-min, y-max, z-min, z-max; a mesh's triangles. Mesh faces
/// with authored vertex normals take the side those normals point to as the front.
std::vector<ShapeFace> shape_faces(const Shape& shape, uint32_t shape_index);

/// The face (as numbered by shape_faces) that Embree primitive `primitive` of `shape` belongs
/// to: quads and boxes are two triangles per face, meshes one.
uint32_t face_index(const Shape& shape, uint32_t primitive);

/// The point of the face at parameters (u, v): bilinear over a quad's corners v0 (0, 0), v1
/// (1, 0), v2 (1, 1), v3 (0, 1); v0 + u (v1 − v0) + v (v2 − v0) on a triangle.
Vec3 face_point(const ShapeFace& face, Vec2 uv);

/// The face parameters of a hit on Embree primitive `primitive` with barycentrics (bu, bv):
/// exact for triangles and parallelograms (a general convex quad is mapped as the
/// parallelogram of its first triangle's edges).
Vec2 face_uv(const ShapeFace& face, uint32_t primitive, float bu, float bv);

}  // namespace kasumi
