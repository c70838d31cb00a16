// Russian roulette on next-event estimation by the shadow ray's expected contribution
// (render.volume.shadow_roulette, volume/scattered_direct.cpp contribution_survival): a shadow
// ray toward a directional light is traced with probability q = min(1, max(0.05, 4 pi w
// mean(sigma_s p T_cache) / share)), w the path weight, and weighted 1/q. Checked: the survival
// probability's closed form and bounds; a heterogeneous grid's single scattering against a
// 1/64-voxel march (q < 1 for most events); multiple scattering in the white furnace's grid
// under a sun against the same paths without the roulette; optical depths 1e-8 .. 1e4 give
// finite, non-negative radiance. Statistical assertions at 4 standard errors (two-sided Gaussian
// false-failure rate 6e-5 each, 6 of them: about 4e-4 for the file; fixed seeds, so a pass is
// reproducible). A 2% gain planted on the roulette's estimate (both branches) fails the grid and
// the furnace checks (tried).
#include "sun_lit_media.h"
#include "volume/scattered_direct.h"
#include "white_furnace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

constexpr double kPi4 = 4.0 * 3.14159265358979323846;

/// Residual ratio tracking with the roulette's `share` (0: off) and no depth limit (Russian
/// roulette ends the paths).
VolumeSettings tracker(VolumeIntegrator integrator, float share, int nee_points = 0) {
    VolumeSettings s;
    s.estimator = Estimator::ResidualRatio;
    s.max_depth = 100000;
    s.integrator = integrator;
    s.nee_points = nee_points;
    s.shadow_roulette = share;
    return s;
}

TEST(ShadowRoulette, SurvivalIsTheContributionShareWithinItsBounds) {
    // q = 4 pi e / share between the floor and 1.
    EXPECT_FLOAT_EQ(contribution_survival(0.3f / kPi4, 1.0f), 0.3f);
    EXPECT_FLOAT_EQ(contribution_survival(0.02f / kPi4, 0.1f), 0.2f);
    EXPECT_FLOAT_EQ(contribution_survival(2.0f / kPi4, 1.0f), 1.0f);
    EXPECT_FLOAT_EQ(contribution_survival(0.0f, 0.1f), kShadowSurvivalFloor);
    EXPECT_FLOAT_EQ(contribution_survival(1e-30f, 1.0f), kShadowSurvivalFloor);
    // An undefined expectation traces (never a roulette on NaN); an infinite one too.
    EXPECT_FLOAT_EQ(contribution_survival(std::nanf(""), 0.1f), 1.0f);
    EXPECT_FLOAT_EQ(contribution_survival(INFINITY, 0.1f), 1.0f);
}

TEST(ShadowRoulette, HeterogeneousGridMatchesAFineMarch) {
    // test::SunLitGrid (one grid, a sun: the light cache exists) with HG g = 0.3; share 0.2, so
    // every event expected to bring less than 0.2 of an isotropic lit scatterer's plays the
    // roulette (T toward the sun is 0.05 .. 0.15 on most of the ray, albedo 0.8). The reference
    // marches at 1/64 voxel (camera ray and shadow rays; O(h²) bias far below the statistics).
    const test::SunLitGrid grid("shadow_roulette_hetero", 0.3f);
    VolumeSettings march;
    march.estimator = Estimator::March;
    march.step_voxels = 1.0f / 64.0f;
    const MeanAndError reference = mean_over_streams(16, 31, [&](Pcg32& rng) {
        VolumeCounters counters;
        return integrate_media(grid.media, grid.sun, nullptr, nullptr, grid.ray, march, true, rng,
                               counters)
            .radiance.g;
    });
    ASSERT_GT(reference.mean, 0.0);
    for (const int k : {0, 4}) {
        const VolumeSettings s = tracker(VolumeIntegrator::Single, 0.2f, k);
        // 480000 paths: 4 standard errors below 1.8% of the answer, so a 2% bias fails.
        const MeanAndError l = mean_over_streams(480000, 37, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(grid.media, grid.sun, nullptr, nullptr, grid.ray, s, true, rng,
                                   counters)
                .radiance.g;
        });
        const double se = std::hypot(l.stderr_, reference.stderr_);
        EXPECT_NEAR(l.mean, reference.mean, 4.0 * se + 1e-3 * reference.mean) << k;
        EXPECT_LT(4.0 * se, 0.018 * reference.mean) << k;
        std::printf("nee_points %d: %.6g +- %.2g, march %.6g +- %.2g\n", k, l.mean, l.stderr_,
                    reference.mean, reference.stderr_);
        // The roulette is active: fewer shadow walks than events, but some.
        VolumeCounters counters;
        for (int i = 0; i < 20000; ++i) {
            Pcg32 rng(53, static_cast<uint64_t>(i));
            integrate_media(grid.media, grid.sun, nullptr, nullptr, grid.ray, s, true, rng,
                            counters, true);
        }
        const double walked = static_cast<double>(counters.transmittance_estimates) /
                              static_cast<double>(counters.scattering_events);
        std::printf("nee_points %d: %.3f shadow walks per event\n", k, walked);
        EXPECT_LT(walked, 0.8) << "nee_points " << k;
        EXPECT_GT(walked, 0.05) << "nee_points " << k;
    }
}

