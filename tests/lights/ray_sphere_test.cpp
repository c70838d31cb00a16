#include "lights/ray_sphere.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

constexpr double kInf = 1e300;

TEST(RaySphere, HeadOnFromOutsideAndInside) {
    const DVec3 c(1, 2, 3);
    EXPECT_EQ(*intersect_sphere(c, 2.0, c + DVec3(0, 0, -10), DVec3(0, 0, 1), 0, kInf), 8.0);
    EXPECT_EQ(*intersect_sphere(c, 2.0, c, DVec3(0, 0, 1), 0, kInf), 2.0);
    // Non-unit direction: t is in its units.
    EXPECT_EQ(*intersect_sphere(c, 2.0, c + DVec3(0, 0, -10), DVec3(0, 0, 4), 0, kInf), 2.0);
}

TEST(RaySphere, IntervalSelectsTheRoot) {
    const DVec3 o(0, 0, -10);
    const DVec3 d(0, 0, 1);
    EXPECT_EQ(*intersect_sphere(DVec3(0), 1.0, o, d, 9.5, kInf), 11.0);
    EXPECT_FALSE(intersect_sphere(DVec3(0), 1.0, o, d, 11.5, kInf));
    EXPECT_FALSE(intersect_sphere(DVec3(0), 1.0, o, d, 0, 8.5));
    EXPECT_FALSE(intersect_sphere(DVec3(0), 1.0, -o, d, 0, kInf));  // sphere behind
}

TEST(RaySphere, MissesAndGrazes) {
    EXPECT_FALSE(intersect_sphere(DVec3(0), 1.0, DVec3(0, 1.001, -5), DVec3(0, 0, 1), 0, kInf));
    // A ray tangent at its own origin: the double root t = 0.
    EXPECT_EQ(*intersect_sphere(DVec3(0), 1.0, DVec3(0, 1, 0), DVec3(0, 0, 1), 0, kInf), 0.0);
}

/// From 1 mm above an Earth-sized sphere, t is good to a few double ulps of r (~1e-9 m), far
/// below the float spacing of any point the renderer holds; in float the same sum would be off
/// by metres (ulp(6.4e6) = 0.5 m).
TEST(RaySphere, PlanetFromJustAboveTheSurface) {
    const double r = 6.371e6;
    const DVec3 center(0, -r, 0);
    const DVec3 origin(0, 1e-3, 0);
    const double t = *intersect_sphere(center, r, origin, DVec3(0, -1, 0), 0, kInf);
    const double tolerance = 4.0 * 0x1p-53 * r;
    EXPECT_NEAR(t, 1e-3, tolerance);
    // Slanted at 45°: the exact distance to the sphere is close to the plane's 1e-3 √2.
    const DVec3 d = glm::normalize(DVec3(1, -1, 0));
    const double exact = [&] {
        const DVec3 f = origin - center;
        const long double b = glm::dot(f, d);
        const long double cc = (long double)glm::dot(f, f) - (long double)r * r;
        return static_cast<double>(cc / (-b + std::sqrt(b * b - cc)));
    }();
    EXPECT_NEAR(*intersect_sphere(center, r, origin, d, 0, kInf), exact, tolerance);
}

}  // namespace
}  // namespace kasumi
