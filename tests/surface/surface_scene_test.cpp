#include "surface/surface_scene.h"

#include "core/rng.h"
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

namespace kasumi {
namespace {

Shape make(std::variant<SphereShape, QuadShape, BoxShape, MeshShape> geometry,
           uint32_t material = 0) {
    Shape s;
    s.geometry = std::move(geometry);
    s.material = material;
    return s;
}

Ray ray_from(const Vec3& origin, const Vec3& toward) {
    Ray r;
    r.origin = origin;
    r.direction = glm::normalize(toward - origin);
    return r;
}

/// Float rays vs the exact sphere, at radii from 1 cm to 10 km and centres up to 10 km away.
/// The closed form, in double: with f = o - c, a = |d|², b = f·d and p = f - (b/a) d,
/// t = (-b - sqrt(a (r² - |p|²))) / a.
TEST(SurfaceScene, SphereDistanceAndNormalMatchClosedForm) {
    Pcg32 rng(7, 1);
    for (const float radius : {1e-2f, 1.0f, 1e2f, 1e4f}) {
        for (const float offset : {0.0f, 1e4f}) {
            const Vec3 center(offset, -0.5f * offset, 0.25f * offset);
            const SurfaceScene scene({make(SphereShape{center, radius})});
            for (int i = 0; i < 200; ++i) {
                // Aim at a random point of the disc facing the origin, from 3 radii away.
                const Vec3 w = sample_uniform_sphere(rng.next_vec2());
                const Vec3 origin = center + 3.0f * radius * w;
                const Frame frame(-w);
                const Vec3 disc = sample_uniform_sphere(rng.next_vec2());  // |xy| <= 1
                const Vec3 target =
                    center + 0.99f * radius * (disc.x * frame.tangent + disc.y * frame.bitangent);
                const Ray ray = ray_from(origin, target);
                const auto hit = scene.intersect(ray);
                ASSERT_TRUE(hit) << radius << " " << offset << " " << i;

                const DVec3 f = DVec3(ray.origin) - DVec3(center);
                const DVec3 d(ray.direction);  // unit only to float precision: keep a = |d|²
                const double a = glm::dot(d, d);
                const double b = glm::dot(f, d);
                const DVec3 perpendicular = f - (b / a) * d;
                const double t = (-b - std::sqrt(a * (double(radius) * radius -
                                                      glm::dot(perpendicular, perpendicular)))) /
                                 a;
                const DVec3 normal = (DVec3(ray.origin) + t * d - DVec3(center)) / double(radius);
                // t is rounded to float once: half an ulp, 2^-24 relative; allow 2 ulps.
                EXPECT_NEAR(hit->t, t, 2.0 * 0x1p-23 * t) << radius << " " << offset;
                EXPECT_NEAR(glm::distance(DVec3(hit->geometric_normal), normal), 0.0, 1e-6);
                EXPECT_EQ(hit->shading_normal, hit->geometric_normal);
                // The position is projected onto the sphere: within float rounding of it.
                const double scale = std::abs(offset) + radius;
                EXPECT_NEAR(glm::distance(DVec3(hit->position), DVec3(center)), radius,
                            4.0 * 0x1p-24 * scale);
            }
        }
    }
}

TEST(SurfaceScene, RayStartingInsideSphereHitsTheFarSideWithOutwardNormal) {
    const SurfaceScene scene({make(SphereShape{Vec3(1, 2, 3), 2.0f})});
    Ray ray;
    ray.origin = Vec3(1, 2, 3);
    ray.direction = Vec3(0, 1, 0);
    const auto hit = scene.intersect(ray);
    ASSERT_TRUE(hit);
    EXPECT_FLOAT_EQ(hit->t, 2.0f);
    EXPECT_EQ(hit->geometric_normal, Vec3(0, 1, 0));
}

TEST(SurfaceScene, BoxFacesHaveOutwardNormals) {
    const BoxShape box{Vec3(-1, 2, -3), Vec3(1, 3, 1)};
    const SurfaceScene scene({make(box, 4)});
    const Vec3 center = 0.5f * (box.min + box.max);
    for (int axis = 0; axis < 3; ++axis) {
        for (const float sign : {-1.0f, 1.0f}) {
            Vec3 outward(0.0f);
            outward[axis] = sign;
            const float face = sign > 0 ? box.max[axis] : box.min[axis];
            // From outside toward the face's centre...
            Ray ray;
            ray.origin = center;
            ray.origin[axis] = face + 5.0f * sign;
            ray.direction = -outward;
            auto hit = scene.intersect(ray);
            ASSERT_TRUE(hit);
            EXPECT_EQ(hit->geometric_normal, outward);
            EXPECT_EQ(hit->shading_normal, outward);
            EXPECT_EQ(hit->t, 5.0f);
            EXPECT_EQ(hit->position[axis], face);
            EXPECT_EQ(hit->material, 4u);
            EXPECT_EQ(hit->shape, 0u);
            // ...and from inside: the normal still points out of the box.
            ray.origin = center + Vec3(0.01f, 0.02f, 0.03f);
            ray.direction = outward;
            hit = scene.intersect(ray);
            ASSERT_TRUE(hit);
            EXPECT_EQ(hit->geometric_normal, outward);
            EXPECT_FLOAT_EQ(hit->t, std::abs(face - ray.origin[axis]));
        }
    }
}

TEST(SurfaceScene, QuadNormalPointsToTheCounterClockwiseSide) {
    // Counter-clockwise seen from +y: the front side is +y, whichever side the ray comes from.
    const QuadShape up{{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 0, 0)}};
    const QuadShape down{{up.vertices[3], up.vertices[2], up.vertices[1], up.vertices[0]}};
    for (const float from : {1.0f, -1.0f}) {
        Ray ray;
        ray.origin = Vec3(0.3f, from, 0.6f);
        ray.direction = Vec3(0.0f, -from, 0.0f);
        const auto hit_up = SurfaceScene({make(up)}).intersect(ray);
        const auto hit_down = SurfaceScene({make(down)}).intersect(ray);
        ASSERT_TRUE(hit_up && hit_down);
        EXPECT_EQ(hit_up->geometric_normal, Vec3(0, 1, 0));
        EXPECT_EQ(hit_down->geometric_normal, Vec3(0, -1, 0));
        EXPECT_EQ(hit_up->t, 1.0f);
        EXPECT_EQ(hit_up->position, Vec3(0.3f, 0.0f, 0.6f));
    }
}

TEST(SurfaceScene, QuadIsHitOnBothTrianglesOnly) {
    const QuadShape q{{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)}};
    const SurfaceScene scene({make(q)});
    Pcg32 rng(3, 3);
    for (int i = 0; i < 1000; ++i) {
        const Vec2 u = rng.next_vec2();
        Ray ray;
        ray.origin = Vec3(3.0f * u.x - 0.5f, 2.0f * u.y - 0.5f, 1.0f);
        ray.direction = Vec3(0, 0, -1);
        const bool inside =
            ray.origin.x > 0 && ray.origin.x < 2 && ray.origin.y > 0 && ray.origin.y < 1;
        const auto hit = scene.intersect(ray);
        EXPECT_EQ(hit.has_value(), inside) << ray.origin.x << " " << ray.origin.y;
        if (hit) {
            EXPECT_EQ(hit->geometric_normal, Vec3(0, 0, 1));
        }
    }
}

