#include "lights/line_light.h"

#include "light_test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

double closed_form(const LineLight& light, const Vec3& p, const Vec3& n) {
    return luminance(unshadowed_irradiance(light, p, n));
}

TEST(LineLight, InfiniteLineOverheadGivesPiIOverTwoH) {
    // An infinite Lambertian line at height h over a parallel receiver: the integral
    // I h² ∫ ds / (s² + h²)² = I π / (2h).
    const LineLight light{Vec3(-1e4f, 2, 0), Vec3(1e4f, 2, 0), Rgb(10.0f)};
    EXPECT_NEAR(closed_form(light, Vec3(0), Vec3(0, 1, 0)), 10.0 * kPiD / 4.0, 1e-5);
}

TEST(LineLight, ShortLineFarAwayIsAPointSource) {
    // Seen from 100 m perpendicular to it, a 1 cm line is a point of intensity I_l L.
    const LineLight light{Vec3(-0.005f, 100, 0), Vec3(0.005f, 100, 0), Rgb(1000.0f)};
    const double expected = 1000.0 * 0.01 / (100.0 * 100.0);
    EXPECT_NEAR(closed_form(light, Vec3(0), Vec3(0, 1, 0)), expected, 1e-5 * expected);
}

TEST(LineLight, ClosedFormMatchesBruteForceQuadrature) {
    struct Case {
        const char* what;
        Vec3 from, to, p, n;
    };
    const Case cases[] = {
        {"overhead, receiver facing up", Vec3(-1, 2, 0), Vec3(1, 2, 0), Vec3(0.3f, 0, 0.5f),
         Vec3(0, 1, 0)},
        {"oblique segment, tilted receiver", Vec3(-1, 1, -0.5f), Vec3(2, 2.5f, 1), Vec3(0),
         glm::normalize(Vec3(0.2f, 1, -0.3f))},
        {"cut by the horizon", Vec3(-2, 1, 0), Vec3(2, 1, 0), Vec3(0),
         glm::normalize(Vec3(1, 0.2f, 0))},
        {"beyond the end of the segment", Vec3(0, 1, 0), Vec3(3, 1, 0), Vec3(-1, 0, 0),
         glm::normalize(Vec3(1, 1, 0))},
        {"wall receiver, line along the normal's plane", Vec3(1, 0.5f, -1), Vec3(1, 0.5f, 1),
         Vec3(0, 0.5f, 0), Vec3(1, 0, 0)},
    };
    for (const Case& c : cases) {
        const LineLight light{c.from, c.to, Rgb(7.0f)};
        const double reference = test::line_quadrature(c.from, c.to, 7.0, c.p, c.n, 2000000);
        EXPECT_GT(reference, 0.0) << c.what;
        EXPECT_NEAR(closed_form(light, c.p, c.n), reference, 1e-5 * reference) << c.what;
    }
}

TEST(LineLight, DarkBelowTheHorizonAndOnTheAxis) {
    const LineLight light{Vec3(-1, 2, 0), Vec3(1, 2, 0), Rgb(7.0f)};
    EXPECT_EQ(closed_form(light, Vec3(0), Vec3(0, -1, 0)), 0.0);
    // On the line's axis every element is seen end-on: sin α = 0.
    EXPECT_EQ(closed_form(light, Vec3(3, 2, 0), Vec3(-1, 0, 0)), 0.0);
}

TEST(LineLight, FluxIsPiSquaredIntensityTimesLength) {
    const LineLight light{Vec3(0), Vec3(0, 0, 2), Rgb(3.0f)};
    EXPECT_NEAR(line_flux_lm(light), kPi * kPi * 3.0f * 2.0f, 1e-4f);
    // The same by integrating I(α) = I_l L sin α over the sphere: 2π ∫ sin²α dα = π².
    double integral = 0.0;
    const int steps = 100000;
    for (int i = 0; i < steps; ++i) {
        const double alpha = (i + 0.5) / steps * kPiD;
        integral += 3.0 * 2.0 * std::sin(alpha) * 2.0 * kPiD * std::sin(alpha) * kPiD / steps;
    }
    EXPECT_NEAR(line_flux_lm(light), integral, 1e-4 * integral);
}

TEST(LineLightJson, FluxAndIntensityAgree) {
    const Light a = test::parse_light_text(
        R"({"type": "line", "from": [0, 0, 0], "to": [2, 0, 0], "intensity_cd_per_m": 5})");
    const Light b = test::parse_light_text(R"({"type": "line", "from": [0, 0, 0], "to": [2, 0, 0],
        "flux_lm": 98.696044})");
    EXPECT_NEAR(luminous_flux_lm(a), 98.696044f, 1e-3f);
    EXPECT_NEAR(luminance(std::get<LineLight>(b.emitter).intensity_per_m), 5.0f, 1e-5f);
}

}  // namespace
}  // namespace kasumi
