#include "lights/spot_light.h"

#include "light_test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

const char* kSpot = R"({"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0],
    "intensity_cd": 800, "cone_deg": 40, "falloff_deg": 20})";

Vec3 below_at_deg(float theta_deg, float r) {
    return Vec3(0, 3, 0) + r * Vec3(std::sin(radians(theta_deg)), -std::cos(radians(theta_deg)), 0);
}

TEST(SpotLight, FullInsideTheFalloffZeroOutsideTheCone) {
    const Light light = test::parse_light_text(kSpot);
    for (float theta : {0.0f, 10.0f, 19.9f}) {
        EXPECT_NEAR(luminance(incident_light(light, below_at_deg(theta, 2)).irradiance), 200.0f,
                    1e-3f);
    }
    for (float theta : {40.1f, 90.0f, 170.0f})
        EXPECT_EQ(luminance(incident_light(light, below_at_deg(theta, 2)).irradiance), 0.0f);
}

TEST(SpotLight, SmoothstepInCosineBetween) {
    const SpotLight spot = std::get<SpotLight>(test::parse_light_text(kSpot).emitter);
    const float mid = 0.5f * (spot.cos_cone + spot.cos_falloff);
    EXPECT_NEAR(spot_falloff(spot, mid), 0.5f, 1e-6f);
    const float quarter = spot.cos_cone + 0.25f * (spot.cos_falloff - spot.cos_cone);
    EXPECT_NEAR(spot_falloff(spot, quarter), 0.15625f, 1e-5f);  // 3t² − 2t³ at t = 1/4
}

TEST(SpotLight, InverseSquareAndCosineOnTheAxis) {
    const Light light = test::parse_light_text(kSpot);
    const Vec3 n = glm::normalize(Vec3(0.5f, 1, 0));
    EXPECT_NEAR(luminance(unshadowed_irradiance(light, Vec3(0), n)), 800.0f / 9.0f * n.y, 1e-3f);
}

TEST(SpotLight, FluxMatchesNumericalIntegration) {
    const SpotLight spot = std::get<SpotLight>(test::parse_light_text(kSpot).emitter);
    double flux = 0.0;
    const int steps = 200000;
    for (int i = 0; i < steps; ++i) {
        const double mu = -1.0 + 2.0 * (i + 0.5) / steps;
        flux += 2.0 * kPiD * spot_falloff(spot, static_cast<float>(mu)) * 2.0 / steps;
    }
    EXPECT_NEAR(spot_flux_per_cd(spot), flux, 1e-5 * flux);
    const Light by_flux = test::parse_light_text(R"({"type": "spot", "position": [0, 3, 0],
        "direction": [0, -1, 0], "flux_lm": 1000, "cone_deg": 40, "falloff_deg": 20})");
    EXPECT_NEAR(luminous_flux_lm(by_flux), 1000.0f, 1e-2f);
}

}  // namespace
}  // namespace kasumi
