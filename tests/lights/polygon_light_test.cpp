#include "lights/polygon_light.h"

#include "light_test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

using test::polygon_quadrature;

/// A square of side 2a centred at (0, h, 0), facing down (counter-clockwise seen from below).
std::vector<Vec3> ceiling_square(float a, float h) {
    return {Vec3(-a, h, -a), Vec3(a, h, -a), Vec3(a, h, a), Vec3(-a, h, a)};
}

double lambert(const PolygonLight& light, const Vec3& p, const Vec3& n) {
    return luminance(unshadowed_irradiance(light, p, n));
}

/// Form factor from a differential area to a parallel rectangle a × b whose corner is at
/// distance c straight above it (Howell, "A Catalog of Radiation Heat Transfer Configuration
/// Factors", B-3): an independent closed form.
double corner_rectangle_form_factor(double a, double b, double c) {
    const double x = a / c, y = b / c;
    const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPiD);
}

TEST(PolygonLight, NormalFollowsCounterClockwiseWinding) {
    const PolygonLight light = make_polygon_light(ceiling_square(1, 2), Rgb(1.0f), false);
    EXPECT_NEAR(light.normal.y, -1.0f, 1e-6f);
    EXPECT_NEAR(light.area, 4.0f, 1e-5f);
    EXPECT_NEAR(polygon_flux_lm(light), 4.0f * kPi, 1e-4f);
}

TEST(PolygonLight, ParallelSquareMatchesHowellFormFactor) {
    for (float a : {0.1f, 1.0f, 3.0f}) {
        const PolygonLight light = make_polygon_light(ceiling_square(a, 2.0f), Rgb(5.0f), false);
        const double expected = 5.0 * kPiD * 4.0 * corner_rectangle_form_factor(a, a, 2.0);
        EXPECT_NEAR(lambert(light, Vec3(0), Vec3(0, 1, 0)), expected, 1e-5 * expected) << a;
    }
}

TEST(PolygonLight, HugePolygonApproachesPiL) {
    // An unbounded emitting plane over the whole hemisphere gives E = π L.
    const PolygonLight light = make_polygon_light(ceiling_square(1e4f, 1.0f), Rgb(2.0f), false);
    const double e = lambert(light, Vec3(0), Vec3(0, 1, 0));
    const double expected = 2.0 * kPiD * 4.0 * corner_rectangle_form_factor(1e4, 1e4, 1.0);
    EXPECT_NEAR(e, expected, 1e-6 * expected);
    EXPECT_NEAR(e, 2.0 * kPiD, 1e-3);
}

TEST(PolygonLight, TinyPolygonIsAPointSourceOfIntensityLA) {
    const float a = 5e-4f;  // a 1 mm square, 10 m away, tilted receiver
    const PolygonLight light = make_polygon_light(ceiling_square(a, 10.0f), Rgb(1e6f), false);
    const Vec3 n = glm::normalize(Vec3(0.3f, 1.0f, 0.0f));
    const double expected = 1e6 * (4.0 * a * a) * n.y / 100.0;  // L A cos θ cos θ' / r²
    EXPECT_NEAR(lambert(light, Vec3(0), n), expected, 1e-4 * expected);
}

struct Case {
    const char* what;
    std::vector<Vec3> vertices;
    bool two_sided;
    Vec3 p, n;
};

