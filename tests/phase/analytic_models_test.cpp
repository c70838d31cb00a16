/// Closed-form checks of the analytic models, beyond the shared property suite.
#include "phase/phase_function.h"
#include "phase/phase_quadrature.h"

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
    // form is normalised to 1e-6 there, which is what the float API samples.
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

TEST(JendersieDeon, BlendsHgAndDraineWithTheFittedParameters) {
    for (const float d : {0.05f, 0.5f, 2.0f, 5.0f, 20.0f, 50.0f}) {
        const JendersieDeon p = make_jendersie_deon(d);
        EXPECT_GT(p.fit.w_d, 0.0f) << d;
        EXPECT_LT(p.fit.w_d, 1.0f) << d;
        EXPECT_LT(std::abs(p.fit.g_hg), 1.0f) << d;
        EXPECT_LT(std::abs(p.fit.g_d), 1.0f) << d;
        for (const float mu : {-1.0f, 0.0f, 0.9f, 1.0f}) {
            const float expected = (1.0f - p.fit.w_d) * eval(HenyeyGreenstein{p.fit.g_hg}, mu) +
                                   p.fit.w_d * eval(Draine{p.fit.g_d, p.fit.alpha}, mu);
            EXPECT_FLOAT_EQ(eval(p, mu), expected);
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
