// Ratio tracking for in-scattering with next-event estimation at several collisions per path
// segment (render.volume.nee_points, volume/volume_path.cpp) against exact answers: a
// homogeneous box lit by a sun (closed form), a heterogeneous grid against a fine march, and
// the white furnace for multiple scattering. Statistical assertions at 4 standard errors
// (two-sided Gaussian false-failure rate 6e-5 each; fixed seeds, so a pass is reproducible).
#include "tests/sample_mean.h"
#include "vdb_test_grids.h"
#include "volume/volume_path.h"
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
    // A box [-1, 1]³ of sigma_s = 2, sigma_a = 0.5 per metre, isotropic, lit from +y by a sun
    // of irradiance 1; a camera ray along +x at height y0 crosses it over 2 m, and every point
    // of it is 1 - y0 below the top face, so
    //   L = sigma_s / (4 pi) exp(-sigma_t (1 - y0)) (1 - exp(-2 sigma_t)) / sigma_t,
    //   T = exp(-2 sigma_t).
    const float sigma_s = 2.0f, sigma_a = 0.5f, sigma_t = sigma_s + sigma_a, y0 = 0.2f;
    const MediumSet box(
        {Medium{"box", HomogeneousMedium{Bounds3{Vec3(-1.0f), Vec3(1.0f)}, Rgb(sigma_a),
                                         Rgb(sigma_s), Isotropic{}}}});
    const std::vector<Light> sun{Light{"sun", DirectionalLight{Vec3(0, -1, 0), Rgb(1.0f)}}};
    const Ray ray{Vec3(-3.0f, y0, 0.1f), Vec3(1, 0, 0), 0.0f, kInfinity};
    const double expected_l = sigma_s / (4.0 * kPiD) * std::exp(-sigma_t * (1.0 - y0)) *
                              (1.0 - std::exp(-2.0 * sigma_t)) / sigma_t;
    const double expected_t = std::exp(-2.0 * sigma_t);
    for (const int k : {1, 4}) {
        const VolumeSettings s = tracked(VolumeIntegrator::Single, k);
        const Mean l = average(160000, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(box, sun, nullptr, nullptr, ray, s, true, rng, counters)
                .radiance.g;
        });
        EXPECT_NEAR(l.mean, expected_l, 4.0 * l.stderr_) << "nee_points " << k;
        EXPECT_LT(4.0 * l.stderr_, 0.015 * expected_l) << "nee_points " << k;  // has teeth
        const Mean t = average(40000, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(box, sun, nullptr, nullptr, ray, s, true, rng, counters)
                .transmittance.g;
        });
        // Constant box: the ratio factors are 1; only the roulette below T^ = 0.05 adds noise.
        EXPECT_NEAR(t.mean, expected_t, 4.0 * t.stderr_ + 1e-7) << "nee_points " << k;
        EXPECT_LT(4.0 * t.stderr_, 0.05 * expected_t) << "nee_points " << k;
    }
}

TEST(TrackedInScattering, HeterogeneousGridMatchesAFineMarch) {
    // A 24³ grid of smoothly varying density (0.1 .. 1.9), albedo 0.8, HG g = 0.5, lit by an
    // oblique sun. Reference: marched single scattering at 1/8 voxel (O(h²) bias, well below
    // the statistics here), averaged over 64 jitter offsets.
    constexpr int n = 24;
    DenseVoxels v;
    v.dims = IVec3(n);
    v.values.resize(static_cast<size_t>(n) * n * n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                v.values[x + n * (y + n * z)] =
                    1.0f + 0.9f * std::sin(0.7f * x) * std::cos(0.45f * y + 0.3f * z);
    const std::string path = test::temp_grid_path("tracked_hetero");
    write_fog_volume(path, "density", v, 0.1, Vec3(0.0f));
    const MediumSet grid({test::vdb_medium(
        path,
        {{"density_scale", 2.0}, {"albedo", 0.8}, {"phase", {{"model", "hg"}, {"g", 0.5}}}})});
    const std::vector<Light> sun{
        Light{"sun", DirectionalLight{glm::normalize(Vec3(-0.3f, -1.0f, 0.4f)), Rgb(3.0f)}}};
    const Ray ray{Vec3(-1.0f, 1.1f, 0.9f), glm::normalize(Vec3(1.0f, 0.1f, 0.15f)), 0.0f,
                  kInfinity};
    VolumeSettings march;
    march.estimator = Estimator::March;
    march.step_voxels = 0.125f;
    const Mean reference = average(64, [&](Pcg32& rng) {
        VolumeCounters counters;
        return integrate_media(grid, sun, nullptr, nullptr, ray, march, true, rng, counters)
            .radiance.g;
    });
    ASSERT_GT(reference.mean, 0.0);
    for (const int k : {1, 4}) {
        const VolumeSettings s = tracked(VolumeIntegrator::Single, k);
        const Mean l = average(160000, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(grid, sun, nullptr, nullptr, ray, s, true, rng, counters)
                .radiance.g;
        });
        const double se = std::hypot(l.stderr_, reference.stderr_);
        EXPECT_NEAR(l.mean, reference.mean, 4.0 * se + 1e-3 * reference.mean) << "nee_points " << k;
        EXPECT_LT(4.0 * se, 0.03 * reference.mean) << "nee_points " << k;
        std::printf("nee_points %d: %.6g +- %.2g, march %.6g +- %.2g\n", k, l.mean, l.stderr_,
                    reference.mean, reference.stderr_);
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