std::vector<Case> quadrature_cases() {
    // A convex pentagon in the plane y = 2 + 0.1 x + 0.1 z, counter-clockwise seen from below.
    std::vector<Vec3> pentagon;
    for (const Vec2 xz :
         {Vec2(1, -1.2f), Vec2(1.5f, 0), Vec2(0.5f, 1.5f), Vec2(-1, 1), Vec2(-1, -1)})
        pentagon.emplace_back(xz.x, 2.0f + 0.1f * xz.x + 0.1f * xz.y, xz.y);
    return {
        {"square above", ceiling_square(1, 2), false, Vec3(0.3f, 0, 0.2f), Vec3(0, 1, 0)},
        {"tilted receiver, fully above", ceiling_square(1, 2), false, Vec3(0),
         glm::normalize(Vec3(0.3f, 1, 0.1f))},
        {"cut by the horizon", ceiling_square(1, 2), false, Vec3(0.5f, 0, 0),
         glm::normalize(Vec3(1, 0.3f, 0))},
        {"cut by the horizon, far side", ceiling_square(2, 1), false, Vec3(0.5f, 0, 0.4f),
         glm::normalize(Vec3(-1, 0.2f, 0.5f))},
        {"wall, receiver on the floor",
         {Vec3(2, 0, -1), Vec3(2, 0, 1), Vec3(2, 2, 1), Vec3(2, 2, -1)},
         false,
         Vec3(0),
         Vec3(0, 1, 0)},
        {"convex pentagon, oblique", pentagon, false, Vec3(0.2f, 0.1f, 0.3f),
         glm::normalize(Vec3(-0.4f, 1, 0.2f))},
        {"two-sided seen from behind", ceiling_square(1, -2), true, Vec3(0.2f, 0, 0),
         Vec3(0, -1, 0)},
        {"nearly edge-on", ceiling_square(1, 0.05f), false, Vec3(3, 0, 0), Vec3(-1, 0, 0)},
    };
}

TEST(PolygonLight, LambertFormulaMatchesBruteForceQuadrature) {
    for (const Case& c : quadrature_cases()) {
        EXPECT_EQ(polygon_problem(c.vertices), "") << c.what;
        const PolygonLight light = make_polygon_light(c.vertices, Rgb(3.0f), c.two_sided);
        const double e = lambert(light, c.p, c.n);
        const double reference = polygon_quadrature(c.vertices, 3.0, c.two_sided, c.p, c.n, 1500);
        EXPECT_GT(reference, 0.0) << c.what;
        EXPECT_NEAR(e, reference, 2e-4 * reference + 1e-7) << c.what;
    }
}

TEST(PolygonLight, DarkBehindAOneSidedLightAndInItsPlane) {
    const PolygonLight light = make_polygon_light(ceiling_square(1, 2), Rgb(3.0f), false);
    EXPECT_EQ(lambert(light, Vec3(0, 3, 0), Vec3(0, -1, 0)), 0.0);
    // In the polygon's plane, outside it: seen exactly edge-on.
    EXPECT_EQ(lambert(light, Vec3(3, 2, 0), Vec3(-1, 0, 0)), 0.0);
    // Entirely below the receiver's horizon.
    EXPECT_EQ(lambert(light, Vec3(0), Vec3(0, -1, 0)), 0.0);
}

TEST(PolygonLight, TwoSidedIsSymmetric) {
    const PolygonLight light = make_polygon_light(ceiling_square(1, 0), Rgb(1.0f), true);
    const Vec3 n = glm::normalize(Vec3(0.2f, 1, 0));
    EXPECT_NEAR(lambert(light, Vec3(0.1f, -1, 0), n), lambert(light, Vec3(-0.1f, 1, 0), -n), 1e-6);
}

TEST(PolygonLight, ProblemsAreNamed) {
    EXPECT_NE(polygon_problem({Vec3(0), Vec3(1, 0, 0)}).find("at least 3"), std::string::npos);
    EXPECT_NE(polygon_problem({Vec3(0), Vec3(1, 0, 0), Vec3(2, 0, 0)}).find("zero area"),
              std::string::npos);
    EXPECT_NE(
        polygon_problem({Vec3(0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)}).find("coincide"),
        std::string::npos);
    EXPECT_NE(polygon_problem({Vec3(0), Vec3(1, 0, 0), Vec3(1, 0.5f, 1), Vec3(0, 0, 1)})
                  .find("not planar"),
              std::string::npos);
    EXPECT_NE(polygon_problem({Vec3(0), Vec3(2, 0, 0), Vec3(1, 0, 0.2f), Vec3(1, 0, 2)})
                  .find("not convex"),
              std::string::npos);
    EXPECT_EQ(polygon_problem(ceiling_square(1, 2)), "");
}

}  // namespace
}  // namespace kasumi
