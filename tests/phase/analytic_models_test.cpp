/// Closed-form checks of the analytic models, beyond the shared property suite.
#include "phase/phase_function.h"
#include "phase/phase_quadrature.h"

#include "core/rng.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

TEST(Rayleigh, ClosedFormValues) {
    // rho = 0: 3/(16π)(1 + mu²).
    EXPECT_NEAR(eval(Rayleigh{0.0f}, 0.0f), 3.0 / (16.0 * kPiD), 1e-7);
    EXPECT_NEAR(eval(Rayleigh{0.0f}, 1.0f), 6.0 / (16.0 * kPiD), 1e-7);
    // Depolarisation raises the side-scattering floor: γ = rho / (2 - rho).
    const double rho = 0.0279, gamma = rho / (2.0 - rho);
    EXPECT_NEAR(eval(Rayleigh{static_cast<float>(rho)}, 0.0f),
                3.0 / (16.0 * kPiD) * (1.0 + 3.0 * gamma) / (1.0 + 2.0 * gamma), 1e-7);
}

TEST(Rayleigh, QuadraticCosineSamplerInvertsTheCdf) {
    for (const double a : {0.0, 1e-6, 0.3, 1.0, 250.0}) {
        for (const double u : {0.0, 0.1, 0.5, 0.77, 1.0}) {
            const double mu = sample_quadratic_cosine(a, u);
            const double cdf =
                (mu + a * mu * mu * mu / 3.0 + 1.0 + a / 3.0) / (2.0 + 2.0 * a / 3.0);
            EXPECT_NEAR(cdf, u, 1e-9) << "a=" << a << " u=" << u;
        }
    }
}

TEST(CornetteShanks, EqualsDraineWithAlphaOneAndHasItsMeanCosine) {
    for (const float g : {-0.8f, 0.0f, 0.3f, 0.95f}) {
        for (const float mu : {-1.0f, -0.2f, 0.4f, 1.0f})
            EXPECT_FLOAT_EQ(eval(CornetteShanks{g}, mu), eval(Draine{g, 1.0f}, mu));
        // Cornette & Shanks 1992: <mu> = 3 g (4 + g²) / (5 (2 + g²)).
        const double expected = 3.0 * g * (4.0 + g * g) / (5.0 * (2.0 + g * g));
        EXPECT_NEAR(mean_cosine(CornetteShanks{g}), expected, 1e-6);
    }
}

TEST(Draine, NormalisedInDoublePrecisionAtExtremeG) {
    // Float mu cannot resolve the g = 0.9999 peak (width ~1e-8 in mu); the double-precision
    // form (eval_precise) is normalised to 1e-6 there.
    for (const double g : {-0.9999, -0.999, 0.0, 0.999, 0.9999}) {
        for (const double alpha : {0.0, 1.0, 30.0}) {
            const double total = 2.0 * kPiD *
                                 integrate_mu([&](double mu) { return draine_value(g, alpha, mu); },
                                              -1.0, 1.0, 1e-10);
            EXPECT_NEAR(total, 1.0, 1e-6) << "g=" << g << " alpha=" << alpha;
        }
    }
}

TEST(Draine, SamplerInvertsItsCdfNearZeroAndExtremeG) {
    for (const double g : {-0.9999, -0.3, 1e-8, 1e-5, 0.02, 0.3, 0.9999}) {
        for (const double alpha : {0.0, 0.5, 250.0}) {
            for (const double u : {0.0, 0.25, 0.5, 0.9, 1.0}) {
                const double mu = sample_draine_cosine(g, alpha, u);
                ASSERT_TRUE(mu >= -1.0 && mu <= 1.0);
                const double cdf = 2.0 * kPiD *
                                   integrate_mu([&](double t) { return draine_value(g, alpha, t); },
                                                -1.0, mu, 1e-10);
                EXPECT_NEAR(cdf, u, 2e-6) << "g=" << g << " alpha=" << alpha << " u=" << u;
            }
        }
    }
}

TEST(HenyeyGreenstein, ExtremeGStaysFiniteAtThePoles) {
    for (const float g : {-0.9999f, 0.9999f}) {
        for (const float mu : {-1.0f, 1.0f}) {
            const float v = eval(HenyeyGreenstein{g}, mu);
            EXPECT_TRUE(std::isfinite(v));
            // p(±1) = (1 ± g) / (4π (1 ∓ g)²) in closed form.
            const double s = mu > 0.0f ? 1.0 : -1.0;
            const double gd = g;
            const double expected = (1.0 + s * gd) / (4.0 * kPiD * (1.0 - s * gd) * (1.0 - s * gd));
            EXPECT_NEAR(v, expected, 1e-3 * expected) << g << " " << mu;
        }
    }
}