TEST(SurfaceScene, MeshNormalsAreInterpolatedWithBarycentrics) {
    MeshShape mesh;
    mesh.mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    mesh.mesh.normals = {Vec3(0, 0, 1), glm::normalize(Vec3(1, 0, 1)),
                         glm::normalize(Vec3(0, 1, 1))};
    mesh.mesh.triangles = {{0, 1, 2}};
    const SurfaceScene scene({make(mesh)});
    const float u = 0.25f, v = 0.5f;  // weights of vertices 1 and 2
    Ray ray;
    ray.origin = Vec3(u, v, -2.0f);
    ray.direction = Vec3(0, 0, 1);
    const auto hit = scene.intersect(ray);
    ASSERT_TRUE(hit);
    const Vec3 expected = glm::normalize((1 - u - v) * mesh.mesh.normals[0] +
                                         u * mesh.mesh.normals[1] + v * mesh.mesh.normals[2]);
    EXPECT_NEAR(glm::distance(hit->shading_normal, expected), 0.0f, 1e-6f);
    EXPECT_EQ(hit->geometric_normal, Vec3(0, 0, 1));  // from the counter-clockwise winding
    EXPECT_EQ(hit->t, 2.0f);
}

TEST(SurfaceScene, AuthoredNormalsDecideTheOutsideOfAMisWoundMesh) {
    MeshShape mesh;
    mesh.mesh.positions = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0)};  // clockwise from +z
    mesh.mesh.normals = {Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)};
    mesh.mesh.triangles = {{0, 1, 2}};
    const SurfaceScene scene({make(mesh)});
    Ray ray;
    ray.origin = Vec3(0.2f, 0.2f, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    const auto hit = scene.intersect(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->geometric_normal, Vec3(0, 0, 1));
    EXPECT_EQ(hit->shading_normal, Vec3(0, 0, 1));
}

