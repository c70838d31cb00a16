#include "lights/sphere_light.h"

#include "light_test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

double closed_form(const SphereLight& light, const Vec3& p, const Vec3& n) {
    return luminance(unshadowed_irradiance(light, p, n));
}

Vec3 at_angle_deg(float theta_deg) {
    return Vec3(std::sin(radians(theta_deg)), std::cos(radians(theta_deg)), 0.0f);
}

TEST(SphereLight, AboveTheHorizonIsPiLSin2SigmaCosTheta) {
    const SphereLight light{Vec3(0, 4, 0), 1.0f, Rgb(10.0f)};
    for (float theta : {0.0f, 30.0f, 60.0f}) {
        const double expected = kPiD * 10.0 / 16.0 * std::cos(radians(theta));
        EXPECT_NEAR(closed_form(light, Vec3(0), at_angle_deg(theta)), expected, 1e-6 * expected)
            << theta;
    }
}

TEST(SphereLight, FarAwayIsAPointSourceOfIntensityPiR2L) {
    const SphereLight light{Vec3(0, 1000, 0), 0.1f, Rgb(1e4f)};
    const double expected = kPiD * 0.01 * 1e4 / 1e6;
    EXPECT_NEAR(closed_form(light, Vec3(0), Vec3(0, 1, 0)), expected, 1e-6 * expected);
}

TEST(SphereLight, ClosedFormMatchesQuadratureAcrossTheHorizon) {
    // σ = 30°: fully above up to θ = 60°, straddling in (60°, 120°), below past 120°.
    const SphereLight light{Vec3(0, 2, 0), 1.0f, Rgb(3.0f)};
    for (float theta : {0.0f, 45.0f, 59.0f, 61.0f, 75.0f, 90.0f, 105.0f, 119.0f}) {
        const Vec3 n = at_angle_deg(theta);
        const double reference = test::sphere_quadrature(light.center, 1.0, 3.0, Vec3(0), n, 1500);
        EXPECT_NEAR(closed_form(light, Vec3(0), n), reference, 2e-5 * 3.0 * kPiD) << theta;
    }
    // A large sphere close by (σ = 72.5°), receiver tilted 100°.
    const SphereLight near{Vec3(0, 1.05f, 0), 1.0f, Rgb(1.0f)};
    const Vec3 n = at_angle_deg(100.0f);
    EXPECT_NEAR(closed_form(near, Vec3(0), n),
                test::sphere_quadrature(near.center, 1.0, 1.0, Vec3(0), n, 1500), 2e-5 * kPiD);
}

TEST(SphereLight, DarkBelowTheHorizonAndInside) {
    const SphereLight light{Vec3(0, 2, 0), 1.0f, Rgb(3.0f)};
    EXPECT_EQ(closed_form(light, Vec3(0), at_angle_deg(121.0f)), 0.0);
    EXPECT_EQ(closed_form(light, Vec3(0, 2.5f, 0), Vec3(0, 1, 0)), 0.0);
}

TEST(SphereLight, FluxIsFourPiSquaredR2L) {
    const Light light = test::parse_light_text(
        R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "luminance_cd_m2": 100})");
    EXPECT_NEAR(luminous_flux_lm(light), 4.0f * kPi * kPi * 0.25f * 100.0f, 1e-2f);
}

}  // namespace
}  // namespace kasumi
