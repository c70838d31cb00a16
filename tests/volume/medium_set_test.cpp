#include "volume/medium_set.h"

#include "core/rng.h"
#include "volume/grid/density_grid.h"
#include "volume/transmittance.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

Medium box_medium(Vec3 lo, Vec3 hi, Rgb sigma_a, Rgb sigma_s) {
    return Medium{"box", HomogeneousMedium{Bounds3{lo, hi}, sigma_a, sigma_s, Isotropic{}}};
}

TEST(MediumSet, BeerLambertThroughABox) {
    const MediumSet media(
        {box_medium(Vec3(0.0f), Vec3(1.0f), Rgb(0.5f, 1.0f, 2.0f), Rgb(1.5f, 1.0f, 0.0f))});
    // Along x through the middle: path length 1, sigma_t = (2, 2, 2).
    const Ray axis{Vec3(-3.0f, 0.5f, 0.5f), Vec3(1, 0, 0), 0.0f, kInfinity};
    const Rgb t = media.transmittance(axis);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(t[c], std::exp(-2.0f), 1e-6f);
    // Along the main diagonal: path length sqrt(3).
    const Ray diagonal{Vec3(-1.0f), glm::normalize(Vec3(1.0f)), 0.0f, kInfinity};
    EXPECT_NEAR(media.transmittance(diagonal).r, std::exp(-2.0f * std::sqrt(3.0f)), 1e-5f);
    // A segment ending inside the box: only the part inside counts.
    const Ray partial{Vec3(-3.0f, 0.5f, 0.5f), Vec3(1, 0, 0), 0.0f, 3.25f};
    EXPECT_NEAR(media.transmittance(partial).r, std::exp(-0.5f), 1e-6f);
    // Missing the box.
    const Ray miss{Vec3(-3.0f, 2.0f, 0.5f), Vec3(1, 0, 0), 0.0f, kInfinity};
    EXPECT_EQ(media.transmittance(miss), Rgb(1.0f));
}

TEST(MediumSet, OverlappingMediaAddCoefficients) {
    const MediumSet media({box_medium(Vec3(0.0f), Vec3(2.0f), Rgb(0.1f), Rgb(0.2f)),
                           box_medium(Vec3(1.0f), Vec3(3.0f), Rgb(0.3f), Rgb(0.0f))});
    const Ray ray{Vec3(-1.0f, 1.5f, 1.5f), Vec3(1, 0, 0), 0.0f, kInfinity};
    // x in [0,1]: 0.3; [1,2]: 0.6; [2,3]: 0.3 → tau = 1.2.
    EXPECT_NEAR(media.optical_depth(ray).r, 1.2f, 1e-5f);
    std::vector<MediumInterval> intervals;
    media.intervals(ray, intervals);
    ASSERT_EQ(intervals.size(), 3u);
    EXPECT_NEAR(intervals[1].sigma_t.r, 0.6f, 1e-6f);
    EXPECT_EQ(intervals[1].scattering_mask, 1u);
    EXPECT_EQ(intervals[2].scattering_mask, 0u);
}

TEST(MediumSet, UnboundedMediumAlongAnEndlessRayIsOpaque) {
    const MediumSet media({Medium{
        "fog", HomogeneousMedium{std::nullopt, Rgb(0.0f, 0.0f, 0.01f), Rgb(0.0f), Isotropic{}}}});
    const Rgb t = media.transmittance(Ray{Vec3(0.0f), Vec3(0, 0, 1), 0.0f, kInfinity});
    EXPECT_EQ(t.r, 1.0f);  // a clear channel stays clear (no 0 * inf = NaN)
    EXPECT_EQ(t.b, 0.0f);
}

// The march walks abutting brick segments as one run: on a grid whose density is linear along
// the ray between the run's ends, the trapezoid rule is exact whatever the jitter, and the
// lookups are the grid nodes plus the run's two ends (no extra pair per 8-voxel brick).
TEST(MarchWalk, LinearDensityAcrossBricksIsExactWithNodesOnlyAtRunEnds) {
    auto grid = std::make_shared<DensityGrid>(IVec3(0), IVec3(39, 3, 3));
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k)
                grid->set(IVec3(i, j, k), 0.001f * static_cast<float>(i + 1));
    grid->finalize();
    VdbMedium v;
    v.grid = grid;
    v.sigma_s_per_density = Rgb(1.0f);
    v.bounds_world = Bounds3{grid->lower(), grid->upper()};
    const MediumSet media({Medium{"ramp", v}});
    // y = z = 1.5 lies between set voxels: density 0.001 (x + 1) for x in [0, 39], a kink at
    // both ends of the ray, linear between; tau = 0.001 (39^2 / 2 + 39).
    const Ray ray{Vec3(0.0f, 1.5f, 1.5f), Vec3(1, 0, 0), 0.0f, 39.0f};
    const double tau = 0.001 * (39.0 * 39.0 / 2.0 + 39.0);
    const float h = 2.0f;
    Pcg32 rng(7, 1);
    for (int trial = 0; trial < 20; ++trial) {
        VolumeCounters counters;
        const Rgb t = estimate_transmittance(media, ray, Estimator::March, h, rng, counters);
        EXPECT_NEAR(t.r, std::exp(-tau), 2e-5);
        // 39 / h nodes (one more at most, by the jitter) and the run's two ends; the five
        // bricks the ray crosses would add eight more end lookups if walked one by one.
        EXPECT_LE(counters.density_lookups, static_cast<uint64_t>(39.0f / h) + 3u);
    }
}

}  // namespace
}  // namespace kasumi
