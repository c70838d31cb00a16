#include "gi/patch_faces.h"

#include "surface/box_faces.h"

namespace kasumi {

namespace {

ShapeFace make_face(const Vec3* v, int count, uint32_t shape, uint32_t material) {
    ShapeFace f;
    f.vertex_count = count;
    for (int k = 0; k < count; ++k)
        f.vertices[k] = v[k];
    // Newell's normal: Σ v_k × v_{k+1} = 2 A n for a planar polygon.
    Vec3 sum(0.0f);
    for (int k = 0; k < count; ++k)
        sum += glm::cross(v[k], v[(k + 1) % count]);
    const float twice_area = glm::length(sum);
    f.area = 0.5f * twice_area;
    f.normal = twice_area > 0.0f ? sum / twice_area : Vec3(0.0f, 0.0f, 1.0f);
    f.shape = shape;
    f.material = material;
    return f;
}

}  // namespace

std::vector<ShapeFace> shape_faces(const Shape& shape, uint32_t shape_index) {
    std::vector<ShapeFace> faces;
    const uint32_t material = shape.material;
    if (const auto* quad = std::get_if<QuadShape>(&shape.geometry)) {
        faces.push_back(make_face(quad->vertices.data(), 4, shape_index, material));
    } else if (const auto* box = std::get_if<BoxShape>(&shape.geometry)) {
        for (const std::array<Vec3, 4>& c : box_faces(*box))
            faces.push_back(make_face(c.data(), 4, shape_index, material));
    } else if (const auto* mesh = std::get_if<MeshShape>(&shape.geometry)) {
        const TriangleMesh& m = mesh->mesh;
        for (const auto& t : m.triangles) {
            const Vec3 c[3] = {m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]};
            ShapeFace f = make_face(c, 3, shape_index, material);
            if (!m.normals.empty()) {
                const Vec3 authored = m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]];
                if (glm::dot(authored, f.normal) < 0.0f) {
                    std::swap(f.vertices[1], f.vertices[2]);
                    f.normal = -f.normal;
                    f.swapped = true;
                }
            }
            faces.push_back(f);
        }
    }
    return faces;
}

uint32_t face_index(const Shape& shape, uint32_t primitive) {
    return std::holds_alternative<MeshShape>(shape.geometry) ? primitive : primitive / 2;
}

Vec3 face_point(const ShapeFace& face, Vec2 uv) {
    const Vec3* v = face.vertices.data();
    if (face.vertex_count == 3)
        return v[0] + uv.x * (v[1] - v[0]) + uv.y * (v[2] - v[0]);
    return (1.0f - uv.x) * (1.0f - uv.y) * v[0] + uv.x * (1.0f - uv.y) * v[1] + uv.x * uv.y * v[2] +
           (1.0f - uv.x) * uv.y * v[3];
}

Vec2 face_uv(const ShapeFace& face, uint32_t primitive, float bu, float bv) {
    if (face.vertex_count == 3)
        return face.swapped ? Vec2(bv, bu) : Vec2(bu, bv);
    // Triangle (v0, v1, v2): p = v0 + bu (v1 - v0) + bv (v2 - v0) -> (bu + bv, bv);
    // triangle (v0, v2, v3): p = v0 + bu (v2 - v0) + bv (v3 - v0) -> (bu, bu + bv).
    return primitive % 2 == 0 ? Vec2(bu + bv, bv) : Vec2(bu, bu + bv);
}

}  // namespace kasumi
