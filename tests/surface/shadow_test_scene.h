#pragma once
// Shared by the polygon shadow tests (shadow volumes, object-space shadows): a scene of a
// rotated icosahedron, a non-convex L-shaped prism standing on the floor, a box, an open tilted
// plate, a panel modelled on both sides and an open fold.
#include "surface/shadows/light_centre.h"
#include "surface/shape.h"
#include "surface/surface_scene.h"
#include "tests/surface/test_shapes.h"

#include <cmath>
#include <optional>

namespace kasumi {

inline Shape mesh_shape(TriangleMesh mesh) {
    Shape s;
    MeshShape m;
    m.file = "(test)";
    m.mesh = std::move(mesh);
    s.geometry = std::move(m);
    return s;
}

/// An icosahedron of circumradius r around c, turned by `angle` about a skew axis, wound
/// counter-clockwise seen from outside (closed).
inline TriangleMesh icosahedron(const Vec3& c, float r, float angle) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    const std::vector<std::array<uint32_t, 3>> f = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    const Vec3 axis = glm::normalize(Vec3(0.3f, 0.8f, 0.5f));
    TriangleMesh m;
    for (Vec3 p : v) {
        p = glm::normalize(p);
        // Rodrigues' rotation.
        p = p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
            axis * glm::dot(axis, p) * (1.0f - std::cos(angle));
        m.positions.push_back(c + r * p);
    }
    m.triangles = f;
    return m;
}

/// A closed, non-convex mesh: an L-shaped prism (extruded L outline) along z.
inline TriangleMesh l_prism(const Vec3& o, float depth) {
    const std::vector<Vec2> outline = {{0, 0},       {0.9f, 0},    {0.9f, 0.3f},
                                       {0.3f, 0.3f}, {0.3f, 0.8f}, {0, 0.8f}};
    TriangleMesh m;
    const auto n = static_cast<uint32_t>(outline.size());
    for (const Vec2& p : outline)
        m.positions.push_back(o + Vec3(p.x, p.y, 0.0f));
    for (const Vec2& p : outline)
        m.positions.push_back(o + Vec3(p.x, p.y, -depth));
    // Front cap (z = o.z, normal +z): the outline is counter-clockwise seen from +z. Fan from
    // vertex 3, the reflex corner, splits it into convex-safe triangles.
    const std::vector<std::array<uint32_t, 3>> cap = {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}};
    for (const auto& t : cap) {
        m.triangles.push_back({t[0], t[1], t[2]});
        m.triangles.push_back({t[0] + n, t[2] + n, t[1] + n});
    }
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t j = (i + 1) % n;
        m.triangles.push_back({i, i + n, j + n});
        m.triangles.push_back({i, j + n, j});
    }
    return m;
}

inline std::vector<Shape> mesh_scene() {
    std::vector<Shape> shapes;
    Shape floor;
    floor.geometry = QuadShape{{Vec3(-5, 0, 5), Vec3(5, 0, 5), Vec3(5, 0, -5), Vec3(-5, 0, -5)}};
    shapes.push_back(floor);
    shapes.push_back(mesh_shape(icosahedron(Vec3(0.9f, 1.1f, 0.4f), 0.5f, 0.7f)));
    shapes.push_back(mesh_shape(l_prism(Vec3(-1.6f, 0.0f, 0.7f), 0.6f)));
    Shape box;
    box.geometry = BoxShape{Vec3(-0.5f, 0.9f, -1.3f), Vec3(0.2f, 1.3f, -0.6f)};
    shapes.push_back(box);
    Shape plate;  // open: a tilted plate
    plate.geometry = QuadShape{{Vec3(1.2f, 1.8f, -1.4f), Vec3(2.0f, 2.0f, -1.4f),
                                Vec3(2.0f, 2.0f, -0.6f), Vec3(1.2f, 1.8f, -0.6f)}};
    shapes.push_back(plate);
    // A panel modelled on both sides (each triangle twice, opposite windings): open, with
    // coincident caps and walls that must count twice.
    TriangleMesh panel;
    panel.positions = {Vec3(-2.4f, 1.2f, -1.6f), Vec3(-1.8f, 1.3f, -1.6f), Vec3(-1.8f, 1.4f, -2.2f),
                       Vec3(-2.4f, 1.3f, -2.2f)};
    panel.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 3, 2}};
    shapes.push_back(mesh_shape(panel));
    // An open fold: two triangles on one edge, one facing the light and one turned away.
    TriangleMesh fold;
    fold.positions = {Vec3(2.2f, 1.0f, 0.6f), Vec3(2.2f, 1.0f, 1.4f), Vec3(2.8f, 1.6f, 1.0f),
                      Vec3(2.9f, 1.2f, 1.0f)};
    fold.triangles = {{0, 1, 2}, {1, 0, 3}};
    shapes.push_back(mesh_shape(fold));
    return shapes;
}