TEST(SurfaceScene, MeshWithoutNormalsIsFlatAndFollowsWinding) {
    MeshShape mesh;
    mesh.mesh.positions = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0)};
    mesh.mesh.triangles = {{0, 1, 2}};  // clockwise seen from +z
    const SurfaceScene scene({make(mesh)});
    Ray ray;
    ray.origin = Vec3(0.2f, 0.2f, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    const auto hit = scene.intersect(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->geometric_normal, Vec3(0, 0, -1));
    EXPECT_EQ(hit->shading_normal, Vec3(0, 0, -1));
}

TEST(SurfaceScene, IntervalIsOpenAndRespected) {
    const SurfaceScene scene({make(BoxShape{Vec3(-1), Vec3(1)})});
    Ray ray;
    ray.origin = Vec3(0, 0, -3);
    ray.direction = Vec3(0, 0, 1);
    ray.t_max = 2.0f;  // the face is exactly at t = 2: outside (t_min, t_max)
    EXPECT_FALSE(scene.intersect(ray));
    EXPECT_FALSE(scene.occluded(ray));
    ray.t_max = std::nextafter(2.0f, 3.0f);
    EXPECT_TRUE(scene.intersect(ray));
    EXPECT_TRUE(scene.occluded(ray));
    ray.t_max = kInfinity;
    ray.t_min = 2.0f;  // skips the near face: the far one, seen from inside
    const auto hit = scene.intersect(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->t, 4.0f);
    EXPECT_EQ(hit->geometric_normal, Vec3(0, 0, 1));
    ray.t_min = 5.0f;
    EXPECT_FALSE(scene.intersect(ray));
    EXPECT_FALSE(scene.occluded(ray));
}

std::vector<Shape> mixed_scene() {
    MeshShape tetra;
    tetra.mesh.positions = {Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1)};
    tetra.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return {
        make(SphereShape{Vec3(0, 0, 0), 1.0f}, 0),
        make(BoxShape{Vec3(-3, -1, -1), Vec3(-2, 1, 1)}, 1),
        make(QuadShape{{Vec3(-5, -2, -5), Vec3(-5, -2, 5), Vec3(5, -2, 5), Vec3(5, -2, -5)}}, 2),
        make(tetra, 3)};
}

TEST(SurfaceScene, OccludedAgreesWithIntersect) {
    const SurfaceScene scene(mixed_scene());
    Pcg32 rng(11, 2);
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray;
        ray.origin = 6.0f * (Vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f);
        ray.direction = sample_uniform_sphere(rng.next_vec2());
        ray.t_min = 0.5f * rng.next_float();
        ray.t_max = ray.t_min + 8.0f * rng.next_float();
        const auto hit = scene.intersect(ray);
        ASSERT_EQ(scene.occluded(ray), hit.has_value()) << i;
        if (hit) {
            ++hits;
            EXPECT_GT(hit->t, ray.t_min);
            EXPECT_LT(hit->t, ray.t_max);
            EXPECT_EQ(hit->material, hit->shape);
            EXPECT_NEAR(glm::length(hit->geometric_normal), 1.0f, 1e-6f);
        }
    }
    EXPECT_GT(hits, 2000);
    EXPECT_LT(hits, 18000);
}

TEST(SurfaceScene, BoundsStatsAndEmptyScene) {
    const SurfaceScene scene(mixed_scene());
    const Bounds3 b = scene.bounds();
    EXPECT_LE(b.min.x, -5.0f);
    EXPECT_LE(b.min.y, -2.0f);
    EXPECT_GE(b.max.x, 5.0f);
    EXPECT_GE(b.max.z, 5.0f);
    EXPECT_LT(b.max.y, 1.01f);
    Ray ray;
    ray.origin = Vec3(0, 5, 0);
    ray.direction = Vec3(0, -1, 0);
    EXPECT_TRUE(scene.intersect(ray));
    EXPECT_TRUE(scene.occluded(ray));
    EXPECT_TRUE(scene.occluded(ray));
    const SurfaceStats stats = scene.stats();
    EXPECT_EQ(stats.closest_rays, 1u);
    EXPECT_EQ(stats.shadow_rays, 2u);
    EXPECT_EQ(stats.primitives, 1u + 12u + 2u + 4u);

    const SurfaceScene empty({});
    EXPECT_TRUE(empty.bounds().empty());
    EXPECT_FALSE(empty.intersect(ray));
    EXPECT_FALSE(empty.occluded(ray));
}

