// Spectral-MIS free flights (volume/spectral_mis_flight.h) in a chromatic homogeneous slab
// against the closed forms per channel: the escape weight's mean is exp(-sigma_t d), and the
// scattering weight times F = sigma_s g(t) has mean integral of exp(-sigma_t t) sigma_s g(t) dt.
// Each check is 4 standard errors (false failure about 6e-5 each) with teeth: 4 standard errors
// are below 2% of the exact value, so a 2% bias fails.
#include "volume/spectral_mis_flight.h"
#include "core/rng.h"
#include "tests/sample_mean.h"
#include "volume/medium_set.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

const Rgb kSigmaT(0.3f, 1.0f, 3.0f);   ///< 1/m, per channel
const Rgb kSigmaS(0.25f, 0.6f, 2.9f);  ///< 1/m
constexpr double kThickness = 1.0;     ///< m

MediumSet slab() {
    HomogeneousMedium h;
    h.bounds = Bounds3{Vec3(-100.0f, -100.0f, 0.0f), Vec3(100.0f, 100.0f, 1.0f)};
    h.sigma_a = kSigmaT - kSigmaS;
    h.sigma_s = kSigmaS;
    return MediumSet({Medium{"slab", h}});
}

/// Scattering estimate of integral_0^d exp(-sigma t) sigma_s t dt, F = sigma_s g with g(t) = t.
double scattered_exact(int c) {
    const double s = kSigmaT[c], d = kThickness;
    return kSigmaS[c] * (1.0 - std::exp(-s * d) * (1.0 + s * d)) / (s * s);
}

TEST(SpectralMisFlight, ChromaticSlabMatchesTheClosedFormsPerChannel) {
    const MediumSet media = slab();
    const Ray ray{Vec3(0.3f, -0.2f, -1.0f), Vec3(0.0f, 0.0f, 1.0f), 0.0f, 5.0f};
    for (const Rgb throughput : {Rgb(1.0f), Rgb(1.0f, 0.2f, 0.05f)}) {
        for (int c = 0; c < 3; ++c) {
            const auto sample = [&](Pcg32& rng, bool scattered_part) {
                VolumeCounters counters;
                const FreeFlight f =
                    sample_free_flight_spectral_mis(media, ray, throughput, rng, counters);
                if (scattered_part)
                    return f.scattered ? f.weight[c] * kSigmaS[c] * (f.t - 1.0) : 0.0;
                return f.scattered ? 0.0 : static_cast<double>(f.weight[c]);
            };
            const MeanAndError escape =
                mean_over_streams(1000000, 31, [&](Pcg32& rng) { return sample(rng, false); });
            const double t_exact = std::exp(-kSigmaT[c] * kThickness);
            EXPECT_NEAR(escape.mean, t_exact, 4.0 * escape.stderr_) << "channel " << c;
            EXPECT_LT(4.0 * escape.stderr_, 0.02 * t_exact) << "channel " << c;
            const MeanAndError scatter =
                mean_over_streams(1000000, 32, [&](Pcg32& rng) { return sample(rng, true); });
            EXPECT_NEAR(scatter.mean, scattered_exact(c), 4.0 * scatter.stderr_) << "channel " << c;
            EXPECT_LT(4.0 * scatter.stderr_, 0.02 * scattered_exact(c)) << "channel " << c;
        }
    }
}

TEST(SpectralMisFlight, EscapeWeightsAreBoundedByTheBalanceHeuristic) {
    // At an escape every weight is nulls_lambda / sum_c q_c nulls_c <= 1 / q_lambda: 3 with grey
    // throughput, 1 / 0.04 for the smallest channel of throughput (1, 0.2, 0.05).
    const MediumSet media = slab();
    const Ray ray{Vec3(0.3f, -0.2f, -1.0f), Vec3(0.0f, 0.0f, 1.0f), 0.0f, 5.0f};
    const Rgb throughput(1.0f, 0.2f, 0.05f);
    const Rgb q = throughput / (throughput.r + throughput.g + throughput.b);
    for (uint64_t i = 0; i < 20000; ++i) {
        Pcg32 rng(41, i);
        VolumeCounters counters;
        const FreeFlight f = sample_free_flight_spectral_mis(media, ray, throughput, rng, counters);
        if (f.scattered)
            continue;
        for (int c = 0; c < 3; ++c)
            ASSERT_LE(f.weight[c], (1.0f + 1e-5f) / q[c]) << "channel " << c;
    }
}

TEST(SpectralMisFlight, GreyMediaGiveUnitWeights) {
    // Equal channels: every technique has the same pdf, so the weights are exactly 1 (escape)
    // and 1 / sigma_s (scattering): delta tracking.
    HomogeneousMedium h;
    h.bounds = Bounds3{Vec3(-100.0f, -100.0f, 0.0f), Vec3(100.0f, 100.0f, 1.0f)};
    h.sigma_a = Rgb(0.2f);
    h.sigma_s = Rgb(0.8f);
    const MediumSet media({Medium{"grey", h}});
    const Ray ray{Vec3(0.0f, 0.0f, -1.0f), Vec3(0.0f, 0.0f, 1.0f), 0.0f, 5.0f};
    for (uint64_t i = 0; i < 1000; ++i) {
        Pcg32 rng(5, i);
        VolumeCounters counters;
        const FreeFlight f = sample_free_flight_spectral_mis(media, ray, Rgb(1.0f), rng, counters);
        const float expected = f.scattered ? 1.0f / 0.8f : (f.weight.r == 0.0f ? 0.0f : 1.0f);
        ASSERT_NEAR(f.weight.r, expected, 1e-6f);
        ASSERT_EQ(f.weight.r, f.weight.g);
        ASSERT_EQ(f.weight.r, f.weight.b);
    }
}

}  // namespace
}  // namespace kasumi