TEST(ShadowRoulette, MultipleScatteringAgreesWithoutRoulette) {
    // The white furnace's grid (albedo 1, HG g = 0.6, density 3 over 4 m) under a sun, nothing
    // beyond: every order does next-event estimation toward the sun, deep events with T_cache
    // near 0 (q at the floor). The same paths with and without the roulette (independent
    // streams) agree.
    const test::WhiteFurnace furnace("shadow_roulette_furnace");
    const std::vector<Light> sun{
        Light{"sun", DirectionalLight{glm::normalize(Vec3(0.4f, -1.0f, -0.3f)), Rgb(2.0f)}}};
    const auto radiance = [&](const VolumeSettings& s, uint64_t seed, int n,
                              VolumeCounters& counters) {
        return mean_over_streams(n, seed, [&](Pcg32& rng) {
            return static_cast<double>(integrate_media(furnace.grid, sun, nullptr, nullptr,
                                                       furnace.inside_grid, s, true, rng, counters)
                                           .radiance.g);
        });
    };
    VolumeCounters off_counters, on_counters;
    const MeanAndError off =
        radiance(tracker(VolumeIntegrator::Multiple, 0.0f), 41, 600000, off_counters);
    const MeanAndError on =
        radiance(tracker(VolumeIntegrator::Multiple, 0.5f), 43, 600000, on_counters);
    const double se = std::hypot(on.stderr_, off.stderr_);
    ASSERT_GT(off.mean, 0.1);
    EXPECT_NEAR(on.mean, off.mean, 4.0 * se);
    // Has teeth: a 2% change of the radiance fails.
    EXPECT_LT(4.0 * se, 0.02 * off.mean);
    EXPECT_LT(on_counters.transmittance_estimates, off_counters.transmittance_estimates / 2);
    std::printf("roulette %.6g +- %.2g (%llu walks), without %.6g +- %.2g (%llu walks)\n", on.mean,
                on.stderr_, static_cast<unsigned long long>(on_counters.transmittance_estimates),
                off.mean, off.stderr_,
                static_cast<unsigned long long>(off_counters.transmittance_estimates));
}

TEST(ShadowRoulette, ExtremeOpticalDepthsStayFinite) {
    // A constant 16³ box grid (4 m across) of albedo 0.9 under a sun, density scale 1e-8 .. 1e4
    // per metre: optical depths 4e-8 .. 4e4 across. Every path's radiance is finite and >= 0,
    // and the thinnest box scatters almost nothing.
    const std::string path = test::write_box("shadow_roulette_extreme", 16, 1.0f, 0.25);
    const std::vector<Light> sun{
        Light{"sun", DirectionalLight{glm::normalize(Vec3(0.3f, -1.0f, 0.2f)), Rgb(1.0f)}}};
    const Ray ray{Vec3(-1.0f, 2.1f, 1.9f), glm::normalize(Vec3(1, 0.05f, 0.1f)), 0.0f, kInfinity};
    for (const double scale : {1e-8, 1e-4, 1.0, 1e2, 1e4}) {
        const MediumSet media({test::vdb_medium(path, {{"density_scale", scale},
                                                       {"albedo", 0.9},
                                                       {"phase", {{"model", "hg"}, {"g", 0.8}}}})});
        VolumeSettings s = tracker(VolumeIntegrator::Multiple, 0.1f);
        s.max_depth = 256;
        VolumeCounters counters;
        double sum = 0.0;
        for (int i = 0; i < 500; ++i) {
            Pcg32 rng(61, static_cast<uint64_t>(i));
            const VolumeResult r =
                integrate_media(media, sun, nullptr, nullptr, ray, s, true, rng, counters);
            ASSERT_TRUE(std::isfinite(r.radiance.g) && r.radiance.g >= 0.0f)
                << "density scale " << scale << ", path " << i;
            ASSERT_TRUE(std::isfinite(r.transmittance.g)) << "density scale " << scale;
            sum += r.radiance.g;
        }
        if (scale == 1e-8) {
            EXPECT_LT(sum / 500.0, 1e-6);
        }
    }
}

}  // namespace
}  // namespace kasumi
