/// The area lights as rays see them (lights/light_hit.h), for every area light in a few
/// configurations: sample_pdf is the density of sample_incident's directions (each sample's
/// irradiance times its pdf is the luminance; the pdf integrates to 1 over the sphere of
/// directions), and intersect() reproduces the closed-form irradiance when directions are
/// sampled without the light (E = ∫ L(w) cos θ dω over a cone holding the light).
///
/// False-failure rate: each statistical check allows 4.5 standard errors (two-sided 7e-6);
/// with the 12 checks of this file below 1e-4 per run; seeds are fixed. Each requires its
/// standard error to be below 0.4 %, so a 2 % error in a pdf or an intersection fails it.
#include "lights/light_hit.h"

#include "core/sampling.h"
#include "lights/polygon_light.h"
#include "tests/sample_mean.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace kasumi {
namespace {

struct LightCase {
    std::string name;
    Light light;
    Vec3 p;
    Vec3 n;  ///< receiver normal for the irradiance check
};

template <class Emitter>
Light light_of(Emitter emitter) {
    Light light;
    light.emitter = std::move(emitter);
    return light;
}

const std::vector<LightCase>& cases() {
    const Rgb l(2.0f, 3.0f, 4.0f);
    static const std::vector<LightCase> c = {
        {"sphere_near", light_of(SphereLight{Vec3(0.3f, 0.2f, 2.0f), 0.8f, l}), Vec3(0.0f),
         glm::normalize(Vec3(1.0f, 0.0f, 0.3f))},  // straddles the receiver's horizon
        {"sphere_far", light_of(SphereLight{Vec3(5.0f, -8.0f, 17.0f), 0.3f, l}), Vec3(0.1f),
         Vec3(0.0f, 0.0f, 1.0f)},
        {"quad_front",
         light_of(make_polygon_light(
             {Vec3(-1, -1, 2), Vec3(-1, 1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2)}, l, false)),
         Vec3(0.2f, 0.1f, 0.0f), glm::normalize(Vec3(0.5f, 0.0f, 1.0f))},
        {"quad_two_sided_behind",
         light_of(make_polygon_light(
             {Vec3(-1, -1, 2), Vec3(1, -1, 2), Vec3(1, 1, 2), Vec3(-1, 1, 2)}, l, true)),
         Vec3(0.4f, -0.3f, 0.0f), Vec3(0.0f, 0.0f, 1.0f)},
        {"triangle_tilted",
         light_of(make_polygon_light({Vec3(0, 0, 1), Vec3(2, 0, 3), Vec3(0, 2, 2.5f)}, l, true)),
         Vec3(0.0f, 0.0f, -0.5f), glm::normalize(Vec3(-0.2f, 0.3f, 1.0f))},
        {"pentagon",
         light_of(make_polygon_light(
             {Vec3(1, 0, 1.5f), Vec3(0.31f, 0.95f, 1.5f), Vec3(-0.81f, 0.59f, 1.5f),
              Vec3(-0.81f, -0.59f, 1.5f), Vec3(0.31f, -0.95f, 1.5f)},
             l, true)),
         Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f)},
    };
    return c;
}

/// A cone about the light's centre that holds every direction from p to the light.
struct BoundingCone {
    Vec3 axis;
    float one_minus_cos;  ///< 1 − cos of the half-angle
};

BoundingCone bounding_cone(const Light& light, const Vec3& p) {
    if (const auto* sphere = std::get_if<SphereLight>(&light.emitter)) {
        const Vec3 axis = glm::normalize(sphere->center - p);
        const float sin_sigma = sphere->radius / glm::length(sphere->center - p);
        const float sigma = std::min(1.1f * std::asin(sin_sigma), kPi);
        return {axis, 2.0f * std::sin(0.5f * sigma) * std::sin(0.5f * sigma)};
    }
    const auto& polygon = std::get<PolygonLight>(light.emitter);
    Vec3 centroid(0.0f);
    for (const Vec3& v : polygon.vertices)
        centroid += v / static_cast<float>(polygon.vertices.size());
    const Vec3 axis = glm::normalize(centroid - p);
    float cos_min = 1.0f;
    for (const Vec3& v : polygon.vertices)
        cos_min = std::min(cos_min, glm::dot(axis, glm::normalize(v - p)));
    const float half_angle = std::min(1.05f * std::acos(cos_min), kPi);
    return {axis, 1.0f - std::cos(half_angle)};
}

/// Mean over n directions uniform in the cone of g(w) / q, q = 1 / (2π (1 − cos)) per sr: an
/// estimate of ∫_cone g dω.
template <class G>
MeanAndError cone_integral(const BoundingCone& cone, int n, uint64_t seed, G&& g) {
    const double inv_q = 2.0 * kPiD * cone.one_minus_cos;
    Pcg32 rng(seed, 5);
    SampleMean mean;
    for (int k = 0; k < n; ++k) {
        const Vec2 u = rng.next_vec2();
        const Vec3 w = direction_about(cone.axis, 1.0f - u.x * cone.one_minus_cos, kTwoPi * u.y);
        mean.add(g(w) * inv_q);
    }
    return mean.result();
}

class LightHitProperties : public ::testing::TestWithParam<LightCase> {};

