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
