#include "surface/shape.h"

#include "test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

using test::input_error_of;
using test::write_temp_file;

const char* kSquareVertices =
    "# a unit square in z = 0\n"
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n"
    "vt 0 0\n"
    "vt 1 0\n"
    "vt 1 1\n"
    "vt 0 1\n"
    "vn 0 0 2\n";

void expect_square(const TriangleMesh& m) {
    ASSERT_EQ(m.triangles.size(), 2u);
    // Fan triangulation of (0, 1, 2, 3): (0, 1, 2) and (0, 2, 3).
    const Vec3 expected[2][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                                 {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    for (int t = 0; t < 2; ++t)
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(m.positions[m.triangles[t][k]], expected[t][k]) << t << " " << k;
}

TEST(ObjLoader, PlainIndices) {
    const auto m = load_obj(write_temp_file("a.obj", std::string(kSquareVertices) +
                                                         "o square\ng g\ns 1\nusemtl x\n"
                                                         "mtllib x.mtl\nf 1 2 3 4\n"));
    expect_square(m);
    EXPECT_TRUE(m.normals.empty());
    EXPECT_EQ(m.positions.size(), 4u);
}

TEST(ObjLoader, TextureIndicesAreIgnored) {
    const auto m =
        load_obj(write_temp_file("a.obj", std::string(kSquareVertices) + "f 1/1 2/2 3/3 4/4\n"));
    expect_square(m);
    EXPECT_TRUE(m.normals.empty());
}

TEST(ObjLoader, NormalIndicesWithoutTexture) {
    const auto m = load_obj(
        write_temp_file("a.obj", std::string(kSquareVertices) + "f 1//1 2//1 3//1 4//1\n"));
    expect_square(m);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (const Vec3& n : m.normals)
        EXPECT_EQ(n, Vec3(0, 0, 1));  // normalised on load
}

TEST(ObjLoader, FullCorners) {
    const auto m = load_obj(
        write_temp_file("a.obj", std::string(kSquareVertices) + "f 1/1/1 2/2/1 3/3/1 4/4/1\r\n"));
    expect_square(m);
    EXPECT_EQ(m.normals.size(), m.positions.size());
}

TEST(ObjLoader, NegativeIndicesCountBack) {
    const auto m =
        load_obj(write_temp_file("a.obj", std::string(kSquareVertices) + "f -4 -3 -2 -1\n"));
    expect_square(m);
}

TEST(ObjLoader, SplitsVerticesWithDifferentNormals) {
    const auto m =
        load_obj(write_temp_file("a.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 -1\nvn 0 -1 0\n"
                                 "f 1//1 3//1 2//1\nf 1//2 2//2 4//2\n"));
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.positions.size(), 6u);  // vertex 1 and 2 appear with two normals each
    EXPECT_EQ(m.normals[m.triangles[1][0]], Vec3(0, -1, 0));
}

TEST(ObjLoader, MixedNormalsGiveFacesWithoutThemTheirFaceNormal) {
    const auto m = load_obj(write_temp_file(
        "a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 -1\nf 1//1 3//1 2//1\nf 1 2 4\n"));
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(m.normals[m.triangles[1][k]], Vec3(0, -1, 0));
}

TEST(ObjLoader, TriangleFaceIsKept) {
    const auto m = load_obj(write_temp_file("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    ASSERT_EQ(m.triangles.size(), 1u);
}

void expect_error_at(const std::string& text, const std::string& location,
                     const std::string& reason) {
    const std::string path = write_temp_file("bad.obj", text);
    const std::string message = input_error_of([&] { load_obj(path); });
    EXPECT_NE(message.find(path + ":" + location), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
}

TEST(ObjLoader, ErrorsNameFileAndLine) {
    expect_error_at("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "4:", "out of range");
    expect_error_at("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "4:", "out of range");
    expect_error_at("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "4:", "out of range");
    expect_error_at("v 0 0 0\nv 1 0 x\n", "2:", "invalid number");
    expect_error_at("v 0 0\n", "1:", "expected a number");
    expect_error_at("v 0 0 0\nv 1 0 0\n\nf 1 2\n", "4:", "at least 3");
    expect_error_at("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "4:", "normal index");
    expect_error_at("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n", "4:", "invalid vertex index");
    expect_error_at("vn 0 0 0\n", "1:", "zero length");
    expect_error_at("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/ 2 3\n", "4:", "empty normal index");
}

TEST(ObjLoader, EmptyMeshIsAnError) {
    const std::string path = write_temp_file("empty.obj", "# nothing\nv 0 0 0\n");
    EXPECT_NE(input_error_of([&] { load_obj(path); }).find("no faces"), std::string::npos);
}

TEST(ObjLoader, MissingFileIsAnError) {
    EXPECT_NE(input_error_of([] { load_obj("/nonexistent/x.obj"); }).find("/nonexistent/x.obj"),
              std::string::npos);
}

}  // namespace
}  // namespace kasumi
