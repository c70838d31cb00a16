// Fresnel reflection of a smooth dielectric against published values and Fresnel's own
// trigonometric form (Born & Wolf, Principles of Optics, 7th ed., §1.5.2, eqs. 21a-b and 35),
// independent of the cosine form surface/fresnel.cpp evaluates.
#include "surface/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

double radians(double deg) {
    return deg * kPiD / 180.0;
}

TEST(PublishedFresnel, MatchesFresnelsSineAndTangentLaws) {
    // r_perp = -sin(i - t) / sin(i + t), r_par = tan(i - t) / tan(i + t), with Snell's
    // sin i = n sin t (Born & Wolf eqs. 1.5.21a-b with 1.5.35): the sign convention too.
    for (const double n : {1.333, 1.5, 2.42}) {
        for (double deg = 1.0; deg < 90.0; deg += 4.0) {
            const double i = radians(deg), t = std::asin(std::sin(i) / n);
            const double rs = -std::sin(i - t) / std::sin(i + t);
            const double rp = std::tan(i - t) / std::tan(i + t);
            const FresnelAmplitudes r =
                fresnel_amplitudes(static_cast<float>(std::cos(i)), static_cast<float>(n));
            EXPECT_NEAR(r.rs, rs, 2e-6) << n << " " << deg;
            EXPECT_NEAR(r.rp, rp, 2e-6) << n << " " << deg;
            EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(i)), static_cast<float>(n)),
                        0.5 * (rs * rs + rp * rp), 2e-6)
                << n << " " << deg;
        }
    }
}

TEST(PublishedFresnel, GlassAndWaterValues) {
    // Crown glass n = 1.5 in air (Hecht, Optics, 5th ed., ch. 4, the Fresnel equations): 4% at
    // normal incidence; at 45° R_s = 0.0920, R_p = 0.0085 and R_p = R_s² exactly (Abelès 1950);
    // Brewster's angle 56.31°; leaving the glass, the critical angle is 41.81°. Water n = 1.333:
    // 2.04% at normal incidence, critical angle 48.6°.
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04, 1e-6);
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.333f), 0.0204, 1e-4);
    const FresnelAmplitudes r45 =
        fresnel_amplitudes(static_cast<float>(std::cos(radians(45.0))), 1.5f);
    EXPECT_NEAR(r45.rs * r45.rs, 0.0920, 5e-5);
    EXPECT_NEAR(r45.rp * r45.rp, 0.0085, 5e-5);
    EXPECT_NEAR(r45.rp * r45.rp, std::pow(r45.rs * r45.rs, 2.0), 1e-6);
    EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(radians(45.0))), 1.5f), 0.0502,
                5e-5);
    const FresnelAmplitudes brewster =
        fresnel_amplitudes(static_cast<float>(std::cos(radians(56.31))), 1.5f);
    EXPECT_NEAR(brewster.rp, 0.0, 1e-5);
    // Total internal reflection from inside (cos < 0 flips the relative index).
    for (const auto& [n, critical_deg] :
         {std::pair<float, double>{1.5f, 41.81}, std::pair<float, double>{1.333f, 48.61}}) {
        EXPECT_EQ(
            fresnel_dielectric(-static_cast<float>(std::cos(radians(critical_deg + 0.02))), n),
            1.0f)
            << n;
        EXPECT_LT(
            fresnel_dielectric(-static_cast<float>(std::cos(radians(critical_deg - 0.02))), n),
            1.0f)
            << n;
    }
}

TEST(PublishedFresnel, StokesRelationsHold) {
    // Stokes (1849): r' = -r and t t' = 1 - r² for the reverse path; in power, the
    // reflectance is the same from both sides at corresponding angles (Born & Wolf §1.5.3).
    for (const float n : {1.333f, 1.5f}) {
        for (double deg = 0.0; deg < 89.0; deg += 7.0) {
            const double i = radians(deg), t = std::asin(std::sin(i) / n);
            EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(i)), n),
                        fresnel_dielectric(-static_cast<float>(std::cos(t)), n), 2e-6)
                << n << " " << deg;
        }
    }
}

}  // namespace
}  // namespace kasumi