/// The hard cases around the shared scene's light at (0.4, 4.2, 0.9).
inline std::vector<Shape> hard_case_scene() {
    std::vector<Shape> shapes = mesh_scene();
    // Touching the floor: a box standing on it.
    shapes.push_back(box(Vec3(1.2f, 0.0f, 1.6f), Vec3(1.6f, 0.5f, 2.0f)));
    // Coplanar faces: a second box whose top is level with the first's and touches it, and a
    // quad lying on both tops.
    shapes.push_back(box(Vec3(1.6f, 0.0f, 1.6f), Vec3(2.0f, 0.5f, 2.0f)));
    shapes.push_back(quad(Vec3(1.4f, 0.5f, 1.9f), Vec3(1.8f, 0.5f, 1.9f), Vec3(1.8f, 0.5f, 1.7f),
                          Vec3(1.4f, 0.5f, 1.7f)));
    // T-junctions: a platform of one quad beside two half-width quads (the middle vertex of
    // their shared side lies on the long quad's edge).
    shapes.push_back(quad(Vec3(-2.0f, 0.3f, 2.6f), Vec3(-1.0f, 0.3f, 2.6f), Vec3(-1.0f, 0.3f, 2.0f),
                          Vec3(-2.0f, 0.3f, 2.0f)));
    shapes.push_back(quad(Vec3(-2.0f, 0.3f, 2.0f), Vec3(-1.5f, 0.3f, 2.0f), Vec3(-1.5f, 0.3f, 1.4f),
                          Vec3(-2.0f, 0.3f, 1.4f)));
    shapes.push_back(quad(Vec3(-1.5f, 0.3f, 2.0f), Vec3(-1.0f, 0.3f, 2.0f), Vec3(-1.0f, 0.3f, 1.4f),
                          Vec3(-1.5f, 0.3f, 1.4f)));
    // Slivers: a needle triangle and a sheet 1 mm thin over the platform.
    TriangleMesh needle;
    needle.positions = {Vec3(-2.2f, 1.0f, 2.0f), Vec3(-0.8f, 1.1f, 1.8f),
                        Vec3(-0.8f, 1.1f, 1.802f)};
    needle.triangles = {{0, 1, 2}};
    shapes.push_back(mesh_shape(needle));
    shapes.push_back(box(Vec3(-1.9f, 0.8f, 1.5f), Vec3(-1.1f, 0.801f, 1.6f)));
    // The light in a face's plane: a vertical panel through x = 0.4.
    shapes.push_back(quad(Vec3(0.4f, 0.0f, -2.5f), Vec3(0.4f, 0.0f, -3.5f), Vec3(0.4f, 1.0f, -3.5f),
                          Vec3(0.4f, 1.0f, -2.5f)));
    // A receiver reaching behind and above the light: a tall back wall, with a plate nearly
    // level with the light casting onto its top.
    shapes.push_back(quad(Vec3(-4.0f, 0.0f, -3.0f), Vec3(4.0f, 0.0f, -3.0f),
                          Vec3(4.0f, 6.0f, -3.0f), Vec3(-4.0f, 6.0f, -3.0f)));
    shapes.push_back(quad(Vec3(-0.4f, 4.1f, -0.6f), Vec3(0.2f, 4.1f, -0.6f),
                          Vec3(0.2f, 4.15f, -1.2f), Vec3(-0.4f, 4.15f, -1.2f)));
    return shapes;
}

