// Shadow volumes against ray-traced shadows: every pixel's lit/unlit state is the same on a
// scene of closed meshes, a box, an open plate, a two-sided panel and an open fold, with the eye
// outside and inside a volume.
#include "surface/shadows/shadow_volume.h"

#include "tests/surface/shadow_test_scene.h"

#include <gtest/gtest.h>

#include <map>

namespace kasumi {
namespace {

struct Comparison {
    int shaded = 0;       ///< pixels on a surface facing the light
    int shadowed = 0;     ///< of those, in shadow by ray tracing
    int differ = 0;       ///< lit/unlit state differs between ray tracing and volumes
    int pass_differ = 0;  ///< depth-pass count (no eye correction) disagrees with depth-fail
};

/// Renders lit/unlit states of a w × h pinhole image from `eye` looking at `target`.
Comparison compare_image(const std::vector<Shape>& shapes, const LightCentre& light,
                         const Vec3& eye, const Vec3& target, int w, int h) {
    const SurfaceScene scene(shapes);
    const ShadowVolumes volumes(shapes, light, scene.bounds());
    const PinholeView view = pinhole_view(eye, target, w, h);
    Comparison c;
    for_each_facing_pixel(scene, light, view, [&](int, int, const FacingHit& f) {
        ++c.shaded;
        const bool volume_shadow = volumes.in_shadow(f.origin, f.direction);
        c.shadowed += f.ray_shadow ? 1 : 0;
        c.differ += f.ray_shadow != volume_shadow ? 1 : 0;
        const int fail = volumes.depth_fail_count(f.origin, f.direction);
        EXPECT_GE(fail, 0);
        c.pass_differ += volumes.depth_pass_count(eye, f.origin) != fail ? 1 : 0;
    });
    return c;
}

// Every pixel agrees with ray tracing; the eye is outside every volume, so depth-pass counting
// from the eye gives the same counts.
TEST(ShadowVolumeTest, AgreesWithRayTracingOnEveryPixel) {
    const Comparison c = compare_image(mesh_scene(), point_centre(Vec3(0.4f, 4.2f, 0.9f)),
                                       Vec3(0.7f, 3.1f, 6.3f), Vec3(0.0f, 0.5f, 0.0f), 320, 200);
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
    const Comparison c =
        compare_image(shapes, point_centre(light), eye, Vec3(2.0f, 0.0f, 2.5f), 320, 200);
    EXPECT_GT(c.shaded, 20000);
    EXPECT_GT(c.shadowed, 500);
    EXPECT_EQ(c.differ, 0);
    EXPECT_GT(c.pass_differ, c.shaded / 2) << "depth-pass without eye correction must fail";
}

// Parallel light (the w = 0 extrusion): every pixel agrees with ray tracing for a high sun and a
// low one that stretches the shadows across the floor.
TEST(ShadowVolumeTest, ParallelLightAgreesWithRayTracingOnEveryPixel) {
    for (const Vec3& sun : {Vec3(0.3f, 1.0f, 0.2f), Vec3(-0.9f, 0.45f, 0.5f)}) {
        const Comparison c =
            compare_image(mesh_scene(), parallel_centre(sun), Vec3(0.7f, 3.1f, 6.3f),
                          Vec3(0.0f, 0.5f, 0.0f), 320, 200);
        EXPECT_GT(c.shaded, 30000);
        EXPECT_GT(c.shadowed, 500);
        EXPECT_EQ(c.differ, 0);
        EXPECT_EQ(c.pass_differ, 0);
    }
}

// Coincident faces of different shapes' volumes (a quad lying on two box tops whose caps share
// its plane, quads meeting along an edge, T-junctions) are each counted: every pixel agrees.
TEST(ShadowVolumeTest, CoincidentFacesOfDifferentShapesAgreeWithRayTracing) {
    for (const LightCentre& light :
         {point_centre(Vec3(0.4f, 4.2f, 0.9f)), parallel_centre(Vec3(-0.5f, 1.0f, 0.6f))}) {
        const Comparison c = compare_image(hard_case_scene(), light, Vec3(0.7f, 3.1f, 6.3f),
                                           Vec3(0.0f, 0.5f, 0.0f), 320, 200);
        EXPECT_GT(c.shaded, 30000);
        EXPECT_GT(c.shadowed, 500);
        EXPECT_EQ(c.differ, 0);
    }
}

// The eye in a parallel light's shadow of the box: depth-fail still agrees.
TEST(ShadowVolumeTest, ParallelLightEyeInsideVolume) {
    const Vec3 sun = glm::normalize(Vec3(0.3f, 1.0f, 0.2f));
    const Vec3 eye = Vec3(-0.15f, 1.1f, -0.95f) - 0.5f * sun;
    const Comparison c =
        compare_image(mesh_scene(), parallel_centre(sun), eye, Vec3(2.0f, 0.0f, 2.5f), 320, 200);
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
    const ShadowVolumeGeometry g = build_shadow_volumes(shapes, point_centre(light), bounds);
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
    const ShadowVolumes volumes(shapes, point_centre(light), bounds);
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
    const ShadowVolumes volumes(shapes, point_centre(Vec3(0.0f, 4.0f, 0.0f)), scene.bounds());
    EXPECT_TRUE(volumes.in_shadow(Vec3(0.0f, 1e-3f, 0.0f), Vec3(0, -1, 0)));
    EXPECT_FALSE(volumes.in_shadow(Vec3(2.0f, 1e-3f, 0.0f), Vec3(0, -1, 0)));
}

}  // namespace
}  // namespace kasumi