/// The shipped lamp post faces outward: every first hit from outside is on a front face, and
/// its smooth normals agree with its winding.
TEST(SurfaceScene, LampPostMeshFacesOutward) {
    MeshShape mesh;
    mesh.mesh = load_obj(std::string(KASUMI_SOURCE_DIR) + "/data/meshes/lamp_post.obj");
    const SurfaceScene scene({make(mesh)});
    const Bounds3 b = scene.bounds();
    EXPECT_EQ(b.min.y, 0.0f);
    EXPECT_GT(b.max.y, 4.0f);
    EXPECT_LT(scene.stats().primitives, 500u);
    Pcg32 rng(5, 5);
    int hits = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 target =
            b.min + b.extent() * Vec3(rng.next_float(), rng.next_float(), rng.next_float());
        const Ray ray = ray_from(target + 10.0f * sample_uniform_sphere(rng.next_vec2()), target);
        const auto hit = scene.intersect(ray);
        if (!hit)
            continue;
        ++hits;
        EXPECT_LT(glm::dot(hit->geometric_normal, ray.direction), 0.0f) << i;
        EXPECT_GT(glm::dot(hit->shading_normal, hit->geometric_normal), 0.0f) << i;
    }
    EXPECT_GT(hits, 500);
}

/// Queries from several threads at once: same answers as one thread, and exact counters.
TEST(SurfaceScene, ConcurrentQueriesAgreeAndCount) {
    const SurfaceScene scene(mixed_scene());
    constexpr int kThreads = 4, kRays = 5000;
    std::vector<Ray> rays(kRays);
    Pcg32 rng(13, 1);
    for (Ray& ray : rays) {
        ray.origin = 6.0f * (Vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f);
        ray.direction = sample_uniform_sphere(rng.next_vec2());
    }
    std::vector<float> expected(kRays);
    for (int i = 0; i < kRays; ++i) {
        const auto hit = scene.intersect(rays[i]);
        expected[i] = hit ? hit->t : -1.0f;
    }
    std::vector<int> mismatches(kThreads, 0);
    std::vector<std::thread> threads;
    for (int k = 0; k < kThreads; ++k) {
        threads.emplace_back([&, k] {
            for (int i = 0; i < kRays; ++i) {
                const auto hit = scene.intersect(rays[i]);
                mismatches[k] += (hit ? hit->t : -1.0f) != expected[i];
                mismatches[k] += scene.occluded(rays[i]) != (expected[i] >= 0.0f);
            }
        });
    }
    for (std::thread& t : threads)
        t.join();
    for (int k = 0; k < kThreads; ++k)
        EXPECT_EQ(mismatches[k], 0);
    EXPECT_EQ(scene.stats().closest_rays, uint64_t(kRays) * (kThreads + 1));
    EXPECT_EQ(scene.stats().shadow_rays, uint64_t(kRays) * kThreads);
}

/// The ray counters are per-thread shards, with one shard shared by every thread past the 63rd:
/// 100 threads (ordinals are never reused, so at least 37 share the last shard), counting rays
/// while the others do, still sum exactly.
TEST(SurfaceScene, RayCountsExactWithManyThreads) {
    const SurfaceScene scene(mixed_scene());
    constexpr int kThreads = 100, kRays = 2000;
    const Ray ray{Vec3(0.0f, 0.0f, -10.0f), Vec3(0.0f, 0.0f, 1.0f)};
    std::vector<std::thread> threads;
    for (int k = 0; k < kThreads; ++k)
        threads.emplace_back([&] {
            for (int i = 0; i < kRays; ++i) {
                (void)scene.intersect(ray);
                (void)scene.occluded(ray);
            }
        });
    for (std::thread& t : threads)
        t.join();
    EXPECT_EQ(scene.stats().closest_rays, uint64_t(kRays) * kThreads);
    EXPECT_EQ(scene.stats().shadow_rays, uint64_t(kRays) * kThreads);
}

}  // namespace
}  // namespace kasumi
