// Shading interpolation: exact values at vertices and edge midpoints, flat shading constant per
// triangle, angle-weighted vertex normals, and the "shading" key.
#include "surface/shading.h"
#include "surface/shape.h"
#include "surface/surface_scene.h"

#include "test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

using test::input_error_of;

const Vec3 kP0(0.0f, 0.0f, 0.0f), kP1(2.0f, 0.0f, 0.0f), kP2(0.0f, 2.0f, 0.0f);

/// One triangle in z = 0 facing +z, with the given vertex normals (possibly none).
Shape triangle_shape(Shading shading, std::vector<Vec3> normals) {
    MeshShape mesh;
    mesh.mesh.positions = {kP0, kP1, kP2};
    mesh.mesh.normals = std::move(normals);
    mesh.mesh.triangles = {{0, 1, 2}};
    Shape s;
    s.geometry = mesh;
    s.shading = shading;
    return s;
}

SurfaceHit hit_at(const SurfaceScene& scene, const Vec3& point) {
    Ray ray;
    ray.origin = point + Vec3(0.0f, 0.0f, 3.0f);
    ray.direction = Vec3(0.0f, 0.0f, -1.0f);
    const auto hit = scene.intersect(ray);
    EXPECT_TRUE(hit.has_value()) << point.x << " " << point.y;
    return hit.value_or(SurfaceHit{});
}

void expect_near(const Vec3& a, const Vec3& b, float tolerance, const std::string& what) {
    EXPECT_NEAR(glm::length(a - b), 0.0f, tolerance)
        << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y
        << ", " << b.z << ")";
}

TEST(Shading, InterpolateIsExactAtVerticesAndMidpoints) {
    const std::array<float, 3> a = {1.0f, 10.0f, 100.0f};
    EXPECT_EQ(interpolate(a, 0.0f, 0.0f), 1.0f);
    EXPECT_EQ(interpolate(a, 1.0f, 0.0f), 10.0f);
    EXPECT_EQ(interpolate(a, 0.0f, 1.0f), 100.0f);
    EXPECT_EQ(interpolate(a, 0.5f, 0.0f), 5.5f);
    EXPECT_EQ(interpolate(a, 0.5f, 0.5f), 55.0f);
    EXPECT_EQ(interpolate(a, 0.0f, 0.5f), 50.5f);
    EXPECT_FLOAT_EQ(interpolate(a, 1.0f / 3.0f, 1.0f / 3.0f), 37.0f);
}

