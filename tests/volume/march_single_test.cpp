// Marched single scattering through a grid (`march` + `single`, volume/march_single.cpp) against
// a quadrature of the exact integral, with the light's transmittance from the light cache (the
// fast path: one grid, directional lights, one exp per node) and from shadow marches (the
// general path).
//
// A constant block of n³ voxels ramps to 0 over one voxel outside each face: along a line
// parallel to an axis, away from the block's edges, the density is the 1D profile
// r(s) = s + 1 on [-1, 0], 1 on [0, n - 1], n - s on [n - 1, n] (trilinear = product of such
// profiles). A camera ray along +x at height y0 under a light shining straight down (toward the
// light: +y) sees, per unit length,
//   sigma_s r(x) p E exp(-sigma_t R(x)) exp(-sigma_t r(x) (n - 1/2 - y0)),  R(x) = int_-1^x r,
// as the light's way up through the block holds density r(x) r(y) with int_y0^n r(y) dy =
// n - 1/2 - y0. The reference integrates each smooth piece by Simpson's rule (4000 intervals:
// error ~1e-12 relative). The march has a jittered node grid and trapezoid optical depths: for a
// piecewise-linear density both errors come from the four kinks and are O(h²) for every jitter,
// so the largest error over 64 jitters must fall at order >= 1.5 as the step halves from one
// voxel (2 in theory; from 2 voxels to 1 the order is still 1.3-1.6) and stay below 2e-3
// relative at an eighth of a voxel. Deterministic (fixed seeds): no false failures.
#include "tests/volume/vdb_test_grids.h"
#include "volume/volume_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

constexpr int kN = 32;
constexpr float kSigmaT = 0.08f;  // per unit density, 1/m (voxel 1 m)
constexpr float kAlbedo = 0.8f;
constexpr float kY0 = 15.3f, kZ0 = 16.2f;
constexpr float kLux = 2.0f;

double profile(double s) {
    if (s <= -1.0 || s >= kN)
        return 0.0;
    if (s < 0.0)
        return s + 1.0;
    if (s > kN - 1)
        return kN - s;
    return 1.0;
}

double cumulative(double s) {  // int_-1^s r
    if (s <= -1.0)
        return 0.0;
    if (s < 0.0)
        return 0.5 * (s + 1.0) * (s + 1.0);
    if (s <= kN - 1)
        return 0.5 + s;
    if (s < kN)
        return 0.5 + (kN - 1) + 0.5 * (1.0 - (kN - s) * (kN - s));
    return kN;
}

double reference_radiance(float light_depth_density) {
    const double sigma_s = kSigmaT * kAlbedo;
    const auto f = [&](double x) {
        return sigma_s * profile(x) * (kLux / (4.0 * kPi)) * std::exp(-kSigmaT * cumulative(x)) *
               std::exp(-kSigmaT * profile(x) * light_depth_density);
    };
    double total = 0.0;
    const double pieces[][2] = {{-1.0, 0.0}, {0.0, kN - 1.0}, {kN - 1.0, double(kN)}};
    for (const auto& p : pieces) {
        const int m = 4000;  // even
        const double h = (p[1] - p[0]) / m;
        double s = f(p[0]) + f(p[1]);
        for (int i = 1; i < m; ++i)
            s += (i % 2 ? 4.0 : 2.0) * f(p[0] + i * h);
        total += s * h / 3.0;
    }
    return total;
}

struct Fixture {
    Medium medium;
    MediumSet media;
    std::vector<Light> sun;
    Ray ray;
    Fixture()
        : medium(test::vdb_medium(test::write_box("march_single_block", kN, 1.0f, 1.0),
                                  {{"density_scale", kSigmaT}, {"albedo", kAlbedo}})),
          media({medium}),
          sun{Light{"sun", DirectionalLight{Vec3(0, -1, 0), Rgb(kLux)}}},
          ray{Vec3(-8.0f, kY0, kZ0), Vec3(1, 0, 0), 0.0f, kInfinity} {}
};

