// The multiple-scattering techniques of issue #19: Russian roulette and splitting by a weight
// window on throughput x the cached sun transmittance (render.volume.splitting "sun",
// volume/weight_window.h) and the camera segment's transmittance from the first free flight
// (render.volume.camera_transmittance "first_flight", volume/volume_path.cpp). The window's
// rounding is checked exactly; the estimators against the same paths without the technique and
// against closed forms. Statistical assertions at 4 standard errors (two-sided Gaussian
// false-failure rate 6e-5 each, 6 such assertions: about 4e-4 for the file; fixed seeds).
#include "volume/weight_window.h"
#include "sun_lit_media.h"
#include "white_furnace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

/// Paths per estimate in the statistical checks.
constexpr int kPaths = 120000;

VolumeSettings paths(PathSplitting splitting,
                     CameraTransmittance camera = CameraTransmittance::Walk) {
    VolumeSettings s;
    s.integrator = VolumeIntegrator::Multiple;
    s.estimator = Estimator::ResidualRatio;
    s.max_depth = 100000;  // no truncation: Russian roulette ends the paths
    s.splitting = splitting;
    s.camera_transmittance = camera;
    return s;
}

TEST(WeightWindow, CopiesTimesWeightAveragesToOne) {
    // E[copies x weight] = 1 over u uniform in [0, 1): on a midpoint grid of u the stochastic
    // rounding is exact up to the grid's step (1e-5).
    for (const float q : {0.001f, 0.05f, 0.3f, 0.5f, 1.0f, 2.0f, 3.3f, 7.9f, 40.0f}) {
        constexpr int n = 100000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const SplitDecision d = split_decision(q, (static_cast<float>(i) + 0.5f) / n);
            sum += d.copies * static_cast<double>(d.weight);
            ASSERT_LE(d.copies, static_cast<int>(kMaxCopies)) << "q " << q;
        }
        EXPECT_NEAR(sum / n, 1.0, 2e-5) << "q " << q;
    }
    // Inside the window the path is left alone; a zero or undefined ratio ends it.
    EXPECT_EQ(split_decision(1.3f, 0.99f).copies, 1);
    EXPECT_EQ(split_decision(1.3f, 0.99f).weight, 1.0f);
    EXPECT_EQ(split_decision(0.0f, 0.0f).copies, 0);
    EXPECT_EQ(split_decision(std::nanf(""), 0.0f).copies, 0);
}

TEST(WeightWindow, WhiteFurnaceStaysExact) {
    // Albedo 1 and a uniform background of 1: L = 1 for any path estimator. Without lights the
    // importance is constant and the window acts on the throughput (Russian roulette below
    // half the first vertex's, splitting above twice).
    const test::WhiteFurnace furnace("weight_window_furnace");
    const test::UniformBackground background(Rgb(1.0f));
    const MeanAndError l = mean_over_streams(20000, 53, [&](Pcg32& rng) {
        VolumeCounters counters;
        const VolumeResult r =
            integrate_media(furnace.grid, {}, nullptr, &background, furnace.inside_grid,
                            paths(PathSplitting::Sun), true, rng, counters);
        return static_cast<double>(r.radiance.g + r.transmittance.g);
    });
    EXPECT_NEAR(l.mean, 1.0, 4.0 * l.stderr_ + 1e-6);
}

TEST(WeightWindow, SunLitGridAgreesWithoutTheWindow) {
    // test::SunLitGrid (albedo 0.8, HG g = 0.3, density 0.2 .. 3.8 per metre) under its sun,
    // every order of scattering: the window's importance comes from the sun's transmittance
    // cache and varies across the grid, so it splits and kills. The same paths with and without
    // the window (independent streams) have the same mean, to 1%: 4 combined standard errors
    // are below 1% of the mean, so a 2% bias fails.
    const test::SunLitGrid grid("weight_window_grid", 0.3f);
    ASSERT_NE(grid.media.light_cache(0, grid.sun[0]), nullptr);
    const auto radiance = [&](const VolumeSettings& s, uint64_t seed) {
        return mean_over_streams(10 * kPaths, seed, [&](Pcg32& rng) {
            VolumeCounters counters;
            return static_cast<double>(integrate_media(grid.media, grid.sun, nullptr, nullptr,
                                                       grid.ray, s, true, rng, counters, true)
                                           .radiance.g);
        });
    };
    const MeanAndError off = radiance(paths(PathSplitting::Off), 61);
    const MeanAndError on = radiance(paths(PathSplitting::Sun), 67);
    const double se = std::hypot(on.stderr_, off.stderr_);
    ASSERT_GT(off.mean, 0.05);
    EXPECT_NEAR(on.mean, off.mean, 4.0 * se);
    EXPECT_LT(4.0 * se, 0.01 * off.mean);
    std::printf("window %.6g +- %.2g, without %.6g +- %.2g\n", on.mean, on.stderr_, off.mean,
                off.stderr_);
}

TEST(CameraTransmittance, FirstFlightIsBeerLambertWithALitBoxInFront) {
    // test::SunLitBox, something behind (nothing_behind false): the first flight's escape weight
    // is T = exp(-2 sigma_t) on average, and the scattered light matches the separate walk's.
    const test::SunLitBox box{HenyeyGreenstein{0.3f}};
    const auto run = [&](CameraTransmittance camera, uint64_t seed, bool want_t) {
        return mean_over_streams((want_t ? 4 : 2) * kPaths, seed, [&](Pcg32& rng) {
            VolumeCounters counters;
            const VolumeResult r =
                integrate_media(box.media, box.sun, nullptr, nullptr, box.ray,
                                paths(PathSplitting::Off, camera), true, rng, counters, false);
            return static_cast<double>(want_t ? r.transmittance.g : r.radiance.g);
        });
    };
    const MeanAndError t = run(CameraTransmittance::FirstFlight, 71, true);
    const double exact = test::SunLitBox::transmittance();
    EXPECT_NEAR(t.mean, exact, 4.0 * t.stderr_);
    EXPECT_LT(4.0 * t.stderr_, 0.1 * exact);  // T = 0.0067: a 10% error fails
    const MeanAndError first = run(CameraTransmittance::FirstFlight, 73, false);
    const MeanAndError walk = run(CameraTransmittance::Walk, 79, false);
    const double se = std::hypot(first.stderr_, walk.stderr_);
    EXPECT_NEAR(first.mean, walk.mean, 4.0 * se);
    EXPECT_LT(4.0 * se, 0.02 * walk.mean);
}

}  // namespace
}  // namespace kasumi
