// Shadow volumes against ray-traced shadows: every pixel's lit/unlit state is the same on a
// scene of closed meshes, a box, an open plate, a two-sided panel and an open fold, with the eye
// outside and inside a volume.
#include "surface/shadow_volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace kasumi {
namespace {

Shape mesh_shape(TriangleMesh mesh) {
    Shape s;
    MeshShape m;
    m.file = "(test)";
    m.mesh = std::move(mesh);
    s.geometry = std::move(m);
    return s;
}

/// An icosahedron of circumradius r around c, turned by `angle` about a skew axis, wound
/// counter-clockwise seen from outside (closed).
TriangleMesh icosahedron(const Vec3& c, float r, float angle) {
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
TriangleMesh l_prism(const Vec3& o, float depth) {
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

std::vector<Shape> mesh_scene() {
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

struct Comparison {
    int shaded = 0;       ///< pixels on a surface facing the light
    int shadowed = 0;     ///< of those, in shadow by ray tracing
    int differ = 0;       ///< lit/unlit state differs between ray tracing and volumes
    int pass_differ = 0;  ///< depth-pass count (no eye correction) disagrees with depth-fail
};

/// Renders lit/unlit states of a w × h pinhole image from `eye` looking at `target`.
Comparison compare_image(const std::vector<Shape>& shapes, const Vec3& light, const Vec3& eye,
                         const Vec3& target, int w, int h) {
    const SurfaceScene scene(shapes);
    const ShadowVolumes volumes(shapes, light, scene.bounds());
    const Vec3 forward = glm::normalize(target - eye);
    const Vec3 right = glm::normalize(glm::cross(forward, Vec3(0, 1, 0)));
    const Vec3 up = glm::cross(right, forward);
    Comparison c;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float sx = (2.0f * (x + 0.5f) / w - 1.0f) * 0.8f;
            const float sy = (1.0f - 2.0f * (y + 0.5f) / h) * 0.8f * h / w;
            const Vec3 dir = glm::normalize(forward + sx * right + sy * up);
            const auto hit = scene.intersect(Ray{eye, dir, 0.0f, kInfinity});
            if (!hit)
                continue;
            Vec3 n = hit->geometric_normal;
            if (glm::dot(n, dir) > 0.0f)
                n = -n;
            const Vec3 to_light = light - hit->position;
            const float distance = glm::length(to_light);
            const Vec3 wi = to_light / distance;
            if (glm::dot(n, wi) <= 0.0f)
                continue;
            ++c.shaded;
            const Vec3 origin = offset_ray_origin(*hit, wi);
            const bool ray_shadow =
                scene.occluded(Ray{origin, wi, 0.0f, glm::length(light - origin) * (1 - 1e-5f)});
            const bool volume_shadow = volumes.in_shadow(origin, dir);
            c.shadowed += ray_shadow ? 1 : 0;
            c.differ += ray_shadow != volume_shadow ? 1 : 0;
            const int fail = volumes.depth_fail_count(origin, dir);
            EXPECT_GE(fail, 0);
            c.pass_differ += volumes.depth_pass_count(eye, origin) != fail ? 1 : 0;
        }
    }
    return c;
}

// Every pixel agrees with ray tracing; the eye is outside every volume, so depth-pass counting
// from the eye gives the same counts.
TEST(ShadowVolumeTest, AgreesWithRayTracingOnEveryPixel) {
    const Comparison c = compare_image(mesh_scene(), Vec3(0.4f, 4.2f, 0.9f), Vec3(0.7f, 3.1f, 6.3f),
                                       Vec3(0.0f, 0.5f, 0.0f), 320, 200);
    EXPECT_GT(c.shaded, 30000);
    EXPECT_GT(c.shadowed, 1000);
    EXPECT_EQ(c.differ, 0);
    EXPECT_EQ(c.pass_differ, 0);
}

// The eye sits in the shadow of the box (inside its volume): depth-pass counts from the eye
// are off by one there, depth-fail counts are not and still agree with ray tracing.
TEST(ShadowVolumeTest, EyeInsideVolumeHandledByDepthFail) {
    const std::vector<Shape> shapes = mesh_scene();
    const Vec3 light(0.4f, 4.2f, 0.9f);
    // Below the box's centre on the line from the light: inside its shadow volume.
    const Vec3 box_center(-0.15f, 1.1f, -0.95f);
    const Vec3 eye = light + 1.2f * (box_center - light);
    {
        const SurfaceScene scene(shapes);
        const Vec3 d = glm::normalize(light - eye);
        ASSERT_TRUE(scene.occluded(Ray{eye, d, 0.0f, glm::length(light - eye)}));
    }
    const Comparison c = compare_image(shapes, light, eye, Vec3(2.0f, 0.0f, 2.5f), 320, 200);
    EXPECT_GT(c.shaded, 20000);
    EXPECT_GT(c.shadowed, 500);
    EXPECT_EQ(c.differ, 0);
    EXPECT_GT(c.pass_differ, c.shaded / 2) << "depth-pass without eye correction must fail";
}

// Silhouette edges of a closed convex mesh seen from a point form one loop: as many edges as
// side quads, and the light-facing triangles are the near caps.
TEST(ShadowVolumeTest, ConvexMeshHasOneSilhouetteLoop) {
    const std::vector<Shape> shapes = {mesh_shape(icosahedron(Vec3(0.0f), 1.0f, 0.3f))};
    Bounds3 bounds;
    bounds.extend(Vec3(-1.0f));
    bounds.extend(Vec3(1.0f));
    const Vec3 light(0.2f, 5.0f, 0.3f);
    const ShadowVolumeGeometry g = build_shadow_volumes(shapes, light, bounds);
    // Every vertex of the loop has exactly one outgoing and one incoming silhouette edge.
    std::map<std::tuple<float, float, float>, int> degree;
    for (const auto& q : g.sides) {
        ++degree[{q[0].x, q[0].y, q[0].z}];
        --degree[{q[3].x, q[3].y, q[3].z}];
    }
    for (const auto& [v, d] : degree)
        EXPECT_EQ(d, 0);
    EXPECT_GE(g.sides.size(), 3u);
    EXPECT_LT(g.near_caps.size(), 20u);
    EXPECT_GT(g.near_caps.size(), 0u);
    EXPECT_EQ(g.far_caps.size(), g.near_caps.size());
    // A point straight behind the mesh is in exactly one volume; one beside it in none.
    const ShadowVolumes volumes(shapes, light, bounds);
    EXPECT_EQ(volumes.depth_fail_count(Vec3(0.2f, -3.0f, 0.3f), Vec3(0, -1, 0)), 1);
    EXPECT_EQ(volumes.depth_fail_count(Vec3(3.0f, -3.0f, 0.3f), Vec3(0, -1, 0)), 0);
}

// Spheres are tested with shadow rays (the documented fallback): a ball shadows the floor.
TEST(ShadowVolumeTest, SpheresFallBackToShadowRays) {
    Shape ball;
    ball.geometry = SphereShape{Vec3(0.0f, 1.0f, 0.0f), 0.5f};
    Shape floor;
    floor.geometry = QuadShape{{Vec3(-5, 0, 5), Vec3(5, 0, 5), Vec3(5, 0, -5), Vec3(-5, 0, -5)}};
    const std::vector<Shape> shapes = {floor, ball};
    const SurfaceScene scene(shapes);
    const ShadowVolumes volumes(shapes, Vec3(0.0f, 4.0f, 0.0f), scene.bounds());
    EXPECT_TRUE(volumes.in_shadow(Vec3(0.0f, 1e-3f, 0.0f), Vec3(0, -1, 0)));
    EXPECT_FALSE(volumes.in_shadow(Vec3(2.0f, 1e-3f, 0.0f), Vec3(0, -1, 0)));
}

}  // namespace
}  // namespace kasumi
