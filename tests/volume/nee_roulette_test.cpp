// Russian roulette on next-event estimation (render.volume.nee_roulette, volume/volume_path.cpp
// nee_survival): the shadow ray is traced with probability q = min(1, max(0.1, 4 pi p(mu))) and
// weighted 1/q. Checked against exact answers with q < 1 (q = 0.54 and the floor 0.1): a
// homogeneous box lit by a sun (closed form), a heterogeneous grid against a fine march, and
// multiple scattering in a grid against the same paths without the roulette. Statistical
// assertions at 4 standard errors (two-sided Gaussian false-failure rate 6e-5 each, 10
// assertions of that kind: about 6e-4 for the file; fixed seeds, so a pass is reproducible).
#include "tests/sample_mean.h"
#include "vdb_test_grids.h"
#include "volume/volume_path.h"
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
    // A box [-1, 1]³ of sigma_s = 2, sigma_a = 0.5 per metre, HG phase, lit from +y by a sun of
    // irradiance 1; a camera ray along +x at height y0 crosses it over 2 m, every point of it
    // 1 - y0 below the top face and the scattering cosine toward the sun is mu = 0, so
    //   L = sigma_s p(0) exp(-sigma_t (1 - y0)) (1 - exp(-2 sigma_t)) / sigma_t.
    // g = 0.5: 4 pi p(0) = 0.54, the survival probability; g = -0.9: 4 pi p(0) = 0.078, so q
    // is the floor 0.1.
    const float sigma_s = 2.0f, sigma_a = 0.5f, sigma_t = sigma_s + sigma_a, y0 = 0.2f;
    const std::vector<Light> sun{Light{"sun", DirectionalLight{Vec3(0, -1, 0), Rgb(1.0f)}}};
    const Ray ray{Vec3(-3.0f, y0, 0.1f), Vec3(1, 0, 0), 0.0f, kInfinity};
    for (const float g : {0.5f, -0.9f}) {
        const MediumSet box(
            {Medium{"box", HomogeneousMedium{Bounds3{Vec3(-1.0f), Vec3(1.0f)}, Rgb(sigma_a),
                                             Rgb(sigma_s), HenyeyGreenstein{g}}}});
        const double expected = sigma_s * hg(g, 0.0) * std::exp(-sigma_t * (1.0 - y0)) *
                                (1.0 - std::exp(-2.0 * sigma_t)) / sigma_t;
        for (const int k : {0, 1}) {
            const VolumeSettings s = tracker(VolumeIntegrator::Single, true, k);
            VolumeCounters counters;
            const MeanAndError l = mean_over_streams(160000, 31, [&](Pcg32& rng) {
                // Nothing behind: no separate walk for the camera ray's transmittance, so
                // every transmittance estimate counted is a shadow ray's.
                return integrate_media(box, sun, nullptr, nullptr, ray, s, true, rng, counters,
                                       true)
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
    // A 24³ grid of smoothly varying density (0.1 .. 1.9), albedo 0.8, HG g = -0.5 (q = 0.39
    // toward this sun), lit by an oblique sun. Reference: marched single scattering at 1/8
    // voxel (O(h²) bias, well below the statistics here), averaged over 64 jitter offsets.
    constexpr int n = 24;
    DenseVoxels v;
    v.dims = IVec3(n);
    v.values.resize(static_cast<size_t>(n) * n * n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                v.values[x + n * (y + n * z)] =
                    1.0f + 0.9f * std::sin(0.7f * x) * std::cos(0.45f * y + 0.3f * z);
    const std::string path = test::temp_grid_path("nee_roulette_hetero");
    write_fog_volume(path, "density", v, 0.1, Vec3(0.0f));
    const MediumSet grid({test::vdb_medium(
        path,
        {{"density_scale", 2.0}, {"albedo", 0.8}, {"phase", {{"model", "hg"}, {"g", -0.5}}}})});
    const std::vector<Light> sun{
        Light{"sun", DirectionalLight{glm::normalize(Vec3(-0.3f, -1.0f, 0.4f)), Rgb(3.0f)}}};
    const Ray ray{Vec3(-1.0f, 1.1f, 0.9f), glm::normalize(Vec3(1.0f, 0.1f, 0.15f)), 0.0f,
                  kInfinity};
    VolumeSettings march;
    march.estimator = Estimator::March;
    march.step_voxels = 0.125f;
    const MeanAndError reference = mean_over_streams(64, 31, [&](Pcg32& rng) {
        VolumeCounters counters;
        return integrate_media(grid, sun, nullptr, nullptr, ray, march, true, rng, counters)
            .radiance.g;
    });
    ASSERT_GT(reference.mean, 0.0);
    for (const int k : {0, 4}) {
        const VolumeSettings s = tracker(VolumeIntegrator::Single, true, k);
        const MeanAndError l = mean_over_streams(160000, 31, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(grid, sun, nullptr, nullptr, ray, s, true, rng, counters)
                .radiance.g;
        });
        const double se = std::hypot(l.stderr_, reference.stderr_);
        EXPECT_NEAR(l.mean, reference.mean, 4.0 * se + 1e-3 * reference.mean) << "nee_points " << k;
        EXPECT_LT(4.0 * se, 0.04 * reference.mean) << "nee_points " << k;
        std::printf("nee_points %d: %.6g +- %.2g, march %.6g +- %.2g\n", k, l.mean, l.stderr_,
                    reference.mean, reference.stderr_);
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