TEST_P(LightHitProperties, EachSampleCarriesItsPdf) {
    // Irradiance at normal incidence of a sample = L / pdf_ω (lights/light.h), so
    // luminance(irradiance) · sample_pdf = luminance(L).
    const LightCase& c = GetParam();
    const float l = luminance(Rgb(2.0f, 3.0f, 4.0f));
    Pcg32 rng(31, 7);
    int checked = 0;
    for (int k = 0; k < 10000; ++k) {
        const IncidentLight in = sample_incident(c.light, c.p, rng.next_vec2());
        if (is_black(in.irradiance))
            continue;
        ++checked;
        ASSERT_NEAR(luminance(in.irradiance) * sample_pdf(c.light, c.p, in.wi), l, 1e-3f * l)
            << c.name << " sample " << k;
    }
    EXPECT_GT(checked, 5000) << c.name;
}

TEST_P(LightHitProperties, PdfIntegratesToOneOverTheSphere) {
    const LightCase& c = GetParam();
    const MeanAndError e =
        cone_integral(bounding_cone(c.light, c.p), 1000000, 11,
                      [&](const Vec3& w) { return sample_pdf(c.light, c.p, w); });
    EXPECT_LT(e.stderr_, 0.004) << c.name;
    EXPECT_NEAR(e.mean, 1.0, 4.5 * e.stderr_ + 1e-4) << c.name;
}

TEST_P(LightHitProperties, RaysThatMeetTheLightGiveTheClosedFormIrradiance) {
    // E = ∫ L_seen(w) max(0, n·w) dω, L_seen from intersect() (0 behind a one-sided light).
    const LightCase& c = GetParam();
    const double closed = luminance(unshadowed_irradiance(c.light, c.p, c.n));
    ASSERT_GT(closed, 0.0) << c.name;
    const MeanAndError e =
        cone_integral(bounding_cone(c.light, c.p), 1000000, 13, [&](const Vec3& w) {
            const auto hit = intersect(c.light, Ray{c.p, w, 0.0f, kInfinity});
            return hit ? luminance(hit->radiance) * std::max(0.0f, glm::dot(c.n, w)) : 0.0f;
        });
    EXPECT_LT(e.stderr_, 0.004 * closed) << c.name;
    EXPECT_NEAR(e.mean, closed, 4.5 * e.stderr_ + 1e-4 * closed) << c.name;
}

INSTANTIATE_TEST_SUITE_P(AreaLights, LightHitProperties, ::testing::ValuesIn(cases()),
                         [](const auto& param_info) { return param_info.param.name; });

TEST(LightHit, OneSidedPolygonBlocksFromBehindWithoutRadiance) {
    const Light light = light_of(make_polygon_light(
        {Vec3(-1, -1, 2), Vec3(-1, 1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2)}, Rgb(1.0f), false));
    const auto front = intersect(light, Ray{Vec3(0.0f), Vec3(0, 0, 1), 0.0f, kInfinity});
    ASSERT_TRUE(front);
    EXPECT_FLOAT_EQ(front->t, 2.0f);
    const auto behind = intersect(light, Ray{Vec3(0, 0, 4), Vec3(0, 0, -1), 0.0f, kInfinity});
    ASSERT_TRUE(behind);
    EXPECT_FALSE(is_black(front->radiance));
    EXPECT_TRUE(is_black(behind->radiance));
}

TEST(LightHit, SphereSeenFromInsideIsNotHit) {
    const Light light = light_of(SphereLight{Vec3(0.0f), 1.0f, Rgb(1.0f)});
    EXPECT_FALSE(intersect(light, Ray{Vec3(0.2f, 0.0f, 0.0f), Vec3(1, 0, 0), 0.0f, kInfinity}));
    EXPECT_EQ(sample_pdf(light, Vec3(0.2f, 0.0f, 0.0f), Vec3(1, 0, 0)), 0.0f);
}

TEST(LightHit, SmallDistantSphereIsHitWithoutCancellation) {
    // A 1 mm sphere 1 km away: b² − c in float loses every digit; the stable form does not.
    const Light light = light_of(SphereLight{Vec3(0.0f, 0.0f, 1000.0f), 1e-3f, Rgb(1.0f)});
    const auto hit = intersect(light, Ray{Vec3(0.0f), Vec3(0, 0, 1), 0.0f, kInfinity});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1000.0f - 1e-3f, 1e-4f);
}

TEST(LightHit, DeltaAndLineLightsAreNeverHitAndHaveNoSolidAnglePdf) {
    const Ray ray{Vec3(0.0f), Vec3(0, 0, 1), 0.0f, kInfinity};
    for (const Light& light : {light_of(PointLight{Vec3(0, 0, 1), Rgb(1.0f)}),
                               light_of(DirectionalLight{Vec3(0, 0, -1), Rgb(1.0f)}),
                               light_of(LineLight{Vec3(-1, 0, 1), Vec3(1, 0, 1), Rgb(1.0f)})}) {
        EXPECT_FALSE(intersect(light, ray)) << light_type_name(light);
        EXPECT_EQ(sample_pdf(light, ray.origin, ray.direction), 0.0f) << light_type_name(light);
    }
}

}  // namespace
}  // namespace kasumi
