/// Stratified and adaptive light samples (lights/light_samples.h): the Owen-scrambled Sobol
/// points form (0, m, 2)-nets and are uniform over the scramble; the sphere light's sampler
/// has a normalised pdf and, with stratified samples, reproduces the closed-form irradiance
/// E = π L sin²α and the exact penumbra behind an occluder's edge, with error falling faster
/// than 1/√N; the adaptive probe rule's bias on a thin occluder vanishes as probes → samples.
/// Fixed seeds; false-failure rates are stated per check for a fresh seed.
#include "lights/light_samples.h"
#include "core/rng.h"
#include "light_test_util.h"
#include "lights/sphere_light.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

namespace kasumi {
namespace {

TEST(LightSamples, FirstPowerOfTwoPointsAreZeroMTwoNets) {
    // Deterministic: every elementary interval of area 2^-m holds exactly one of the first 2^m
    // points (and of the next aligned block), for any scramble.
    Pcg32 rng(3, 5);
    for (int trial = 0; trial < 20; ++trial) {
        const StratifiedLightSamples u(rng);
        for (int m = 0; m <= 8; ++m) {
            const int n = 1 << m;
            for (int block = 0; block < 2; ++block) {
                for (int a = 0; a <= m; ++a) {
                    const int nx = 1 << a, ny = 1 << (m - a);
                    std::vector<int> count(n, 0);
                    for (int k = 0; k < n; ++k) {
                        const Vec2 p = u[block * n + k];
                        ASSERT_GE(p.x, 0.0f);
                        ASSERT_LT(p.x, 1.0f);
                        ASSERT_GE(p.y, 0.0f);
                        ASSERT_LT(p.y, 1.0f);
                        const int i = static_cast<int>(p.x * nx), j = static_cast<int>(p.y * ny);
                        ++count[j * nx + i];
                    }
                    for (int c : count)
                        ASSERT_EQ(c, 1) << "m " << m << " a " << a << " block " << block;
                }
            }
        }
    }
}

TEST(LightSamples, EachPointIsUniformOverTheScramble) {
    // Point k of independently scrambled sequences, binned 8 x 8: chi-square with 63 degrees
    // of freedom, three points tested, each at a threshold giving a 1e-4 joint false-failure
    // rate.
    const double threshold = 1.0 - std::pow(1.0 - 1e-4, 1.0 / 3.0);
    for (int k : {0, 5, 13}) {
        Pcg32 rng(17, static_cast<uint64_t>(k));
        const int trials = 64000, bins = 8;
        std::vector<double> observed(bins * bins, 0.0);
        const std::vector<double> expected(bins * bins,
                                           static_cast<double>(trials) / (bins * bins));
        for (int t = 0; t < trials; ++t) {
            const Vec2 p = StratifiedLightSamples(rng)[k];
            observed[static_cast<int>(p.y * bins) * bins + static_cast<int>(p.x * bins)] += 1.0;
        }
        EXPECT_GT(test::chi_square_p_value(observed, expected), threshold) << "point " << k;
    }
}

TEST(LightSamples, SpherePdfIntegratesToOne) {
    // Midpoint quadrature of the pdf over the whole sphere of directions (z, φ grid about an
    // axis unrelated to the light's): the cone's rim cuts cells, an O(1/n) error.
    const SphereLight light{Vec3(1.0f, 2.0f, 0.5f), 0.9f, Rgb(1.0f)};
    for (const Vec3& p : {Vec3(0.0f), Vec3(3.0f, -4.0f, 2.0f), Vec3(0.9f, 1.0f, 0.5f)}) {
        const int nz = 4000, nphi = 4000;
        double sum = 0.0;
        for (int i = 0; i < nz; ++i) {
            const double z = -1.0 + 2.0 * (i + 0.5) / nz;
            const double r = std::sqrt(1.0 - z * z);
            for (int j = 0; j < nphi; ++j) {
                const double phi = 2.0 * kPiD * (j + 0.5) / nphi;
                const Vec3 w(static_cast<float>(r * std::cos(phi)),
                             static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
                sum += sample_pdf(light, p, w);
            }
        }
        EXPECT_NEAR(sum * 4.0 * kPiD / (double(nz) * nphi), 1.0, 2e-3);
    }
    // Outside the cone and from inside the sphere the density is 0.
    EXPECT_EQ(sample_pdf(light, Vec3(0.0f), Vec3(0, -1, 0)), 0.0f);
    EXPECT_EQ(sample_pdf(light, light.center, Vec3(0, 1, 0)), 0.0f);
}

/// One shading point's estimate of the shadowed illuminance of a sphere light with `samples`
/// stratified samples: the plain mean of E_k cos θ_k V_k (unbiased), or with the adaptive rule.
struct Estimate {
    double mean;   ///< Σ_k E_k cos θ_k V_k / (samples taken)
    double ratio;  ///< E × Σ_k cos θ_k V_k E_k / Σ_k cos θ_k E_k: shade_surface's estimator
    int taken;
};

Estimate estimate(const SphereLight& light, const Vec3& p, const Vec3& n, int samples, int probes,
                  const StratifiedLightSamples& u, const test::Visibility& visible) {
    ProbeRule rule(samples, probes);
    double lit = 0.0, all = 0.0;
    int k = 0;
    while (k < samples) {
        const IncidentLight in = sample_incident(light, p, u[k]);
        const double c = std::max(0.0f, glm::dot(n, in.wi));
        LightSampleOutcome outcome = LightSampleOutcome::Ignored;
        if (c > 0.0) {
            const double e = luminance(in.irradiance) * c;
            all += e;
            const bool v = visible(p, in.light_position);
            lit += v ? e : 0.0;
            outcome = v ? LightSampleOutcome::Lit : LightSampleOutcome::Blocked;
        }
        ++k;
        if (rule.record(k - 1, outcome))
            break;
    }
    const double exact_unshadowed = luminance(unshadowed_irradiance(light, p, n));
    return {lit / k, all > 0.0 ? exact_unshadowed * lit / all : 0.0, k};
}

const SphereLight kLamp{Vec3(0.0f, 4.0f, 0.0f), 0.5f, Rgb(100.0f)};
const Vec3 kUp(0.0f, 1.0f, 0.0f);

TEST(LightSamples, StratifiedUnshadowedIrradianceIsPiLSin2Alpha) {
    // No occluder, receiver facing the light: E = π L sin²α exactly (L = 100, sin α = 0.5/4).
    // Each stratified estimate is within 0.5% of it (deterministic bound for this cone: the
    // cos θ weight varies by < 1.6% over it), and the mean over 4000 scrambles is within 5
    // standard errors (two-sided normal tail 5.7e-7).
    const double expected = kPiD * 100.0 * (0.125 * 0.125);
    const test::Visibility always = [](const Vec3&, const Vec3&) { return true; };
    Pcg32 rng(9, 1);
    double sum = 0.0, sum_sq = 0.0;
    const int trials = 4000;
    for (int t = 0; t < trials; ++t) {
        const double e =
            estimate(kLamp, Vec3(0.0f), kUp, 16, 0, StratifiedLightSamples(rng), always).mean;
        ASSERT_NEAR(e, expected, 5e-3 * expected);
        sum += e;
        sum_sq += e * e;
    }
    const double mean = sum / trials;
    const double se = std::sqrt(std::max(0.0, sum_sq / trials - mean * mean) / (trials - 1));
    EXPECT_LT(std::abs(mean - expected), 5.0 * se + 1e-6 * expected);
    EXPECT_NEAR(luminance(unshadowed_irradiance(kLamp, Vec3(0.0f), kUp)), expected,
                1e-6 * expected);
}

/// Mean and RMSE of the plain estimator over `trials` scrambles, against `exact`.
struct Stats {
    double bias, se, rmse;
};
Stats stats(const Vec3& p, int samples, int probes, int trials, uint64_t seed, double exact,
            const test::Visibility& visible, bool ratio = false) {
    Pcg32 rng(seed, 3);
    double sum = 0.0, sum_sq = 0.0, sq_err = 0.0;
    for (int t = 0; t < trials; ++t) {
        const Estimate e =
            estimate(kLamp, p, kUp, samples, probes, StratifiedLightSamples(rng), visible);
        const double x = ratio ? e.ratio : e.mean;
        sum += x;
        sum_sq += x * x;
        sq_err += (x - exact) * (x - exact);
    }
    const double mean = sum / trials;
    return {mean - exact, std::sqrt(std::max(0.0, sum_sq / trials - mean * mean) / (trials - 1)),
            std::sqrt(sq_err / trials)};
}

TEST(LightSamples, PenumbraProfileMatchesTheExactVisibleFraction) {
    // Floor points across the penumbra of the half-plane's edge (from full shadow to full
    // light: the penumbra spans |x| < 0.25 m here). Unbiased: the mean of 16-sample estimates
    // over 2000 scrambles is within 5 standard errors of the quadrature (5.7e-7 per point, 7
    // points). Faster than 1/√N: from 16 to 256 samples the RMSE summed over the profile falls
    // by more than 5.5x (1/√N gives 4; Owen-scrambled nets give 16^(3/4) = 8 for a smooth
    // edge); the RMSE estimates from 2000 trials are good to a few per cent.
    const test::Visibility visible = test::past_edge;
    double rmse16 = 0.0, rmse256 = 0.0;
    for (float x : {-0.3f, -0.2f, -0.1f, 0.0f, 0.1f, 0.2f, 0.3f}) {
        const Vec3 p(x, 0.0f, 0.0f);
        const double exact = test::sphere_quadrature(kLamp, p, kUp, visible, 2000);
        const double unshadowed = luminance(unshadowed_irradiance(kLamp, p, kUp));
        ASSERT_LE(exact, unshadowed * (1.0 + 1e-4));
        const Stats s16 = stats(p, 16, 0, 2000, 21, exact, visible);
        EXPECT_LT(std::abs(s16.bias), 5.0 * s16.se + 1e-4 * unshadowed)
            << "x " << x << " exact " << exact << " bias " << s16.bias;
        const Stats s256 = stats(p, 256, 0, 2000, 22, exact, visible);
        rmse16 += s16.rmse;
        rmse256 += s256.rmse;
        // The ratio estimator of shade_surface: biased by O(1/N), small next to the noise.
        const Stats r16 = stats(p, 16, 0, 2000, 23, exact, visible, true);
        EXPECT_LT(std::abs(r16.bias), 0.01 * unshadowed) << "ratio estimator, x " << x;
    }
    std::printf("penumbra RMSE summed over 7 points: 16 samples %.4g, 256 samples %.4g\n", rmse16,
                rmse256);
    EXPECT_GT(rmse16 / rmse256, 5.5) << "RMSE 16: " << rmse16 << " 256: " << rmse256;
}

TEST(LightSamples, AdaptiveProbesConvergeAsTheyTighten) {
    // A thin bar (y = 2, |x − 0.05| < 0.02, far narrower than the light's 0.25 m shadow-space
    // width) casts a faint partial shadow that a few probes often miss. With 64 samples, the
    // bias of the adaptive estimate (mean over 4000 scrambles minus the exact value) must shrink
    // as probes grow: it is at least 10 standard errors at 2 probes (the rule is biased) and
    // within 5 standard errors of 0 at 64 probes (the plain estimator). Probes must also save
    // work where the light is fully visible: all 4 probes agree, so 4 samples are taken.
    const test::Visibility bar = [](const Vec3& p, const Vec3& target) {
        const float t = (2.0f - p.y) / (target.y - p.y);
        return std::abs(p.x + t * (target.x - p.x) - 0.05f) >= 0.02f;
    };
    const Vec3 p(0.0f, 0.0f, 0.0f);
    const double exact = test::sphere_quadrature(kLamp, p, kUp, bar, 2000);
    const double unshadowed = luminance(unshadowed_irradiance(kLamp, p, kUp));
    ASSERT_LT(exact, 0.95 * unshadowed);
    std::vector<double> bias;
    for (int probes : {2, 4, 8, 16, 64}) {
        const Stats s = stats(p, 64, probes, 4000, 40 + probes, exact, bar);
        bias.push_back(std::abs(s.bias));
        if (probes == 2) {
            EXPECT_GT(s.bias, 10.0 * s.se) << "2 probes: bias " << s.bias << " se " << s.se;
        }
        if (probes == 64) {
            EXPECT_LT(std::abs(s.bias), 5.0 * s.se + 1e-6 * exact);
        }
        std::printf("probes %d: bias %.4g (%.3g of exact) se %.3g\n", probes, s.bias,
                    s.bias / exact, s.se);
    }
    for (size_t i = 1; i < bias.size(); ++i)
        EXPECT_LE(bias[i], bias[i - 1] * 1.05 + 1e-3 * exact) << "probes step " << i;
    const test::Visibility always = [](const Vec3&, const Vec3&) { return true; };
    Pcg32 rng(5, 5);
    EXPECT_EQ(estimate(kLamp, p, kUp, 64, 4, StratifiedLightSamples(rng), always).taken, 4);
}

}  // namespace
}  // namespace kasumi
