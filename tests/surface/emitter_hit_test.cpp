// Area lights seen by rays: where a ray meets a polygon or sphere light and what it sees.
#include "surface/emitter_hit.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

Light panel(bool two_sided) {
    Light l;
    // Counter-clockwise seen from below: emits toward -y.
    l.emitter = make_polygon_light({Vec3(-1, 2, 1), Vec3(-1, 2, -1), Vec3(1, 2, -1), Vec3(1, 2, 1)},
                                   Rgb(500.0f), two_sided);
    return l;
}

Light ball(const Vec3& c, float r, float luminance) {
    Light l;
    l.emitter = SphereLight{c, r, Rgb(luminance)};
    return l;
}

TEST(EmitterHitTest, PolygonSeenFromItsEmittingSideOnly) {
    const std::vector<Light> one = {panel(false)};
    const auto below =
        intersect_emitters(one, Ray{Vec3(0.3f, 0, 0.2f), Vec3(0, 1, 0), 0, kInfinity});
    ASSERT_TRUE(below);
    EXPECT_FLOAT_EQ(below->t, 2.0f);
    EXPECT_FLOAT_EQ(below->radiance.g, 500.0f);
    const auto above =
        intersect_emitters(one, Ray{Vec3(0.3f, 4, 0.2f), Vec3(0, -1, 0), 0, kInfinity});
    ASSERT_TRUE(above) << "the back of a one-sided panel still hides what is behind it";
    EXPECT_TRUE(is_black(above->radiance));
    const std::vector<Light> two = {panel(true)};
    const auto back =
        intersect_emitters(two, Ray{Vec3(0.3f, 4, 0.2f), Vec3(0, -1, 0), 0, kInfinity});
    ASSERT_TRUE(back);
    EXPECT_FLOAT_EQ(back->radiance.g, 500.0f);
    EXPECT_FALSE(intersect_emitters(one, Ray{Vec3(1.01f, 0, 0), Vec3(0, 1, 0), 0, kInfinity}));
    EXPECT_FALSE(intersect_emitters(one, Ray{Vec3(0, 0, 0), Vec3(0, 1, 0), 0, 1.99f}));
}

TEST(EmitterHitTest, NearestOfSeveralAndSphereDistance) {
    const std::vector<Light> lights = {panel(false), ball(Vec3(0, 1, 0), 0.25f, 80.0f)};
    const auto hit = intersect_emitters(lights, Ray{Vec3(0, 0, 0), Vec3(0, 1, 0), 0, kInfinity});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->light, 1u);
    EXPECT_NEAR(hit->t, 0.75f, 1e-6f);
    EXPECT_FLOAT_EQ(hit->radiance.r, 80.0f);
    // From inside the sphere it is not seen; the panel beyond is.
    const auto inside = intersect_emitters(lights, Ray{Vec3(0, 1, 0), Vec3(0, 1, 0), 0, kInfinity});
    ASSERT_TRUE(inside);
    EXPECT_EQ(inside->light, 0u);
}

TEST(EmitterHitTest, SphereGrazedFromFarAwayIsStillHit) {
    // The float pre-test must not reject rays that pass just inside the rim, from near and
    // from 1 km away: every ray whose line (the float ray, in double) passes inside the sphere
    // is hit, at the closed-form t = f·d − √(R² − |f − (f·d) d|²).
    const DVec3 c(2.5, 5.0, -1.0);
    const double radius = 0.4;
    const std::vector<Light> lights{ball(Vec3(c), static_cast<float>(radius), 1.0f)};
    int hits = 0;
    for (const double distance : {1.5, 8.0, 1000.0}) {
        for (const double inside : {1e-6, 1e-3, 0.1}) {
            for (int k = 0; k < 16; ++k) {
                const double phi = 2.0 * kPiD * k / 16.0;
                const DVec3 to_center = glm::normalize(DVec3(std::cos(phi), 0.3, std::sin(phi)));
                const DVec3 side = glm::normalize(glm::cross(to_center, DVec3(0, 1, 0)));
                // The line passes (1 − inside) R from the centre.
                const double sin_t = (1.0 - inside) * radius / distance;
                const DVec3 dir = std::sqrt(1.0 - sin_t * sin_t) * to_center + sin_t * side;
                const Ray ray{Vec3(c - distance * to_center), Vec3(dir), 0.0f, kInfinity};
                const DVec3 f = c - DVec3(ray.origin);
                const DVec3 d = glm::normalize(DVec3(ray.direction));
                const double b = glm::dot(f, d);
                const double perp2 = glm::dot(f - b * d, f - b * d);
                if (!(perp2 < radius * radius * (1.0 - 1e-9)))
                    continue;  // rounding to float moved this line off the sphere
                const auto hit = intersect_emitters(lights, ray);
                ASSERT_TRUE(hit.has_value()) << distance << " " << inside << " " << k;
                ++hits;
                const double root = std::sqrt(radius * radius - perp2);
                // The float direction is unit to ~1e-7; near the rim t moves by that times
                // distance² / root (the root's conditioning).
                EXPECT_NEAR(hit->t, b - root, 1e-6 * distance * (1.0 + distance / root))
                    << distance << " " << inside << " " << k;
            }
        }
    }
    EXPECT_GE(hits, 120);  // of 144: the near and middle distances all count
}

TEST(EmitterHitTest, PointLikeAndLineLightsAreInvisible) {
    Light point;
    point.emitter = PointLight{Vec3(0, 1, 0), Rgb(100.0f)};
    Light line;
    line.emitter = LineLight{Vec3(-1, 1, 0), Vec3(1, 1, 0), Rgb(10.0f)};
    const std::vector<Light> lights = {point, line};
    EXPECT_FALSE(has_visible_emitters(lights));
    EXPECT_FALSE(intersect_emitters(lights, Ray{Vec3(0, 0, 0), Vec3(0, 1, 0), 0, kInfinity}));
}

}  // namespace
}  // namespace kasumi