VolumeSettings march_settings(float step_voxels, bool light_cache) {
    VolumeSettings s;
    s.estimator = Estimator::March;
    s.integrator = VolumeIntegrator::Single;
    s.step_voxels = step_voxels;
    s.light_cache = light_cache;
    return s;
}

class MarchedSingle : public ::testing::TestWithParam<bool> {};

TEST_P(MarchedSingle, ConstantBlockConvergesToTheIntegralAtOrderTwo) {
    const bool light_cache = GetParam();
    const Fixture fx;
    const double expected = reference_radiance(kN - 0.5f - kY0);
    const double expected_t = std::exp(-kSigmaT * double(kN));
    double previous = 0.0;
    for (float step : {1.0f, 0.5f, 0.25f, 0.125f}) {
        const VolumeSettings settings = march_settings(step, light_cache);
        double worst = 0.0, worst_t = 0.0;
        VolumeCounters counters;
        for (uint64_t seed = 0; seed < 64; ++seed) {
            Pcg32 rng(seed, 7u);
            const VolumeResult r = integrate_media(fx.media, fx.sun, nullptr, nullptr, fx.ray,
                                                   settings, true, rng, counters);
            ASSERT_EQ(r.radiance.r, r.radiance.b);
            worst = std::max(worst, std::abs(r.radiance.g - expected) / expected);
            worst_t = std::max(worst_t, std::abs(r.transmittance.g - expected_t) / expected_t);
        }
        EXPECT_GT(counters.steps, 0u);
        // Optical depth by the trapezoid rule: exact between kinks; across a kink where the
        // slope changes by 1 (density per voxel) its error is a (h - a) / 2 <= h²/8 for a node
        // a voxels before it. Four kinks: |tau error| <= sigma_t h²/2, T's relative error too.
        EXPECT_LT(worst_t, 0.5 * kSigmaT * step * step * 1.001) << "step " << step;
        std::printf("step %.2f voxels: largest relative error %.3g (radiance), %.3g (T)\n",
                    static_cast<double>(step), worst, worst_t);
        if (previous > 0.0) {
            EXPECT_LT(worst, previous * std::pow(0.5, 1.5))
                << "step " << step << " (previous step's error " << previous << ")";
        }
        previous = worst;
    }
    EXPECT_LT(previous, 2e-3) << "at an eighth of a voxel";
}

INSTANTIATE_TEST_SUITE_P(LightTransmittance, MarchedSingle, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& i) {
                             return i.param ? std::string("Cached") : std::string("Marched");
                         });

// Two directional lights in one march (the fast path keeps one weight and one exp per light):
// the result is the sum of each light alone for the same jitter (same seed), and the camera
// transmittance does not depend on the lights. Deterministic. (A set caches each light index's
// transmittance once: every light list gets its own set.)
TEST(MarchedSingle, TwoCachedLightsAddUp) {
    const Light a{"a", DirectionalLight{Vec3(0, -1, 0), Rgb(kLux)}};
    const Light b{"b", DirectionalLight{glm::normalize(Vec3(0.3f, -1.0f, 0.4f)), Rgb(0.5f)}};
    const VolumeSettings settings = march_settings(1.5f, true);
    VolumeCounters counters;
    const auto run = [&](const std::vector<Light>& lights) {
        const Fixture fx;
        Pcg32 rng(11u, 3u);
        return integrate_media(fx.media, lights, nullptr, nullptr, fx.ray, settings, true, rng,
                               counters);
    };
    const VolumeResult both = run({a, b}), only_a = run({a}), only_b = run({b});
    EXPECT_GT(only_b.radiance.g, 0.0f);
    EXPECT_NEAR(both.radiance.g, only_a.radiance.g + only_b.radiance.g, 1e-5f * both.radiance.g);
    EXPECT_EQ(both.transmittance.g, only_a.transmittance.g);
}

}  // namespace
}  // namespace kasumi