TEST(Shading, AngleWeightedNormalAtACubeCornerIsTheDiagonal) {
    // Three unit squares meeting at the origin, each split in two differently: the corner's
    // angles are π/2 per face whatever the split, so the normal is -(1, 1, 1) / √3 (faces wind
    // toward the outside of the cube [0, 1]³, i.e. toward -x, -y, -z here).
    const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                                 {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
    const std::vector<std::array<uint32_t, 3>> tris = {
        {0, 2, 4}, {0, 4, 1},  // z = 0, facing -z
        {0, 3, 5}, {0, 5, 2},  // x = 0, facing -x
        {0, 1, 3},             // y = 0, facing -y, split at the corner: two triangles with
        {1, 6, 3},             // angles π/2 and 0 at the origin
    };
    const std::vector<Vec3> n = angle_weighted_normals(p, tris);
    expect_near(n[0], -Vec3(1.0f) / std::sqrt(3.0f), 1e-6f, "corner");
    // A vertex used by one face only gets that face's normal.
    expect_near(n[6], Vec3(0, -1, 0), 1e-6f, "edge vertex");
}

TEST(Shading, PhongNormalsAreExactAtVerticesAndEdgeMidpoints) {
    const Vec3 n0 = glm::normalize(Vec3(-1.0f, -1.0f, 2.0f));
    const Vec3 n1 = glm::normalize(Vec3(1.0f, 0.0f, 1.0f));
    const Vec3 n2 = glm::normalize(Vec3(0.0f, 1.0f, 3.0f));
    const SurfaceScene scene({triangle_shape(Shading::Phong, {n0, n1, n2})});
    const std::pair<Vec3, Vec3> cases[] = {
        {kP0, n0},
        {kP1, n1},
        {kP2, n2},
        {0.5f * (kP0 + kP1), glm::normalize(n0 + n1)},
        {0.5f * (kP1 + kP2), glm::normalize(n1 + n2)},
        {0.5f * (kP0 + kP2), glm::normalize(n0 + n2)},
        {(kP0 + kP1 + kP2) / 3.0f, glm::normalize(n0 + n1 + n2)},
    };
    for (const auto& [point, normal] : cases) {
        const SurfaceHit hit = hit_at(scene, point);
        EXPECT_EQ(hit.shading, Shading::Phong);
        expect_near(hit.shading_normal, normal, 2e-6f, "phong");
        expect_near(hit.geometric_normal, Vec3(0, 0, 1), 0.0f, "geometric");
    }
}

TEST(Shading, FlatIsConstantPerTriangle) {
    const Vec3 n0 = glm::normalize(Vec3(-1.0f, -1.0f, 2.0f));
    const Vec3 n1 = glm::normalize(Vec3(1.0f, 0.0f, 1.0f));
    const Vec3 n2 = glm::normalize(Vec3(0.0f, 1.0f, 3.0f));
    const SurfaceScene scene({triangle_shape(Shading::Flat, {n0, n1, n2})});
    for (const Vec3& point : {kP0, kP1, kP2, 0.5f * (kP1 + kP2), Vec3(0.3f, 0.7f, 0.0f)}) {
        const SurfaceHit hit = hit_at(scene, point);
        EXPECT_EQ(hit.shading, Shading::Flat);
        EXPECT_EQ(hit.shading_normal, Vec3(0, 0, 1));
        EXPECT_EQ(hit.geometric_normal, Vec3(0, 0, 1));
    }
}

TEST(Shading, GouraudHitsCarryTheirTriangleAndBarycentrics) {
    const SurfaceScene scene({triangle_shape(Shading::Gouraud, {})});
    const SurfaceHit hit = hit_at(scene, Vec3(0.5f, 1.0f, 0.0f));  // u = 0.25, v = 0.5
    EXPECT_EQ(hit.shading, Shading::Gouraud);
    EXPECT_EQ(hit.primitive, 0u);
    EXPECT_NEAR(hit.u, 0.25f, 1e-6f);
    EXPECT_NEAR(hit.v, 0.5f, 1e-6f);
    const auto triangle = scene.triangle(hit);
    ASSERT_TRUE(triangle);
    EXPECT_EQ(triangle->positions[1], kP1);
    // No normals in the "file": computed ones, here the face normal.
    for (const Vec3& n : triangle->normals)
        expect_near(n, Vec3(0, 0, 1), 1e-7f, "computed normal");
}

TEST(Shading, ComputedNormalsOfAnIcosphereAreNearlyRadial) {
    const TriangleMesh mesh = load_obj(KASUMI_SOURCE_DIR "/data/meshes/icosphere2.obj");
    const std::vector<Vec3> n = angle_weighted_normals(mesh.positions, mesh.triangles);
    for (size_t i = 0; i < n.size(); ++i)
        EXPECT_GT(glm::dot(n[i], glm::normalize(mesh.positions[i])), 0.999f) << i;
    // The 12 icosahedron vertices (the only ones in 5 triangles; the loader renumbers
    // vertices) have 5-fold symmetric rings: exactly radial.
    std::vector<int> valence(mesh.positions.size(), 0);
    for (const auto& tri : mesh.triangles)
        for (const uint32_t i : tri)
            ++valence[i];
    int corners = 0;
    for (size_t i = 0; i < n.size(); ++i) {
        if (valence[i] != 5)
            continue;
        ++corners;
        expect_near(n[i], glm::normalize(mesh.positions[i]), 1e-6f, "icosahedron vertex");
    }
    EXPECT_EQ(corners, 12);
}

Shape parse_shape_text(const std::string& text) {
    static Json json;
    json = parse_json_text(text, "scene.json");
    return parse_shape(JsonNode(json, "scene.json", "/shapes/0"), {{"grey", 0}}, "");
}

TEST(Shading, KeyDefaultsAndErrors) {
    const std::string quad =
        R"("type": "quad", "material": "grey", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]])";
    EXPECT_EQ(shading_of(parse_shape_text("{" + quad + "}")), Shading::Flat);
    EXPECT_EQ(shading_of(parse_shape_text("{" + quad + R"(, "shading": "gouraud"})")),
              Shading::Gouraud);
    const std::string sphere = R"("type": "sphere", "material": "grey", "center": [0,0,0],
                                  "radius": 1)";
    EXPECT_EQ(shading_of(parse_shape_text("{" + sphere + "}")), Shading::Phong);
    EXPECT_EQ(shading_of(parse_shape_text("{" + sphere + R"(, "shading": "phong"})")),
              Shading::Phong);
    std::string message =
        input_error_of([&] { parse_shape_text("{" + sphere + R"(, "shading": "flat"})"); });
    EXPECT_NE(message.find("scene.json: /shapes/0/shading"), std::string::npos) << message;
    message = input_error_of([&] { parse_shape_text("{" + quad + R"(, "shading": "smooth"})"); });
    EXPECT_NE(message.find("scene.json: /shapes/0/shading"), std::string::npos) << message;
    EXPECT_NE(message.find("gouraud"), std::string::npos) << message;
    const std::string mesh = R"("type": "mesh", "material": "grey", "file": ")" KASUMI_SOURCE_DIR
                             R"(/data/meshes/icosphere2.obj")";
    EXPECT_EQ(shading_of(parse_shape_text("{" + mesh + "}")), Shading::Flat);  // no vn in the file
    EXPECT_EQ(shading_of(parse_shape_text("{" + mesh + R"(, "shading": "phong"})")),
              Shading::Phong);
}

}  // namespace
}  // namespace kasumi
