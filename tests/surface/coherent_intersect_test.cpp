// SurfaceScene::intersect_coherent (Embree's ray streams, used for the camera rays of a tile's
// row) must answer exactly as intersect() does ray by ray: same hits, bit for bit, so images do
// not change with the batching. Checked on camera-like (coherent) and random (incoherent)
// rays over spheres (Embree user geometry), boxes and quads, with misses and empty intervals,
// in batch sizes on both sides of the stream's internal batch of 64.
#include "surface/surface_scene.h"
#include "tests/surface/test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <vector>

namespace kasumi {
namespace {

/// The peer benchmark's soft-shadow scene (floor, ball, block) plus a tilted quad and a second
/// sphere partly inside the block.
std::vector<Shape> test_shapes() {
    return {box(Vec3(-6.0f, -0.1f, -6.0f), Vec3(6.0f, 0.0f, 6.0f)),
            sphere(Vec3(0.3f, 1.6f, 0.0f), 0.6f),
            box(Vec3(-2.2f, 0.0f, -1.5f), Vec3(-1.4f, 1.2f, -0.7f)),
            quad(Vec3(1.0f, 0.0f, -2.0f), Vec3(3.0f, 0.5f, -2.5f), Vec3(3.0f, 2.5f, -2.5f),
                 Vec3(1.0f, 2.0f, -2.0f)),
            sphere(Vec3(-1.4f, 1.2f, -0.7f), 0.3f)};
}

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same_bits(const Vec3& a, const Vec3& b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

/// Every ray of `rays` through intersect_coherent in batches of `batch`, compared with
/// intersect(); returns how many rays hit (so a test can check it exercised both outcomes).
size_t expect_same_hits(const SurfaceScene& scene, const std::vector<Ray>& rays, size_t batch) {
    std::vector<std::optional<SurfaceHit>> coherent(rays.size());
    for (size_t start = 0; start < rays.size(); start += batch) {
        const size_t n = std::min(batch, rays.size() - start);
        scene.intersect_coherent(rays.data() + start, n, coherent.data() + start);
    }
    size_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<SurfaceHit> single = scene.intersect(rays[i]);
        EXPECT_EQ(single.has_value(), coherent[i].has_value()) << "ray " << i;
        if (!single || !coherent[i])
            continue;
        ++hits;
        const SurfaceHit& a = *single;
        const SurfaceHit& b = *coherent[i];
        EXPECT_TRUE(same_bits(a.t, b.t)) << "ray " << i << ": " << a.t << " vs " << b.t;
        EXPECT_TRUE(same_bits(a.position, b.position)) << "ray " << i;
        EXPECT_TRUE(same_bits(a.geometric_normal, b.geometric_normal)) << "ray " << i;
        EXPECT_TRUE(same_bits(a.shading_normal, b.shading_normal)) << "ray " << i;
        EXPECT_TRUE(same_bits(a.u, b.u) && same_bits(a.v, b.v)) << "ray " << i;
        EXPECT_TRUE(same_bits(a.error_scale, b.error_scale)) << "ray " << i;
        EXPECT_EQ(a.shape, b.shape) << "ray " << i;
        EXPECT_EQ(a.material, b.material) << "ray " << i;
        EXPECT_EQ(a.primitive, b.primitive) << "ray " << i;
    }
    return hits;
}

TEST(CoherentIntersect, CameraRaysMatchSingleRaysBitForBit) {
    const SurfaceScene scene(test_shapes());
    // A pinhole camera at the benchmark's eye, 97 x 61 pixel centres over a 50° field: rows
    // of neighbouring rays, some leaving the scene.
    const Vec3 eye(0.0f, 1.5f, 8.0f);
    std::vector<Ray> rays;
    for (int y = 0; y < 61; ++y) {
        for (int x = 0; x < 97; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) / 97.0f * 2.0f - 1.0f;
            const float v = 1.0f - (static_cast<float>(y) + 0.5f) / 61.0f * 2.0f;
            const Vec3 d = glm::normalize(Vec3(0.0f, -0.06f, -1.0f) + 0.47f * u * Vec3(1, 0, 0) +
                                          0.35f * v * Vec3(0, 1, 0));
            rays.push_back(Ray{eye, d, 0.0f, kInfinity});
        }
    }
    for (size_t batch : {size_t{1}, size_t{7}, size_t{16}, size_t{64}, size_t{100}, rays.size()}) {
        const size_t hits = expect_same_hits(scene, rays, batch);
        EXPECT_GT(hits, rays.size() / 2);
        EXPECT_LT(hits, rays.size());
    }
}

TEST(CoherentIntersect, RandomRaysAndIntervalsMatchSingleRays) {
    const SurfaceScene scene(test_shapes());
    std::mt19937 rng(2026);
    std::uniform_real_distribution<float> coord(-4.0f, 4.0f), unit(-1.0f, 1.0f), t(0.0f, 12.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < 4000; ++i) {
        Vec3 d(unit(rng), unit(rng), unit(rng));
        if (glm::dot(d, d) < 1e-4f)
            d = Vec3(0.0f, -1.0f, 0.0f);
        d = glm::normalize(d);
        Ray ray{Vec3(coord(rng), coord(rng) + 2.0f, coord(rng)), d, 0.0f, kInfinity};
        switch (i % 5) {
            case 1:  // a bounded interval
                ray.t_min = 0.5f * t(rng);
                ray.t_max = ray.t_min + t(rng);
                break;
            case 2:  // empty: t_min >= t_max
                ray.t_min = t(rng);
                ray.t_max = ray.t_min * 0.5f;
                break;
            case 3:  // from the ball's surface outward and inward
                ray.origin = Vec3(0.3f, 1.6f, 0.0f) + 0.6f * d;
                ray.direction = (i % 2) ? d : -d;
                break;
            default:
                break;
        }
        rays.push_back(ray);
    }
    for (size_t batch : {size_t{3}, size_t{64}, size_t{65}, rays.size()}) {
        const size_t hits = expect_same_hits(scene, rays, batch);
        EXPECT_GT(hits, rays.size() / 10);
        EXPECT_LT(hits, rays.size());
    }
}

TEST(CoherentIntersect, CountsEveryRayAsAClosestHitQuery) {
    // The -v statistics count camera rays traced either way.
    const SurfaceScene scene(test_shapes());
    std::vector<Ray> rays(70,
                          Ray{Vec3(0.0f, 1.5f, 8.0f), Vec3(0.0f, 0.0f, -1.0f), 0.0f, kInfinity});
    rays[3].t_max = 0.0f;  // empty interval: counted, not traced
    std::vector<std::optional<SurfaceHit>> hits(rays.size());
    const uint64_t before = scene.stats().closest_rays;
    scene.intersect_coherent(rays.data(), rays.size(), hits.data());
    EXPECT_EQ(scene.stats().closest_rays - before, rays.size());
    EXPECT_FALSE(hits[3].has_value());
    EXPECT_TRUE(hits[4].has_value());
}

}  // namespace
}  // namespace kasumi
