// Unbiased ray-marching transmittance (volume/unbiased_march.h) and its debiasing series
// (volume/debiased_exp.h): exact with zero variance on a constant box, unbiased against a fine
// deterministic march on heterogeneous grids (with teeth: a 2% bias fails), finite for optical
// depths 1e-8..1e4. False failures: each 4-standard-error check about 6e-5; stated per test.
// Checked to fail (2026-12-04): a 2% factor planted in the estimate fails every mean test, and
// so does dropping the series' corrections (the plain jittered march, ~1% Jensen bias here).
#include "volume/unbiased_march.h"
#include "core/rng.h"
#include "tests/sample_mean.h"
#include "tests/volume/smooth_cloud.h"
#include "volume/debiased_exp.h"
#include "volume/grid/density_grid.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace kasumi {
namespace {

TEST(DebiasedExp, RouletteMatchesItsStatedLaw) {
    EXPECT_DOUBLE_EQ(series_order_survival(0), 1.0);
    EXPECT_DOUBLE_EQ(series_order_survival(1), 0.1);
    EXPECT_DOUBLE_EQ(series_order_survival(2), 0.1);
    EXPECT_DOUBLE_EQ(series_order_survival(3), 0.1 * 2.0 / 3.0);
    // E[N] = 0.1 (2 + sum_{k >= 3} 2^(k-2) / (k! / 2)) = 0.1 (2 + (e² - 5) / 2).
    EXPECT_NEAR(expected_series_order(), 0.1 * (2.0 + (std::exp(2.0) - 5.0) / 2.0), 1e-12);
    // Inversion: the frequency of N >= k over a fine uniform grid of u is P(N >= k).
    constexpr int kU = 1 << 20;
    std::vector<int> at_least(8, 0);
    for (int i = 0; i < kU; ++i) {
        const int n = sample_series_order((i + 0.5f) / kU);
        for (int k = 0; k < 8 && k <= n; ++k)
            ++at_least[k];
    }
    for (int k = 0; k < 8; ++k)
        EXPECT_NEAR(static_cast<double>(at_least[k]) / kU, series_order_survival(k), 2.0 / kU)
            << "k = " << k;
}

TEST(DebiasedExp, EqualEstimatesGiveTheirExponentialExactly) {
    for (int n = 0; n < 6; ++n) {
        const std::vector<DVec3> tau(n + 1, DVec3(0.3, 7.0, 40.0));
        const DVec3 t = debiased_exp(tau);
        EXPECT_NEAR(t.x, std::exp(-0.3), 1e-15);
        EXPECT_NEAR(t.y, std::exp(-7.0), 1e-18);
        EXPECT_NEAR(t.z, std::exp(-40.0), 1e-30);
    }
}

TEST(DebiasedExp, UnbiasedForNoisyDepthEstimates) {
    // tau^ = tau + a (2u - 1): independent, unbiased. The mean of the debiased exp over many
    // streams is exp(-tau) within 4 standard errors, and the error is small enough that a 2%
    // bias would fail. One check per (tau, a): false failure about 6e-5 each.
    for (const double tau : {0.1, 1.0, 4.0}) {
        for (const double a : {0.2, 1.0}) {
            const MeanAndError m = mean_over_streams(400000, 5, [&](Pcg32& rng) {
                std::vector<DVec3> tau_hat(sample_series_order(rng.next_float()) + 1);
                for (DVec3& t : tau_hat)
                    t = DVec3(tau + a * (2.0 * rng.next_float() - 1.0));
                return debiased_exp(tau_hat).x;
            });
            const double exact = std::exp(-tau);
            EXPECT_NEAR(m.mean, exact, 4.0 * m.stderr_) << "tau " << tau << " a " << a;
            EXPECT_LT(4.0 * m.stderr_, 0.02 * exact) << "tau " << tau << " a " << a;
        }
    }
}

TEST(DebiasedExp, InfiniteDepthIsZeroNotNaN) {
    const std::vector<DVec3> tau{DVec3(HUGE_VAL, 1.0, 2e4), DVec3(HUGE_VAL, 1.5, 1e4)};
    const DVec3 t = debiased_exp(tau);
    EXPECT_EQ(t.x, 0.0);
    EXPECT_TRUE(std::isfinite(t.y));
    EXPECT_EQ(t.z, 0.0);
}

using test::constant_grid;
using test::grid_media;
using test::smooth_cloud;

Rgb one_estimate(const MediumSet& media, const Ray& ray, Estimator e, float step, uint64_t seed,
                 uint64_t stream) {
    Pcg32 rng(seed, stream);
    VolumeCounters counters;
    return estimate_transmittance(media, ray, e, step, rng, counters);
}

/// The 1/64-voxel march: deterministic up to its O(h²) error, far below the noise here.
double fine_march(const MediumSet& media, const Ray& ray) {
    return one_estimate(media, ray, Estimator::March, 1.0f / 64.0f, 1, 1).r;
}

MeanAndError unbiased_mean(const MediumSet& media, const Ray& ray, int n, uint64_t seed) {
    return mean_over_streams(n, seed, [&](Pcg32& rng) {
        VolumeCounters counters;
        return static_cast<double>(
            estimate_transmittance(media, ray, Estimator::UnbiasedMarch, 0.0f, rng, counters).r);
    });
}

TEST(UnbiasedMarch, ConstantBoxIsExactWithZeroVariance) {
    // Voxels 0..24 all 1, the box [0.5, 15.5]³: the rays cross only bricks whose bounds meet.
    const auto grid = constant_grid();
    for (const float sigma_t : {0.01f, 0.1f, 1.0f}) {
        const MediumSet media = grid_media(grid, sigma_t, Bounds3{Vec3(0.5f), Vec3(15.5f)});
        const Ray ray{Vec3(-2.0f, 3.3f, 7.1f), Vec3(1.0f, 0.0f, 0.0f), 0.0f, 30.0f};
        const double exact = std::exp(-15.0 * sigma_t);
        for (uint64_t i = 0; i < 200; ++i) {
            const Rgb t = one_estimate(media, ray, Estimator::UnbiasedMarch, 0.0f, 3, i);
            ASSERT_NEAR(t.r, exact, 2e-6 * exact) << "sigma_t " << sigma_t << " stream " << i;
            ASSERT_EQ(t.r, t.g);
        }
    }
}

TEST(UnbiasedMarch, MatchesAFineMarchOnASmoothCloud) {
    // Four rays (through the centre, grazing, starting inside, through the constant block):
    // within 4 standard errors of the 1/64-voxel march, and with teeth: 4 standard errors are
    // below 2% of the transmittance, so a 2% bias would fail. False failure ~6e-5 per ray.
    const MediumSet media = grid_media(smooth_cloud(), 0.07f, Bounds3{Vec3(0.0f), Vec3(39.0f)});
    const Ray rays[] = {
        {Vec3(-5.0f, 19.3f, 20.7f), glm::normalize(Vec3(1.0f, 0.05f, -0.02f)), 0.0f, 60.0f},
        {Vec3(-5.0f, 31.0f, 8.0f), glm::normalize(Vec3(1.0f, 0.1f, 0.3f)), 0.0f, 60.0f},
        {Vec3(20.2f, 21.1f, 19.4f), glm::normalize(Vec3(0.2f, -1.0f, 0.4f)), 0.5f, 30.0f},
        {Vec3(-1.0f, 2.0f, 3.0f), glm::normalize(Vec3(1.0f, 0.9f, 0.8f)), 0.0f, 60.0f},
    };
    for (const Ray& ray : rays) {
        const double reference = fine_march(media, ray);
        ASSERT_GT(reference, 0.01);
        ASSERT_LT(reference, 0.95);
        const MeanAndError m = unbiased_mean(media, ray, 20000, 7);
        EXPECT_NEAR(m.mean, reference, 4.0 * m.stderr_);
        EXPECT_LT(4.0 * m.stderr_, 0.02 * reference);
    }
}

TEST(UnbiasedMarch, MeanHoldsOverManyRaysAndSeeds) {
    // 48 random rays through the cloud, each its own seed: the pooled z-score
    // sum(z) / sqrt(48) of the means against the fine march is within 4 (a common bias of a
    // fraction of the per-ray error shows here), and mean(z²) < 2 (the standard errors are
    // honest; a chi-square with 48 degrees of freedom exceeds 96 with probability ~4e-5).
    const MediumSet media = grid_media(smooth_cloud(), 0.1f, Bounds3{Vec3(0.0f), Vec3(39.0f)});
    Pcg32 rays(11, 0);
    double z_sum = 0.0, z2_sum = 0.0;
    int k = 0;
    while (k < 48) {
        const Vec3 a = Vec3(rays.next_float(), rays.next_float(), rays.next_float()) * 39.0f;
        const Vec3 b = Vec3(rays.next_float(), rays.next_float(), rays.next_float()) * 39.0f;
        const Ray ray{a, glm::normalize(b - a), 0.0f, glm::length(b - a)};
        const double reference = fine_march(media, ray);
        if (!(reference < 0.98))
            continue;  // rays that miss the cloud test nothing
        const MeanAndError m = unbiased_mean(media, ray, 2000, 100 + k);
        ASSERT_GT(m.stderr_, 0.0);
        const double z = (m.mean - reference) / m.stderr_;
        z_sum += z;
        z2_sum += z * z;
        ++k;
    }
    EXPECT_LT(std::abs(z_sum / std::sqrt(48.0)), 4.0);
    EXPECT_LT(z2_sum / 48.0, 2.0);
}

TEST(UnbiasedMarch, ExtremeOpticalDepthsStayFiniteAndConsistent) {
    // The same ray with sigma_t per density from 1e-9 to 1e3: optical depths ~1e-8 to ~1e4.
    // Every estimate finite; the mean within 4 standard errors (+ float resolution) of the fine
    // march, which lies in [0, 1].
    const auto cloud = smooth_cloud();
    const Ray ray{Vec3(-5.0f, 19.3f, 20.7f), glm::normalize(Vec3(1.0f, 0.05f, -0.02f)), 0.0f,
                  60.0f};
    for (const float sigma_t : {1e-9f, 1e-5f, 1e-2f, 1.0f, 10.0f, 1e3f}) {
        const MediumSet media = grid_media(cloud, sigma_t, Bounds3{Vec3(0.0f), Vec3(39.0f)});
        const double reference = fine_march(media, ray);
        SampleMean m;
        for (uint64_t i = 0; i < 2000; ++i) {
            const Rgb t = one_estimate(media, ray, Estimator::UnbiasedMarch, 0.0f, 9, i);
            ASSERT_TRUE(std::isfinite(t.r) && std::isfinite(t.g) && std::isfinite(t.b))
                << "sigma_t " << sigma_t;
            m.add(t.r);
        }
        const MeanAndError r = m.result();
        EXPECT_NEAR(r.mean, reference, 4.0 * r.stderr_ + 1e-6) << "sigma_t " << sigma_t;
        EXPECT_GE(r.mean, -1e-6);
        EXPECT_LE(r.mean, 1.0 + 1e-6);
    }
}

TEST(UnbiasedMarch, NodeCountGrowsWithTheResidualDepth) {
    EXPECT_EQ(unbiased_march_nodes(0.0), 1);
    EXPECT_LT(unbiased_march_nodes(1.0), unbiased_march_nodes(10.0));
    EXPECT_LT(unbiased_march_nodes(10.0), unbiased_march_nodes(100.0));
    EXPECT_EQ(unbiased_march_nodes(1e9), kMaxMarchNodes);
    EXPECT_EQ(unbiased_march_nodes(HUGE_VAL), kMaxMarchNodes);
}

}  // namespace
}  // namespace kasumi
