#include "core/error.h"
#include "surface/shape.h"

#include <cmath>
#include <filesystem>
#include <string>

namespace kasumi {

namespace {

/// Relative tolerances for quads, as fractions of the quad's longest diagonal. A quad whose
/// vertices lie farther than this from their best-fit plane is not planar; a corner whose
/// sine is below kMinCornerSine is degenerate (collinear edges) or, if negative, reflex.
constexpr double kPlanarityTolerance = 1e-4;
constexpr double kMinCornerSine = 1e-6;
/// Float rounding of JSON coordinates: 2^-24 relative per coordinate; allow a few ulps.
constexpr double kCoordinateRounding = 4.0 * 5.96e-8;

std::string known_names(const std::map<std::string, uint32_t>& materials) {
    std::string names;
    for (const auto& entry : materials)
        names += (names.empty() ? "" : ", ") + entry.first;
    return names.empty() ? "(none defined)" : names;
}

SphereShape parse_sphere(JsonObjectReader& reader) {
    SphereShape s;
    s.center = reader.required("center").as_point();
    s.radius = reader.required("radius").positive_length();
    return s;
}

QuadShape parse_quad(JsonObjectReader& reader) {
    const JsonNode node = reader.required("vertices");
    if (!node.is_array() || node.size() != 4)
        node.fail("expected an array of 4 points [x, y, z]");
    QuadShape q;
    DVec3 v[4];
    double max_coordinate = 0.0;
    for (size_t i = 0; i < 4; ++i) {
        q.vertices[i] = node.child(i).as_point();
        v[i] = DVec3(q.vertices[i]);
        for (int axis = 0; axis < 3; ++axis)
            max_coordinate = std::max(max_coordinate, std::abs(v[i][axis]));
    }
    // Twice the area vector of a planar quad is the cross product of its diagonals (Newell);
    // it points toward the side the vertices wind counter-clockwise toward.
    const DVec3 area2 = glm::cross(v[2] - v[0], v[3] - v[1]);
    const double size = std::max(glm::length(v[2] - v[0]), glm::length(v[3] - v[1]));
    if (!(glm::length(area2) > kMinCornerSine * size * size))
        node.fail("quad is degenerate (zero area, or self-intersecting)");
    const DVec3 n = glm::normalize(area2);
    const DVec3 centroid = 0.25 * (v[0] + v[1] + v[2] + v[3]);
    const double tolerance = kPlanarityTolerance * size + kCoordinateRounding * max_coordinate;
    for (size_t i = 0; i < 4; ++i) {
        if (std::abs(glm::dot(v[i] - centroid, n)) > tolerance)
            node.fail("quad is not planar (vertex " + std::to_string(i) +
                      " is off the plane of the others by more than 1e-4 of the quad's size)");
    }
    for (size_t i = 0; i < 4; ++i) {
        const DVec3 a = v[i] - v[(i + 3) % 4];
        const DVec3 b = v[(i + 1) % 4] - v[i];
        const double sine = glm::dot(glm::cross(a, b), n) / (glm::length(a) * glm::length(b));
        if (!(sine > kMinCornerSine))
            node.fail("quad is degenerate or not convex at vertex " + std::to_string(i));
    }
    return q;
}

BoxShape parse_box(JsonObjectReader& reader) {
    BoxShape b;
    b.min = reader.required("min").as_point();
    const JsonNode max_node = reader.required("max");
    b.max = max_node.as_point();
    if (!(b.min.x < b.max.x && b.min.y < b.max.y && b.min.z < b.max.z))
        max_node.fail("must exceed \"min\" on every axis");
    return b;
}

MeshShape parse_mesh(JsonObjectReader& reader, const std::string& base_dir) {
    const JsonNode file = reader.required("file");
    std::filesystem::path path(file.as_string());
    if (path.is_relative() && !base_dir.empty())
        path = std::filesystem::path(base_dir) / path;
    MeshShape m;
    m.file = path.lexically_normal().string();
    Vec3 translate(0.0f);
    float scale = 1.0f;
    if (const auto t = reader.optional("translate"))
        translate = t->as_point();
    if (const auto s = reader.optional("scale"))
        scale = s->positive();
    try {
        m.mesh = load_obj(m.file);
    } catch (const Error& e) {
        file.fail(e.what());
    }
    // A uniform positive scale and a translation leave unit normals unchanged.
    for (Vec3& p : m.mesh.positions) {
        p = scale * p + translate;
        if (!(std::abs(p.x) <= kMaxCoordinateM && std::abs(p.y) <= kMaxCoordinateM &&
              std::abs(p.z) <= kMaxCoordinateM))
            file.fail(
                "a scaled and translated vertex lies beyond +-1e12 m (single precision "
                "breaks down beyond)");
    }
    return m;
}

}  // namespace

Shading shading_of(const Shape& shape) {
    if (std::holds_alternative<SphereShape>(shape.geometry))
        return Shading::Phong;
    if (shape.shading)
        return *shape.shading;
    if (const auto* mesh = std::get_if<MeshShape>(&shape.geometry))
        return mesh->mesh.normals.empty() ? Shading::Flat : Shading::Phong;
    return Shading::Flat;
}

Shape parse_shape(const JsonNode& node, const std::map<std::string, uint32_t>& materials,
                  const std::string& base_dir) {
    JsonObjectReader reader(node);
    const JsonNode type = reader.required("type");
    const std::string kind = type.as_string();
    Shape shape;
    if (kind == "sphere") {
        shape.geometry = parse_sphere(reader);
    } else if (kind == "quad") {
        shape.geometry = parse_quad(reader);
    } else if (kind == "box") {
        shape.geometry = parse_box(reader);
    } else if (kind == "mesh") {
        shape.geometry = parse_mesh(reader, base_dir);
    } else {
        type.fail("unknown shape type (known types: box, mesh, quad, sphere)");
    }
    if (const auto shading = reader.optional("shading")) {
        const std::string mode = shading->as_string();
        if (mode == "flat")
            shape.shading = Shading::Flat;
        else if (mode == "gouraud")
            shape.shading = Shading::Gouraud;
        else if (mode == "phong")
            shape.shading = Shading::Phong;
        else
            shading->fail("must be \"flat\", \"gouraud\" or \"phong\"");
        if (kind == "sphere" && *shape.shading != Shading::Phong)
            shading->fail(
                "spheres are shaded with their exact normal (\"phong\"); use a "
                "tessellated mesh for flat or Gouraud shading");
    }
    const JsonNode material = reader.required("material");
    const auto found = materials.find(material.as_string());
    if (found == materials.end())
        material.fail("unknown material (known materials: " + known_names(materials) + ")");
    shape.material = found->second;
    if (const auto name = reader.optional("name"))
        shape.name = name->as_string();
    else
        shape.name = node.pointer();
    reader.finish();
    return shape;
}

}  // namespace kasumi