/// A w × h pinhole image from `eye` toward `target`, half_width (0.8 unless set: kasumi's
/// Camera has aspect · tan(fov/2)) wide per unit distance on each side.
struct PinholeView {
    Vec3 eye, forward, right, up;
    int w = 0, h = 0;
    float half_width = 0.8f;
    /// Unit direction through the image point (x, y), in pixels from the top left corner.
    Vec3 direction(float x, float y) const {
        const float sx = (2.0f * x / w - 1.0f) * half_width;
        const float sy = (1.0f - 2.0f * y / h) * half_width * h / w;
        return glm::normalize(forward + sx * right + sy * up);
    }
};

inline PinholeView pinhole_view(const Vec3& eye, const Vec3& target, int w, int h) {
    PinholeView v;
    v.eye = eye;
    v.forward = glm::normalize(target - eye);
    v.right = glm::normalize(glm::cross(v.forward, Vec3(0, 1, 0)));
    v.up = glm::cross(v.right, v.forward);
    v.w = w;
    v.h = h;
    return v;
}

/// What the camera ray through image point (x, y) sees when it is a surface facing the light:
/// the hit, the ray's direction, the hit offset toward the light, and whether a shadow ray from
/// there toward the light is blocked (ray-traced shadows, the reference of the polygon methods).
struct FacingHit {
    SurfaceHit hit;
    Vec3 direction{0.0f};
    Vec3 origin{0.0f};
    bool ray_shadow = false;
};

inline std::optional<FacingHit> facing_hit(const SurfaceScene& scene, const LightCentre& light,
                                           const PinholeView& view, float x, float y) {
    const Vec3 dir = view.direction(x, y);
    const auto hit = scene.intersect(Ray{view.eye, dir, 0.0f, kInfinity});
    if (!hit)
        return std::nullopt;
    Vec3 n = hit->geometric_normal;
    if (glm::dot(n, dir) > 0.0f)
        n = -n;
    const Vec3 wi = toward_light(light, hit->position);
    if (glm::dot(n, wi) <= 0.0f)
        return std::nullopt;
    const Vec3 origin = offset_ray_origin(*hit, wi);
    const float reach =
        light.at_infinity ? kInfinity : glm::length(light.position - origin) * (1 - 1e-5f);
    return FacingHit{*hit, dir, origin, scene.occluded(Ray{origin, wi, 0.0f, reach})};
}

/// Calls visit(x, y, facing) for every pixel of `view` whose centre sees a surface facing the
/// light, row by row.
template <class Visit>
void for_each_facing_pixel(const SurfaceScene& scene, const LightCentre& light,
                           const PinholeView& view, Visit&& visit) {
    for (int y = 0; y < view.h; ++y)
        for (int x = 0; x < view.w; ++x)
            if (const auto f = facing_hit(scene, light, view, x + 0.5f, y + 0.5f))
                visit(x, y, *f);
}

/// By ray tracing, what image point (x, y) sees: −1 for nothing, or a surface turned away from
/// the light; else shape index × 2 + 1 if a shadow ray toward the light is blocked, + 0 if not.
inline int ray_shadow_state(const SurfaceScene& scene, const LightCentre& light,
                            const PinholeView& view, float x, float y) {
    const auto f = facing_hit(scene, light, view, x, y);
    return f ? int(f->hit.shape) * 2 + (f->ray_shadow ? 1 : 0) : -1;
}

}  // namespace kasumi