TEST(HenyeyGreenstein, PrecisePeakHasNoCancellationForEitherSign) {
    // p(±1) = (1 ± g) / (4π (1 ∓ g)²); the textbook 1 + g² - 2 g mu loses ~1e-8 relative here.
    for (const float g : {-0.9999f, 0.9999f}) {
        const double gd = g, s = g > 0.0f ? 1.0 : -1.0;
        const double peak = (1.0 + s * gd) / (4.0 * kPiD * (1.0 - s * gd) * (1.0 - s * gd));
        EXPECT_NEAR(eval_precise(HenyeyGreenstein{g}, s), peak, 1e-13 * peak) << g;
        // Just inside the pole, where float mu cannot go: 1 - |mu| = 1e-9.
        const double mu = s * (1.0 - 1e-9);
        const double gap = 1.0 - s * mu;  // exact (Sterbenz), unlike the literal 1e-9
        const double d = (1.0 - s * gd) * (1.0 - s * gd) + 2.0 * s * gd * gap;
        const double expected = (1.0 - gd * gd) / (4.0 * kPiD * d * std::sqrt(d));
        EXPECT_NEAR(eval_precise(HenyeyGreenstein{g}, mu), expected, 1e-12 * expected) << g;
    }
}

TEST(PhaseFunction, FloatEvalIsThePreciseValueRounded) {
    const std::vector<PhaseFunction> models = {Isotropic{},
                                               HenyeyGreenstein{0.9999f},
                                               Rayleigh{0.03f},
                                               DoubleHenyeyGreenstein{0.9f, -0.4f, 0.6f},
                                               CornetteShanks{-0.7f},
                                               Draine{0.5f, 3.0f},
                                               make_jendersie_deon(20.0f)};
    for (const PhaseFunction& p : models) {
        for (const float mu : {-1.0f, -0.3f, 0.0f, 0.7f, 0.999f, 1.0f}) {
            EXPECT_EQ(eval(p, mu), static_cast<float>(eval_precise(p, mu)))
                << p.index() << " mu=" << mu;
        }
    }
}

TEST(HenyeyGreenstein, ExtremeGSamplesAreDeflectedNotSnappedToThePole) {
    // For g = 0.9999 half the mass has 1 - mu < 5e-9, below float spacing of mu: a sampler that
    // went through a float mu would return wi == -wo (θ = 0) for most samples.
    const Vec3 wo = glm::normalize(Vec3(0.3f, -0.5f, 0.81f));
    Pcg32 rng(3u, 5u);
    int on_pole = 0;
    for (int i = 0; i < 10000; ++i) {
        const PhaseSample s = sample(HenyeyGreenstein{0.9999f}, wo, rng.next_vec2());
        if (glm::length(DVec3(s.wi) + DVec3(wo)) < 1e-6)
            ++on_pole;
    }
    // P(θ < 1e-6) = P(1 - mu < 5e-13) ≈ 2π p(1) 5e-13 ≈ 5e-5: expect ~0.5 of 10^4.
    EXPECT_LE(on_pole, 5);
}

TEST(JendersieDeon, BlendsHgAndDraineWithTheFittedParameters) {
    for (const float d : {0.05f, 0.5f, 2.0f, 5.0f, 20.0f, 50.0f}) {
        const JendersieDeon p = make_jendersie_deon(d);
        EXPECT_GT(p.fit.w_d, 0.0f) << d;
        EXPECT_LT(p.fit.w_d, 1.0f) << d;
        EXPECT_LT(std::abs(p.fit.g_hg), 1.0f) << d;
        EXPECT_LT(std::abs(p.fit.g_d), 1.0f) << d;
        for (const float mu : {-1.0f, 0.0f, 0.9f, 1.0f}) {
            const double w = p.fit.w_d;
            const double expected = (1.0 - w) * eval_precise(HenyeyGreenstein{p.fit.g_hg}, mu) +
                                    w * eval_precise(Draine{p.fit.g_d, p.fit.alpha}, mu);
            EXPECT_NEAR(eval_precise(p, mu), expected, 1e-14 * expected);
            EXPECT_FLOAT_EQ(eval(p, mu), static_cast<float>(expected));
        }
    }
    // Fog droplets scatter strongly forward.
    EXPECT_GT(mean_cosine(make_jendersie_deon(20.0f)), 0.8f);
}

TEST(Convention, LookingTowardTheSunThroughForwardScatteringFogIsBrighter) {
    // Sun toward +z (wi = +z points at the light). A camera looking toward the sun sees light
    // that continued forward: the view ray travels +z, so wo (toward the viewer) is -z.
    const Vec3 to_sun(0.0f, 0.0f, 1.0f);
    const Vec3 wo_looking_at_sun(0.0f, 0.0f, -1.0f);
    const Vec3 wo_looking_away(0.0f, 0.0f, 1.0f);
    for (const PhaseFunction& p :
         {PhaseFunction{HenyeyGreenstein{0.8f}}, PhaseFunction{make_jendersie_deon(10.0f)},
          PhaseFunction{make_mie(50.0, Complex(1.33, 0.0))}}) {
        EXPECT_GT(eval(p, wo_looking_at_sun, to_sun), 10.0f * eval(p, wo_looking_away, to_sun));
        EXPECT_FLOAT_EQ(scattering_cosine(wo_looking_at_sun, to_sun), 1.0f);
    }
}

}  // namespace
}  // namespace kasumi
