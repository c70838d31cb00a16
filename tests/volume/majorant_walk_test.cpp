// The trackers' lazy walk over a grid's bricks (DensityGrid::walk, volume/majorant_walk.h): its
// bounds hold everywhere, it matches bricks_along, it stops when told, and the trackers over it
// stay unbiased on a grid of scattered blocks with many empty bricks.
#include "volume/majorant_walk.h"
#include "core/rng.h"
#include "tests/sample_mean.h"
#include "volume/grid/density_grid.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace kasumi {
namespace {

constexpr int kEdge = 64;  ///< voxels per grid edge: 8 bricks of 8 cells per axis

/// A grid of random blocks: about a third of the 8³ blocks hold random densities in [0, 2)
/// (some constant), the rest stay empty.
std::shared_ptr<DensityGrid> random_grid(uint64_t seed) {
    auto grid = std::make_shared<DensityGrid>(IVec3(0), IVec3(kEdge - 1));
    Pcg32 rng(seed, 3);
    for (int bz = 0; bz < kEdge / 8; ++bz)
        for (int by = 0; by < kEdge / 8; ++by)
            for (int bx = 0; bx < kEdge / 8; ++bx) {
                const float u = rng.next_float();
                if (u < 0.65f)
                    continue;
                const bool constant = u > 0.9f;
                const float level = 2.0f * rng.next_float();
                for (int z = 0; z < 8; ++z)
                    for (int y = 0; y < 8; ++y)
                        for (int x = 0; x < 8; ++x)
                            grid->set(IVec3(8 * bx + x, 8 * by + y, 8 * bz + z),
                                      constant ? level : 2.0f * rng.next_float());
            }
    grid->finalize();
    return grid;
}

/// A random ray across the grid's box, in index space, with its parameter range.
struct IndexRay {
    Vec3 o, d;
    float t0, t1;
};

IndexRay random_ray(Pcg32& rng) {
    const auto in_box = [&] {
        return Vec3(-4.0f) + Vec3(rng.next_float(), rng.next_float(), rng.next_float()) *
                                 static_cast<float>(kEdge + 8);
    };
    const Vec3 a = in_box(), b = in_box();
    // Every 16th ray is axis-parallel (zero direction components take the DDA's special case).
    IndexRay r{a, b - a, 0.0f, 1.0f};
    if (rng.next_u32() % 16 == 0)
        r.d = Vec3(0.0f, 0.0f, b.z - a.z);
    return r;
}

TEST(DensityGridWalk, BoundsHoldEverywhereAndNoDensityIsMissed) {
    const auto grid = random_grid(11);
    ASSERT_GT(grid->allocated_bricks(), 100u);
    ASSERT_LT(grid->allocated_bricks(), grid->total_bricks());
    Pcg32 rng(5, 1);
    size_t checked = 0;
    for (int r = 0; r < 2000; ++r) {
        const IndexRay ray = random_ray(rng);
        std::vector<BrickSpan> spans;
        std::vector<BrickRef> bricks;
        grid->walk(ray.o, ray.d, ray.t0, ray.t1, [&](const BrickSpan& s, const BrickRef& b) {
            spans.push_back(s);
            bricks.push_back(b);
            return true;
        });
        for (size_t i = 0; i < spans.size(); ++i) {
            const BrickSpan& s = spans[i];
            ASSERT_LT(s.t0, s.t1);
            ASSERT_GE(s.t0, ray.t0);
            ASSERT_LE(s.t1, ray.t1);
            if (i > 0) {
                ASSERT_LE(spans[i - 1].t1, s.t0);  // in order, disjoint
            }
            ASSERT_LE(s.density_min, s.density_max);
            // Points inside the span lie within its bounds, read either way. Spans a few ulps
            // long occur where the DDA's rounded crossings of two planes nearly coincide; their
            // points may lie a rounding error outside their block, so they are not sampled.
            if (s.t1 - s.t0 < 1e-5f * (ray.t1 - ray.t0))
                continue;
            for (int k = 0; k < 8; ++k) {
                const float t = s.t0 + (s.t1 - s.t0) * (1e-4f + 0.9998f * rng.next_float());
                const Vec3 p = ray.o + t * ray.d;
                const float d = grid->density(p);
                EXPECT_LE(d, s.density_max * (1.0f + 1e-6f) + 1e-6f) << "ray " << r;
                EXPECT_GE(d, s.density_min * (1.0f - 1e-6f) - 1e-6f) << "ray " << r;
                EXPECT_NEAR(DensityGrid::density_in(bricks[i], p), d, 1e-5f);
                ++checked;
            }
        }
        // The same stretches as the eager listing (which merges equal neighbours).
        std::vector<BrickSpan> listed;
        grid->bricks_along(ray.o, ray.d, ray.t0, ray.t1, listed);
        float covered_walk = 0.0f, covered_list = 0.0f;
        for (const BrickSpan& s : spans)
            covered_walk += s.t1 - s.t0;
        for (const BrickSpan& s : listed)
            covered_list += s.t1 - s.t0;
        EXPECT_NEAR(covered_walk, covered_list, 1e-5f * (ray.t1 - ray.t0)) << "ray " << r;
        if (!spans.empty() && !listed.empty()) {
            EXPECT_EQ(spans.front().t0, listed.front().t0);
            EXPECT_EQ(spans.back().t1, listed.back().t1);
        }
        // Every point with density lies in some span (empty space only is skipped).
        for (int k = 0; k < 64; ++k) {
            const float t = ray.t0 + (ray.t1 - ray.t0) * rng.next_float();
            const float d = grid->density(ray.o + t * ray.d);
            if (!(d > 1e-4f))
                continue;
            bool covered = false;
            for (const BrickSpan& s : spans)
                covered = covered || (t >= s.t0 && t <= s.t1);
            EXPECT_TRUE(covered) << "ray " << r << " t " << t << " density " << d;
        }
    }
    EXPECT_GT(checked, 10000u);
}

TEST(DensityGridWalk, StopsWhenTheVisitSaysSo) {
    const auto grid = random_grid(13);
    Pcg32 rng(3, 1);
    for (int r = 0; r < 200; ++r) {
        const IndexRay ray = random_ray(rng);
        size_t all = 0;
        grid->walk(ray.o, ray.d, ray.t0, ray.t1, [&](const BrickSpan&, const BrickRef&) {
            ++all;
            return true;
        });
        if (all < 2)
            continue;
        size_t calls = 0;
        const bool finished =
            grid->walk(ray.o, ray.d, ray.t0, ray.t1,
                       [&](const BrickSpan&, const BrickRef&) { return ++calls < 2; });
        EXPECT_FALSE(finished);
        EXPECT_EQ(calls, 2u);
    }
}

/// Mean and standard error of n estimates (red channel; the medium is grey).
std::pair<double, double> mean_and_stderr(const MediumSet& media, const Ray& ray,
                                          Estimator estimator, int n) {
    VolumeCounters counters;
    SampleMean m;
    for (int i = 0; i < n; ++i) {
        Pcg32 rng(21, static_cast<uint64_t>(i));
        m.add(estimate_transmittance(media, ray, estimator, 0.0f, rng, counters).r);
    }
    const MeanAndError r = m.result();
    return {r.mean, r.stderr_};
}

TEST(DensityGridWalk, TrackersMatchAFineMarchThroughManyEmptyBricks) {
    // Rays across the random grid (empty, constant and varying bricks; some rays start or end
    // inside): every unbiased tracker, walking the bricks lazily, agrees with
    // a march of 1/64 voxel (deterministic up to its O(h²) error, far below the noise here).
    const auto grid = random_grid(14);
    VdbMedium v;
    v.grid = grid;
    v.sigma_a_per_density = Rgb(0.01f);
    v.sigma_s_per_density = Rgb(0.04f);
    v.bounds_world = Bounds3{grid->lower(), grid->upper()};
    const MediumSet media({Medium{"blocks", v}});
    ASSERT_NE(media.single_grid(), nullptr);
    const Ray rays[] = {
        {Vec3(-3.0f, 20.3f, 37.9f), glm::normalize(Vec3(1.0f, 0.31f, -0.17f)), 0.0f, 90.0f},
        {Vec3(70.0f, 5.5f, 60.1f), glm::normalize(Vec3(-1.0f, 0.8f, -0.9f)), 0.0f, 120.0f},
        {Vec3(30.2f, 33.3f, 12.1f), Vec3(0.0f, 0.0f, 1.0f), 3.0f, 40.0f},  // starts inside
        {Vec3(12.5f, -5.0f, 47.5f), Vec3(0.0f, 1.0f, 0.0f), 0.0f, 80.0f},
    };
    for (const Ray& ray : rays) {
        VolumeCounters counters;
        Pcg32 rng(1, 1);
        const double reference =
            estimate_transmittance(media, ray, Estimator::March, 1.0f / 64.0f, rng, counters).r;
        ASSERT_GT(reference, 0.02);
        ASSERT_LT(reference, 0.95);
        for (Estimator e : {Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio}) {
            const auto [mean, se] = mean_and_stderr(media, ray, e, 40000);
            // 4 standard errors: a false failure about once in 16000 per check (12 checks).
            EXPECT_NEAR(mean, reference, 4.0 * se + 1e-4) << estimator_name(e);
            // Teeth: a 5% bias would fail.
            EXPECT_LT(4.0 * se + 1e-4, 0.05 * reference) << estimator_name(e);
        }
    }
}

}  // namespace
}  // namespace kasumi
