#include "surface/shape.h"

#include "test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

using test::input_error_of;

const std::map<std::string, uint32_t> kMaterials = {{"grey", 0}, {"red", 1}};

/// Parses the shape at `index` of {"shapes": [...]}, as a scene loader would.
Shape parse_at(const std::string& shapes, size_t index, const std::string& base_dir = "") {
    static Json json;
    json = parse_json_text("{\"shapes\": " + shapes + "}", "scene.json");
    const JsonNode root(json, "scene.json");
    return parse_shape(root.child("shapes").child(index), kMaterials, base_dir);
}

/// Expects the shape at index 2 (after two valid spheres) to fail naming `pointer` and `reason`.
void expect_error(const std::string& shape, const std::string& pointer, const std::string& reason) {
    const std::string sphere =
        R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"})";
    const std::string message =
        input_error_of([&] { parse_at("[" + sphere + ", " + sphere + ", " + shape + "]", 2); });
    EXPECT_NE(message.find("scene.json: " + pointer + " "), std::string::npos)
        << shape << " -> " << message;
    EXPECT_NE(message.find(reason), std::string::npos) << shape << " -> " << message;
}

TEST(ShapeJson, Sphere) {
    const Shape s = parse_at(
        R"([{"type": "sphere", "center": [1, 2, 3], "radius": 0.5, "material": "red",
             "name": "ball"}])",
        0);
    const auto& sphere = std::get<SphereShape>(s.geometry);
    EXPECT_EQ(sphere.center, Vec3(1, 2, 3));
    EXPECT_EQ(sphere.radius, 0.5f);
    EXPECT_EQ(s.material, 1u);
    EXPECT_EQ(s.name, "ball");
}

TEST(ShapeJson, DefaultNameIsThePointer) {
    const Shape s =
        parse_at(R"([{"type": "box", "min": [0, 0, 0], "max": [1, 2, 3], "material": "grey"}])", 0);
    EXPECT_EQ(s.name, "/shapes/0");
    EXPECT_EQ(std::get<BoxShape>(s.geometry).max, Vec3(1, 2, 3));
}

TEST(ShapeJson, Quad) {
    const Shape s = parse_at(
        R"([{"type": "quad", "vertices": [[0, 0, 0], [2, 0, 0], [2, 0, -1], [0, 0, -1]],
             "material": "grey"}])",
        0);
    EXPECT_EQ(std::get<QuadShape>(s.geometry).vertices[2], Vec3(2, 0, -1));
}

TEST(ShapeJson, QuadFarFromOriginWithinRounding) {
    // 0.1 is not a float: coordinates near 1e4 round by ~5e-4 m, which must not read as warp.
    EXPECT_NO_THROW(parse_at(
        R"([{"type": "quad", "vertices": [[10000.1, 0.1, 10000.3], [10000.7, 0.1, 10000.3],
             [10000.7, 0.3, 10000.9], [10000.1, 0.3, 10000.9]], "material": "grey"}])",
        0));
}

TEST(ShapeJson, MeshResolvesRelativeToBaseDir) {
    const std::string dir = std::string(KASUMI_SOURCE_DIR) + "/data/meshes";
    const Shape s = parse_at(
        R"([{"type": "mesh", "file": "lamp_post.obj", "material": "grey",
             "translate": [10, 0, 0], "scale": 2}])",
        0, dir);
    const auto& mesh = std::get<MeshShape>(s.geometry);
    EXPECT_EQ(mesh.file, dir + "/lamp_post.obj");
    EXPECT_FALSE(mesh.mesh.triangles.empty());
    Vec3 lo(1e30f);
    for (const Vec3& p : mesh.mesh.positions)
        lo = glm::min(lo, p);
    EXPECT_EQ(lo.y, 0.0f);  // the post stands on y = 0
    EXPECT_GT(lo.x, 9.0f);
}

TEST(ShapeJson, BadSphere) {
    expect_error(R"({"type": "sphere", "center": [0, 0, 0], "radius": 0, "material": "grey"})",
                 "/shapes/2/radius", "must be > 0");
    expect_error(R"({"type": "sphere", "center": [0, 0], "radius": 1, "material": "grey"})",
                 "/shapes/2/center", "3 numbers");
    expect_error(R"({"type": "sphere", "center": [0, 0, 0], "material": "grey"})", "/shapes/2",
                 "missing required key \"radius\"");
    expect_error(
        R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey", "r": 1})",
        "/shapes/2/r", "unknown key");
}

TEST(ShapeJson, BadQuad) {
    expect_error(R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
                     "material": "grey"})",
                 "/shapes/2/vertices", "4 points");
    expect_error(R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0.01], [0, 1, 0]],
                     "material": "grey"})",
                 "/shapes/2/vertices", "not planar");
    expect_error(R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]],
                     "material": "grey"})",
                 "/shapes/2/vertices", "degenerate");
    expect_error(R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 0]],
                     "material": "grey"})",
                 "/shapes/2/vertices", "degenerate");
    expect_error(R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]],
                     "material": "grey"})",
                 "/shapes/2/vertices", "self-intersecting");
    expect_error(R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [0.2, 0.2, 0], [0, 1, 0]],
                     "material": "grey"})",
                 "/shapes/2/vertices", "not convex at vertex 2");
    expect_error(R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, "a"]],
                     "material": "grey"})",
                 "/shapes/2/vertices/3/2", "expected a number");
}

TEST(ShapeJson, BadBox) {
    expect_error(R"({"type": "box", "min": [0, 0, 0], "max": [1, 0, 1], "material": "grey"})",
                 "/shapes/2/max", "must exceed");
    expect_error(R"({"type": "box", "min": [0, 0, 0], "material": "grey"})", "/shapes/2",
                 "\"max\"");
}

TEST(ShapeJson, BadMesh) {
    expect_error(R"({"type": "mesh", "file": "missing.obj", "material": "grey"})", "/shapes/2/file",
                 "cannot open file");
    expect_error(R"({"type": "mesh", "file": 3, "material": "grey"})", "/shapes/2/file",
                 "expected a string");
    expect_error(R"({"type": "mesh", "file": "x.obj", "scale": -1, "material": "grey"})",
                 "/shapes/2/scale", "must be > 0");
}

TEST(ShapeJson, MeshLoadErrorNamesSceneAndObjLine) {
    const std::string path = test::write_temp_file("broken.obj", "v 0 0 0\nf 1 2 3\n");
    const std::string message = input_error_of([&] {
        parse_at(R"([{"type": "mesh", "file": ")" + path + R"(", "material": "grey"}])", 0);
    });
    EXPECT_NE(message.find("scene.json: /shapes/0/file"), std::string::npos) << message;
    EXPECT_NE(message.find(path + ":2:"), std::string::npos) << message;
}

TEST(ShapeJson, UnknownMaterialListsKnownOnes) {
    expect_error(R"({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "blue"})",
                 "/shapes/2/material", "known materials: grey, red");
}

TEST(ShapeJson, MissingMaterial) {
    expect_error(R"({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1]})", "/shapes/2",
                 "missing required key \"material\"");
}

TEST(ShapeJson, UnknownTypeListsKnownOnes) {
    expect_error(R"({"type": "cylinder", "material": "grey"})", "/shapes/2/type",
                 "box, mesh, quad, sphere");
}

}  // namespace
}  // namespace kasumi
