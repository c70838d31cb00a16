// Ratio tracking for in-scattering with next-event estimation at several collisions per path
// segment (render.volume.nee_points, volume/scattered_paths.cpp) against exact answers: a
// homogeneous box lit by a sun (closed form), a heterogeneous grid against a fine march, and
// the white furnace for multiple scattering. Statistical assertions at 4 standard errors
// (two-sided Gaussian false-failure rate 6e-5 each; fixed seeds, so a pass is reproducible).
#include "sun_lit_media.h"
#include "white_furnace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

namespace kasumi {
namespace {

using Mean = MeanAndError;

Mean average(int n, const std::function<double(Pcg32&)>& sample) {
    return mean_over_streams(n, 29, sample);
}

VolumeSettings tracked(VolumeIntegrator integrator, int nee_points) {
    VolumeSettings s;
    s.integrator = integrator;
    s.estimator = Estimator::ResidualRatio;
    s.nee_points = nee_points;
    s.max_depth = 100000;  // no truncation: Russian roulette ends the paths
    return s;
}

TEST(TrackedInScattering, HomogeneousBoxUnderASunIsExact) {
    // test::SunLitBox, isotropic: L = sigma_s / (4 pi) exp(-sigma_t (1 - y0)) (1 - exp(-2
    // sigma_t)) / sigma_t and T = exp(-2 sigma_t).
    const test::SunLitBox box{Isotropic{}};
    const double expected_l = test::SunLitBox::single_scattering(1.0 / (4.0 * kPiD));
    const double expected_t = test::SunLitBox::transmittance();
    for (const int k : {1, 4}) {
        const VolumeSettings s = tracked(VolumeIntegrator::Single, k);
        const Mean l = average(160000, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(box.media, box.sun, nullptr, nullptr, box.ray, s, true, rng,
                                   counters)
                .radiance.g;
        });
        EXPECT_NEAR(l.mean, expected_l, 4.0 * l.stderr_) << "nee_points " << k;
        EXPECT_LT(4.0 * l.stderr_, 0.015 * expected_l) << "nee_points " << k;  // has teeth
        const Mean t = average(40000, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(box.media, box.sun, nullptr, nullptr, box.ray, s, true, rng,
                                   counters)
                .transmittance.g;
        });
        // Constant box: the ratio factors are 1; only the roulette below T^ = 0.05 adds noise.
        EXPECT_NEAR(t.mean, expected_t, 4.0 * t.stderr_ + 1e-7) << "nee_points " << k;
        EXPECT_LT(4.0 * t.stderr_, 0.05 * expected_t) << "nee_points " << k;
    }
}

TEST(TrackedInScattering, HeterogeneousGridMatchesAFineMarch) {
    // test::SunLitGrid with HG g = 0.5 against its marched reference.
    const test::SunLitGrid grid("tracked_hetero", 0.5f);
    const Mean reference = grid.march_reference(29);
    ASSERT_GT(reference.mean, 0.0);
    for (const int k : {1, 4}) {
        grid.expect_matches(reference, tracked(VolumeIntegrator::Single, k), 29, 0.03,
                            "nee_points " + std::to_string(k));
    }
}

TEST(TrackedInScattering, WhiteFurnace) {
    // Albedo 1 inside a uniform environment of radiance 1: L = 1 exactly in expectation
    // (energy conservation), for a grid and a homogeneous box, camera inside the medium.
    const test::WhiteFurnace furnace("tracked_furnace");
    for (const int k : {1, 3}) {
        const VolumeSettings s = tracked(VolumeIntegrator::Multiple, k);
        for (const auto& [media, ray] : {std::pair{&furnace.grid, furnace.inside_grid},
                                         std::pair{&furnace.fog, furnace.inside_fog}}) {
            const Mean l = average(4000, [&](Pcg32& rng) {
                return test::WhiteFurnace::radiance(*media, s, ray, rng);
            });
            EXPECT_NEAR(l.mean, 1.0, 4.0 * l.stderr_ + 1e-6) << "nee_points " << k;
            EXPECT_LT(4.0 * l.stderr_, 0.02) << "nee_points " << k;  // a 2% loss fails
        }
    }
}

}  // namespace
}  // namespace kasumi
