// Russian roulette on next-event estimation (render.volume.nee_roulette,
// volume/scattered_direct.cpp nee_survival): the shadow ray is traced with probability q = min(1,
// max(0.1, 4 pi p(mu))) and weighted 1/q. Checked against exact answers with q < 1 (q = 0.54 and
// the floor 0.1): a homogeneous box lit by a sun (closed form), a heterogeneous grid against a fine
// march, and multiple scattering in a grid against the same paths without the roulette. Statistical
// assertions at 4 standard errors (two-sided Gaussian false-failure rate 6e-5 each, 10
// assertions of that kind: about 6e-4 for the file; fixed seeds, so a pass is reproducible).
#include "sun_lit_media.h"
#include "white_furnace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

VolumeSettings tracker(VolumeIntegrator integrator, bool roulette, int nee_points = 0) {
    VolumeSettings s;
    s.integrator = integrator;
    s.estimator = Estimator::ResidualRatio;
    s.nee_roulette = roulette;
    s.nee_points = nee_points;
    s.max_depth = 100000;  // no truncation: Russian roulette ends the paths
    return s;
}

/// Henyey-Greenstein phase function at scattering cosine mu, 1/sr (double precision).
double hg(double g, double mu) {
    return (1.0 - g * g) /
           (4.0 * 3.14159265358979323846 * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
}

TEST(NeeRoulette, HomogeneousBoxUnderASunIsExact) {
    // test::SunLitBox with HG g: L = sigma_s p(0) exp(-sigma_t (1 - y0)) (1 - exp(-2 sigma_t)) /
    // sigma_t, the scattering cosine toward the sun being mu = 0 all along the ray.
    // g = 0.5: 4 pi p(0) = 0.54, the survival probability; g = -0.9: 4 pi p(0) = 0.078, so q
    // is the floor 0.1.
    for (const float g : {0.5f, -0.9f}) {
        const test::SunLitBox box{HenyeyGreenstein{g}};
        const double expected = test::SunLitBox::single_scattering(hg(g, 0.0));
        for (const int k : {0, 1}) {
            const VolumeSettings s = tracker(VolumeIntegrator::Single, true, k);
            VolumeCounters counters;
            const MeanAndError l = mean_over_streams(160000, 31, [&](Pcg32& rng) {
                // Nothing behind: no separate walk for the camera ray's transmittance, so
                // every transmittance estimate counted is a shadow ray's.
                return integrate_media(box.media, box.sun, nullptr, nullptr, box.ray, s, true, rng,
                                       counters, true)
                    .radiance.g;
            });
            EXPECT_NEAR(l.mean, expected, 4.0 * l.stderr_) << "g " << g << ", nee_points " << k;
            EXPECT_LT(4.0 * l.stderr_, 0.04 * expected) << "g " << g << ", nee_points " << k;
            // The roulette did leave shadow walks out: about q of the scattering events walk.
            const double walked = static_cast<double>(counters.transmittance_estimates) /
                                  static_cast<double>(counters.scattering_events);
            const double q = std::max(0.1, 4.0 * 3.14159265358979323846 * hg(g, 0.0));
            EXPECT_NEAR(walked, q, 0.02) << "g " << g << ", nee_points " << k;
        }
    }
}

TEST(NeeRoulette, HeterogeneousGridMatchesAFineMarch) {
    // test::SunLitGrid with HG g = -0.5 (q = 0.39 toward its sun) against its marched reference.
    const test::SunLitGrid grid("nee_roulette_hetero", -0.5f);
    const MeanAndError reference = grid.march_reference(31);
    ASSERT_GT(reference.mean, 0.0);
    for (const int k : {0, 4}) {
        grid.expect_matches(reference, tracker(VolumeIntegrator::Single, true, k), 31, 0.04,
                            "nee_points " + std::to_string(k));
    }
}

TEST(NeeRoulette, MultipleScatteringAgreesWithoutRoulette) {
    // The white furnace's grid (albedo 1, HG g = 0.6) lit by a sun and the uniform background:
    // every order of scattering does next-event estimation toward the sun at cosines all over
    // [-1, 1] (q from 0.1 to 1). The same paths with and without the roulette (independent
    // streams) have the same mean; the background alone gives the furnace's L = 1.
    const test::WhiteFurnace furnace("nee_roulette_furnace");
    const test::UniformBackground background(Rgb(1.0f));
    const std::vector<Light> sun{
        Light{"sun", DirectionalLight{glm::normalize(Vec3(0.4f, -1.0f, -0.3f)), Rgb(2.0f)}}};
    const auto radiance = [&](const VolumeSettings& s, const std::vector<Light>& lights,
                              uint64_t seed, int n) {
        return mean_over_streams(n, seed, [&](Pcg32& rng) {
            VolumeCounters counters;
            const VolumeResult r = integrate_media(furnace.grid, lights, nullptr, &background,
                                                   furnace.inside_grid, s, true, rng, counters);
            return static_cast<double>(r.radiance.g + r.transmittance.g);
        });
    };
    for (const int k : {0, 1}) {
        const MeanAndError off =
            radiance(tracker(VolumeIntegrator::Multiple, false, k), sun, 41, 80000);
        const MeanAndError on =
            radiance(tracker(VolumeIntegrator::Multiple, true, k), sun, 43, 80000);
        const double se = std::hypot(on.stderr_, off.stderr_);
        ASSERT_GT(off.mean, 1.1);  // the sun adds a visible share
        EXPECT_NEAR(on.mean, off.mean, 4.0 * se) << "nee_points " << k;
        // Has teeth: a 6% change of the sun's share fails.
        EXPECT_LT(4.0 * se, 0.06 * (off.mean - 1.0)) << "nee_points " << k;
        const MeanAndError furnace_only =
            radiance(tracker(VolumeIntegrator::Multiple, true, k), {}, 47, 4000);
        EXPECT_NEAR(furnace_only.mean, 1.0, 4.0 * furnace_only.stderr_ + 1e-6)
            << "nee_points " << k;
        std::printf("nee_points %d: roulette %.6g +- %.2g, without %.6g +- %.2g\n", k, on.mean,
                    on.stderr_, off.mean, off.stderr_);
    }
}

}  // namespace
}  // namespace kasumi
