#include "surface/shadows/shadow_volume.h"

#include "surface/shadows/sphere_shadow_rays.h"
#include "surface/shadows/welded_mesh.h"

#include <map>
#include <tuple>

namespace kasumi {

namespace {

using Edge = std::pair<uint32_t, uint32_t>;

void add_volumes(const WeldedMesh& mesh, const LightCentre& light, float far_distance,
                 ShadowVolumeGeometry& out) {
    const bool closed = is_closed(mesh);
    // Triangles turned to face the light, counter-clockwise seen from it, with the number of
    // times each occurs (a surface modelled on both sides gives the same cap twice).
    std::map<std::array<uint32_t, 3>, int> cap_count;
    const auto add_cap = [&cap_count](std::array<uint32_t, 3> t) {
        // Rotate the smallest index first: one key per oriented triangle.
        while (t[0] > t[1] || t[0] > t[2])
            t = {t[1], t[2], t[0]};
        ++cap_count[t];
    };
    for (const auto& t : mesh.triangles) {
        const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        const Vec3 to_light = light.at_infinity ? light.direction : light.position - a;
        const float facing = glm::dot(glm::cross(b - a, c - a), to_light);
        if (facing > 0.0f)
            add_cap(t);
        else if (facing < 0.0f && !closed)
            add_cap({t[0], t[2], t[1]});
        // facing == 0: edge-on to the light, bounds no volume.
    }
    // Silhouette: directed cap edges whose reverse is no cap edge. Where two caps share an edge
    // (traversed both ways), their volumes' side walls would coincide with opposite normals
    // and cancel in every count, so neither is built.
    std::map<Edge, int> edges;
    for (const auto& [t, n] : cap_count)
        for (int k = 0; k < 3; ++k)
            edges[{t[k], t[(k + 1) % 3]}] += n;
    // A point light pushes each vertex out along its ray from the light; a light at infinity
    // along the parallel rays (the w = 0 extrusion, stopped at the far cap).
    const auto extrude = [&](uint32_t i) {
        const Vec3& v = mesh.positions[i];
        if (light.at_infinity)
            return v - far_distance * light.direction;
        const Vec3 d = v - light.position;
        return light.position + d * (far_distance / glm::length(d));
    };
    for (const auto& [edge, n] : edges) {
        const auto reverse = edges.find({edge.second, edge.first});
        // Walls at a fold of an open mesh (two caps on the same side of one edge) coincide:
        // one wall, counted with the multiplicity.
        const int unmatched = n - (reverse == edges.end() ? 0 : reverse->second);
        if (unmatched > 0) {
            out.sides.push_back({mesh.positions[edge.first], extrude(edge.first),
                                 extrude(edge.second), mesh.positions[edge.second]});
            out.side_weights.push_back(unmatched);
            ++out.silhouette_edges;
        }
    }
    for (const auto& [t, n] : cap_count) {
        out.near_caps.push_back({mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]});
        out.far_caps.push_back({extrude(t[0]), extrude(t[2]), extrude(t[1])});
        out.cap_weights.push_back(n);
    }
}

}  // namespace

ShadowVolumeGeometry build_shadow_volumes(const std::vector<Shape>& shapes,
                                          const LightCentre& light, const Bounds3& scene_bounds) {
    const Vec3 center = 0.5f * (scene_bounds.min + scene_bounds.max);
    const float radius = 0.5f * glm::length(scene_bounds.extent());
    // Point light: from the light, beyond the far side of the bounding sphere. Parallel light:
    // from any vertex (inside the sphere) a diameter and a margin takes it out of the sphere.
    const float far_distance = light.at_infinity
                                   ? 2.0f * (2.0f * radius) + 1.0f
                                   : 2.0f * (glm::length(light.position - center) + radius) + 1.0f;
    ShadowVolumeGeometry out;
    for (const Shape& shape : shapes)
        if (const auto mesh = welded_mesh(shape))
            add_volumes(*mesh, light, far_distance, out);
    return out;
}

