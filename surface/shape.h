#pragma once
/// Shapes a scene may contain, as plain values (world space, metres). The Embree scene turns
/// them into geometry; nothing here depends on Embree.
#include "core/json_node.h"
#include "core/math.h"
#include "surface/shading.h"

#include <array>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace kasumi {

struct SphereShape {
    Vec3 center{0.0f};
    float radius = 1.0f;  ///< > 0
};

/// A planar quadrilateral; its front side is the one its vertices wind counter-clockwise toward.
struct QuadShape {
    std::array<Vec3, 4> vertices;
};

struct BoxShape {
    Vec3 min{-0.5f};
    Vec3 max{0.5f};
};

/// A triangle mesh in world space. Normals are per vertex when the file gives them (else empty).
struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<std::array<uint32_t, 3>> triangles;
};

struct MeshShape {
    std::string file;  ///< resolved path of the OBJ file
    TriangleMesh mesh;
};

struct Shape {
    std::string name;
    std::variant<SphereShape, QuadShape, BoxShape, MeshShape> geometry;
    uint32_t material = 0;  ///< index into the scene's material list
    /// Empty: the shape's default, shading_of(). Spheres are always Phong (exact normals).
    std::optional<Shading> shading;
};

/// The shading a shape uses: its `shading` if set, else Phong for spheres and for meshes with
/// vertex normals, flat otherwise. Quads and boxes use the face normal at every vertex (Phong
/// then equals flat; Gouraud differs under point lights); meshes use the file's vertex normals
/// or, when it has none, angle-weighted ones (surface/shading.h).
Shading shading_of(const Shape& shape);

/// Parses one entry of `shapes`; `materials` maps names to indices, `base_dir` resolves files
/// (meshes are loaded here, so load errors name the scene file and JSON path). Keys:
///   {"type": "sphere", "center": [x, y, z], "radius": > 0}
///   {"type": "quad", "vertices": [4 points]}: planar to 1e-4 of its size, convex, non-degenerate
///   {"type": "box", "min": [x, y, z], "max": [x, y, z]}: max > min on every axis
///   {"type": "mesh", "file": "x.obj", "translate": [0, 0, 0], "scale": 1 (> 0)}: positions
///       become scale * p + translate
/// and on every shape "material": a name in `materials` (required), "name" (default: the
/// shape's JSON pointer, e.g. "/shapes/2"), "shading": "flat" | "gouraud" | "phong" (default
/// as Shape::shading says; spheres accept only "phong"). Unknown keys and bad values throw
/// input errors.
Shape parse_shape(const JsonNode& node, const std::map<std::string, uint32_t>& materials,
                  const std::string& base_dir);

/// Reads a Wavefront OBJ file (v, vn, f with polygons fan-triangulated; other statements
/// ignored). Throws an input error naming file and line.
TriangleMesh load_obj(const std::string& path);

}  // namespace kasumi
