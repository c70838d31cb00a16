#include "phase/phase_function.h"

#include "core/rng.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

/// Integrates p over the sphere by the midpoint rule in mu (azimuthal symmetry: 2π ∫ p dmu).
double integrate(const PhaseFunction& p, int n = 200000) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const float mu = -1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
        sum += eval(p, mu);
    }
    return 2.0 * kPiD * sum * 2.0 / n;
}

TEST(HenyeyGreenstein, NormalisedAndMeanCosineIsG) {
    for (float g : {-0.9f, -0.3f, 0.0f, 0.5f, 0.9f}) {
        const PhaseFunction p = HenyeyGreenstein{g};
        EXPECT_NEAR(integrate(p), 1.0, 2e-3) << g;
        double mean = 0.0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const float mu = -1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / n;
            mean += mu * eval(p, mu);
        }
        EXPECT_NEAR(2.0 * kPiD * mean * 2.0 / n, g, 2e-3) << g;
    }
}

TEST(HenyeyGreenstein, ForwardIsMuPlusOne) {
    const HenyeyGreenstein p{0.8f};
    EXPECT_GT(eval(p, 1.0f), eval(p, -1.0f));
    // Closed form at mu = 1: (1 - g²) / (4π (1 - g)³) = (1 + g) / (4π (1 - g)²).
    EXPECT_NEAR(eval(p, 1.0f), (1.0f + 0.8f) / (4.0f * kPi * 0.04f), 1e-3f);
}

TEST(HenyeyGreenstein, SampledDirectionsFollowConvention) {
    const HenyeyGreenstein p{0.7f};
    const Vec3 wo = glm::normalize(Vec3(0.3f, -0.2f, 0.9f));
    Pcg32 rng(7u, 11u);
    double mean_mu = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const PhaseSample s = sample(p, wo, rng.next_vec2());
        ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-4f);
        const float mu = scattering_cosine(wo, s.wi);
        ASSERT_NEAR(s.pdf, eval(p, mu), 1e-3f * s.pdf);
        mean_mu += mu;
    }
    // Var(mu) <= 1, so the sample mean has sd <= 1/sqrt(n) ≈ 2.2e-3; 5 sd bound.
    EXPECT_NEAR(mean_mu / n, 0.7, 5.0 * 2.24e-3);
}

}  // namespace
}  // namespace kasumi