namespace {

/// The faces of `g` as one Embree scene (null when there are none) and their multiplicities.
std::unique_ptr<SurfaceScene> face_scene(const ShadowVolumeGeometry& g, std::vector<int>& weights) {
    MeshShape faces;
    faces.file = "(shadow volumes)";
    TriangleMesh& mesh = faces.mesh;
    const auto add = [&mesh](const Vec3& a, const Vec3& b, const Vec3& c) {
        const auto base = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, b, c});
        mesh.triangles.push_back({base, base + 1, base + 2});
    };
    for (size_t i = 0; i < g.near_caps.size(); ++i) {
        const auto& t = g.near_caps[i];
        add(t[0], t[1], t[2]);
        weights.push_back(g.cap_weights[i]);
    }
    for (size_t i = 0; i < g.far_caps.size(); ++i) {
        const auto& t = g.far_caps[i];
        add(t[0], t[1], t[2]);
        weights.push_back(g.cap_weights[i]);
    }
    for (size_t i = 0; i < g.sides.size(); ++i) {
        const auto& q = g.sides[i];
        add(q[0], q[1], q[2]);
        add(q[0], q[2], q[3]);
        weights.insert(weights.end(), 2, g.side_weights[i]);
    }
    if (mesh.triangles.empty())
        return nullptr;
    Shape shape;
    shape.name = "shadow volumes";
    shape.geometry = std::move(faces);
    return std::make_unique<SurfaceScene>(std::vector<Shape>{std::move(shape)});
}

template <typename T>
void append(std::vector<T>& to, const std::vector<T>& from) {
    to.insert(to.end(), from.begin(), from.end());
}

}  // namespace

ShadowVolumes::ShadowVolumes(const std::vector<Shape>& shapes, const LightCentre& light,
                             const Bounds3& scene_bounds)
    : m_light(light) {
    // One face scene per shape: faces of different shapes' volumes may coincide (a quad lying
    // on a box's top, quads meeting along an edge) and each must be counted, whereas the
    // counting loop below counts the faces of one scene met at one t once.
    for (const Shape& shape : shapes) {
        const ShadowVolumeGeometry g = build_shadow_volumes({shape}, light, scene_bounds);
        ShapeFaces faces;
        faces.scene = face_scene(g, faces.weights);
        faces.max_crossings = 3 * g.near_caps.size() + 2 * g.sides.size() + 8;
        if (faces.scene != nullptr)
            m_faces.push_back(std::move(faces));
        append(m_geometry.near_caps, g.near_caps);
        append(m_geometry.far_caps, g.far_caps);
        append(m_geometry.cap_weights, g.cap_weights);
        append(m_geometry.sides, g.sides);
        append(m_geometry.side_weights, g.side_weights);
        m_geometry.silhouette_edges += g.silhouette_edges;
    }
    m_spheres = sphere_scene(shapes);
}

ShadowVolumes::~ShadowVolumes() = default;

int ShadowVolumes::count_crossings(const Ray& ray, float sign_of_exit) const {
    int count = 0;
    for (const ShapeFaces& faces : m_faces) {
        Ray r = ray;
        // Each face is crossed at most once; the bound only guards against a stuck loop.
        for (size_t k = 0; k < faces.max_crossings; ++k) {
            const auto hit = faces.scene->intersect(r);
            if (!hit)
                break;
            // Faces sharing an edge hit at the same t are counted once: the next search starts
            // strictly after t.
            const bool exits = glm::dot(hit->geometric_normal, r.direction) > 0.0f;
            const int weight = faces.weights[hit->primitive];
            count += (exits ? 1 : -1) * static_cast<int>(sign_of_exit) * weight;
            r.t_min = hit->t;
        }
    }
    return count;
}

int ShadowVolumes::depth_fail_count(const Vec3& p, const Vec3& direction) const {
    return count_crossings(Ray{p, direction, 0.0f, kInfinity}, +1.0f);
}

int ShadowVolumes::depth_pass_count(const Vec3& eye, const Vec3& p) const {
    const Vec3 d = p - eye;
    const float distance = glm::length(d);
    if (!(distance > 0.0f))
        return 0;
    return count_crossings(Ray{eye, d / distance, 0.0f, distance}, -1.0f);
}

bool ShadowVolumes::in_shadow(const Vec3& p, const Vec3& view_direction) const {
    if (depth_fail_count(p, view_direction) > 0)
        return true;
    return m_spheres != nullptr && shadow_ray_blocked(*m_spheres, p, m_light);
}

ShadowVolumeSet::ShadowVolumeSet(const std::vector<Shape>& shapes, const std::vector<Light>& lights,
                                 const Bounds3& scene_bounds) {
    for (const Light& light : lights) {
        if (light.shadows != ShadowMode::ShadowVolume) {
            m_volumes.push_back(nullptr);
            continue;
        }
        m_volumes.push_back(
            std::make_unique<ShadowVolumes>(shapes, light_centre(light), scene_bounds));
    }
}

}  // namespace kasumi
