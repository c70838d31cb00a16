// Shadow maps against ray-traced shadows: identical away from shadow boundaries, different only
// within a few texels of them (so the differing area shrinks as the resolution grows), no
// self-shadowing on lit surfaces; area-light maps approach the sampled soft shadow.
#include "surface/shadows/shadow_map.h"

#include "core/rng.h"
#include "lights/light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

Shape quad(const std::array<Vec3, 4>& v) {
    Shape s;
    s.geometry = QuadShape{v};
    return s;
}
Shape box(const Vec3& lo, const Vec3& hi) {
    Shape s;
    s.geometry = BoxShape{lo, hi};
    return s;
}
Shape sphere(const Vec3& c, float r) {
    Shape s;
    s.geometry = SphereShape{c, r};
    return s;
}

/// A 12 m floor, a floating tilted-free box, a ball and a plate: shadows with straight and
/// curved boundaries, none touching its caster (so no contact region where bias matters).
std::vector<Shape> test_shapes() {
    return {quad({Vec3(-6, 0, 6), Vec3(6, 0, 6), Vec3(6, 0, -6), Vec3(-6, 0, -6)}),
            box(Vec3(-1.2f, 0.8f, -0.6f), Vec3(-0.2f, 1.6f, 0.3f)),
            sphere(Vec3(1.0f, 1.2f, 0.8f), 0.45f),
            quad({Vec3(0.2f, 2.0f, -1.6f), Vec3(1.4f, 2.0f, -1.6f), Vec3(1.4f, 2.1f, -0.8f),
                  Vec3(0.2f, 2.1f, -0.8f)})};
}

Light directional_light() {
    Light l;
    l.emitter = DirectionalLight{glm::normalize(Vec3(0.35f, -1.0f, 0.2f)), Rgb(1.0f)};
    l.shadows = ShadowMode::Map;
    return l;
}
Light point_light() {
    Light l;
    l.emitter = PointLight{Vec3(0.7f, 3.6f, 0.4f), Rgb(1.0f)};
    l.shadows = ShadowMode::Map;
    return l;
}
Light spot_light() {
    Light l;
    SpotLight s;
    s.position = Vec3(-0.3f, 4.0f, 0.2f);
    s.direction = Vec3(0.0f, -1.0f, 0.0f);
    s.cos_cone = std::cos(radians(45.0f));
    s.cos_falloff = s.cos_cone;
    s.intensity = Rgb(1.0f);
    l.emitter = s;
    l.shadows = ShadowMode::Map;
    return l;
}

/// Ray-traced visibility of `light_point` (or of the direction of a directional light).
bool ray_visible(const SurfaceScene& scene, const Light& light, const Vec3& p, const Vec3& n,
                 const Vec3& light_point) {
    if (const auto* d = std::get_if<DirectionalLight>(&light.emitter)) {
        const Vec3 wi = -d->direction;
        return !scene.occluded(Ray{offset_ray_origin(p, n, wi), wi, 0.0f, kInfinity});
    }
    const Vec3 to = light_point - p;
    const float dist = glm::length(to);
    const Vec3 o = offset_ray_origin(p, n, to / dist);
    return !scene.occluded(Ray{o, to / dist, 0.0f, glm::length(light_point - o) * (1 - 1e-5f)});
}

Vec3 light_point(const Light& light) {
    return incident_light(light, Vec3(0.0f)).light_position;
}

struct FloorComparison {
    int points = 0;
    int differ = 0;
    int differ_interior = 0;  ///< differing points farther than `band` texels from a boundary
};

/// Compares map and ray visibility on a grid of floor points over [-4, 4]². A point is
/// interior when the ray-traced visibility is the same at it and at 8 neighbours `band`
/// texel footprints away.
FloorComparison compare_floor(const SurfaceScene& scene, const Light& light, int grid, float band) {
    const LightShadowMaps maps(light, scene);
    const Vec3 n(0.0f, 1.0f, 0.0f);
    const Vec3 lp = light_point(light);
    const auto& projector = maps.projectors().front();
    FloorComparison c;
    for (int i = 0; i < grid; ++i) {
        for (int j = 0; j < grid; ++j) {
            const Vec3 p(-4.0f + 8.0f * (i + 0.5f) / grid, 0.0f, -4.0f + 8.0f * (j + 0.5f) / grid);
            const Vec3 to_light = std::holds_alternative<DirectionalLight>(light.emitter)
                                      ? -std::get<DirectionalLight>(light.emitter).direction
                                      : glm::normalize(lp - p);
            if (to_light.y <= 0.0f)
                continue;
            const bool ray = ray_visible(scene, light, p, n, lp);
            const float map = maps.visibility(p, n, lp);
            EXPECT_TRUE(map == 0.0f || map == 1.0f) << "pcf_radius 0 gives hard shadows";
            ++c.points;
            if (ray == (map == 1.0f))
                continue;
            ++c.differ;
            // The texel's footprint on the floor is its size over cos θ.
            float texel = 0.0f;
            for (const DepthView& v : projector.views) {
                const ViewProjection proj = project(v, p);
                if (proj.inside)
                    texel = std::max(texel, proj.texel_size);
            }
            const float step = band * texel / to_light.y;
            bool interior = true;
            for (int a = -1; a <= 1 && interior; ++a)
                for (int b = -1; b <= 1 && interior; ++b)
                    interior = ray_visible(scene, light, p + step * Vec3(a, 0, b), n, lp) == ray;
            if (interior)
                ++c.differ_interior;
        }
    }
    return c;
}

class HardShadowMapTest : public ::testing::TestWithParam<int> {};

Light light_for(int kind, int resolution) {
    Light l = kind == 0 ? directional_light() : kind == 1 ? spot_light() : point_light();
    l.shadow_map.resolution = resolution;
    l.shadow_map.pcf_radius = 0;
    return l;
}

// Away from shadow boundaries (3 texel footprints), map and rays agree exactly; near them the
// differing area is a band whose width is a few texels, so it shrinks ~ 1/resolution: from 256²
// to 1024² it must shrink by more than 2 (4 expected).
TEST_P(HardShadowMapTest, AgreesWithRaysExceptNearBoundaries) {
    const SurfaceScene scene(test_shapes());
    const FloorComparison coarse = compare_floor(scene, light_for(GetParam(), 256), 240, 3.0f);
    const FloorComparison fine = compare_floor(scene, light_for(GetParam(), 1024), 240, 3.0f);
    EXPECT_GT(coarse.points, 40000);
    EXPECT_EQ(coarse.differ_interior, 0);
    EXPECT_EQ(fine.differ_interior, 0);
    EXPECT_GT(coarse.differ, 0) << "a 256² map cannot resolve every boundary point";
    EXPECT_LT(2 * fine.differ, coarse.differ);
    // Bound from the boundary length: the shadows' outlines are under 20 m on the floor, each
    // differing point lies within a band of ±1 texel footprint (< 8 m / 256 · 1.5 here) around
    // them, and a grid cell is (8 m / 240)².
    const float cell = 8.0f / 240.0f;
    EXPECT_LT(coarse.differ, 20.0f * 2.0f * (8.0f / 256.0f * 1.5f) / (cell * cell));
}

INSTANTIATE_TEST_SUITE_P(Lights, HardShadowMapTest, ::testing::Values(0, 1, 2),
                         [](const ::testing::TestParamInfo<int>& p) {
                             return std::string(p.param == 0   ? "Directional"
                                                : p.param == 1 ? "Spot"
                                                               : "PointCube");
                         });

// No shadow acne: lit points on the ball, the box top and the floor stay lit with PCF, at the
// default bias, wherever the light arrives at least 10° above the surface.
TEST(ShadowMapTest, NoSelfShadowingOnLitSurfaces) {
    const SurfaceScene scene(test_shapes());
    for (int kind = 0; kind < 3; ++kind) {
        Light light = light_for(kind, 512);
        light.shadow_map.pcf_radius = 2;
        const LightShadowMaps maps(light, scene);
        const Vec3 lp = light_point(light);
        int tested = 0;
        Pcg32 rng(7, 3);
        for (int k = 0; k < 4000; ++k) {
            // Points on the ball's surface and on the box's top face.
            Vec3 p, n;
            if (k % 2 == 0) {
                const Vec2 u = rng.next_vec2();
                const float z = 1.0f - 2.0f * u.x, phi = kTwoPi * u.y;
                n = Vec3(safe_sqrt(1 - z * z) * std::cos(phi), z,
                         safe_sqrt(1 - z * z) * std::sin(phi));
                p = Vec3(1.0f, 1.2f, 0.8f) + 0.45f * n;
            } else {
                const Vec2 u = rng.next_vec2();
                p = Vec3(-1.2f + 1.0f * u.x, 1.6f, -0.6f + 0.9f * u.y);
                n = Vec3(0, 1, 0);
            }
            const Vec3 to_light = kind == 0 ? -std::get<DirectionalLight>(light.emitter).direction
                                            : glm::normalize(lp - p);
            if (glm::dot(n, to_light) < std::sin(radians(10.0f)) ||
                !ray_visible(scene, light, p, n, lp))
                continue;
            ++tested;
            EXPECT_EQ(maps.visibility(p, n, lp), 1.0f)
                << "kind " << kind << " at " << p.x << "," << p.y << "," << p.z;
        }
        EXPECT_GT(tested, 1000);
    }
}

// PCF turns the hard edge into a ramp: values between 0 and 1 appear only near boundaries and
// the filtered value is the fraction of lit taps, a multiple of 1/(2r+1)².
TEST(ShadowMapTest, PercentageCloserFilterIsFractionOfTaps) {
    const SurfaceScene scene(test_shapes());
    Light light = light_for(2, 512);
    light.shadow_map.pcf_radius = 1;
    const LightShadowMaps maps(light, scene);
    const Vec3 lp = light_point(light);
    int partial = 0;
    for (int i = 0; i < 400; ++i) {
        const Vec3 p(-3.0f + 6.0f * (i + 0.5f) / 400, 0.0f, 0.1f);
        const float v = maps.visibility(p, Vec3(0, 1, 0), lp);
        EXPECT_NEAR(v * 9.0f, std::round(v * 9.0f), 1e-5f);
        partial += (v > 0.0f && v < 1.0f) ? 1 : 0;
    }
    EXPECT_GT(partial, 0);
}

// A directional map is fitted to the scene bounds: every corner of the bounds projects inside
// the map, and the near plane lies before the whole scene.
TEST(ShadowMapTest, OrthographicFitCoversSceneBounds) {
    const SurfaceScene scene(test_shapes());
    const LightShadowMaps maps(directional_light(), scene);
    const DepthView& v = maps.projectors().front().views.front();
    const Bounds3 b = scene.bounds();
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y,
                          (c & 4) ? b.max.z : b.min.z);
        const ViewProjection p = project(v, corner);
        EXPECT_GT(p.depth, 0.0f);
        EXPECT_GE(p.texel.x, -0.5f);
        EXPECT_LE(p.texel.x, v.resolution - 0.5f);
        EXPECT_GE(p.texel.y, -0.5f);
        EXPECT_LE(p.texel.y, v.resolution - 0.5f);
    }
}

// Area lights: the maps from K points approximate visibility to each sampled point by
// visibility to the nearest of the K points. The mean visible fraction under a plate in the
// penumbra converges to the ray-traced one as K grows (the error is bounded by the light's
// size over √K relative to the penumbra width, so 64 views must beat 4 views).
TEST(ShadowMapTest, AreaLightViewsConvergeToRayTracedSoftShadow) {
    const std::vector<Shape> shapes = {
        quad({Vec3(-6, 0, 6), Vec3(6, 0, 6), Vec3(6, 0, -6), Vec3(-6, 0, -6)}),
        quad({Vec3(-3, 1, 3), Vec3(0, 1, 3), Vec3(0, 1, -3), Vec3(-3, 1, -3)})};
    const SurfaceScene scene(shapes);
    const float s = 1.0f, h_light = 3.0f;
    const auto make = [&](int views) {
        Light l;
        l.emitter = make_polygon_light({Vec3(-s / 2, h_light, s / 2), Vec3(-s / 2, h_light, -s / 2),
                                        Vec3(s / 2, h_light, -s / 2), Vec3(s / 2, h_light, s / 2)},
                                       Rgb(1.0f), false);
        l.shadows = ShadowMode::Map;
        l.shadow_map.views = views;
        l.shadow_map.resolution = 256;
        l.shadow_map.pcf_radius = 0;
        return l;
    };
    ASSERT_LT(std::get<PolygonLight>(make(1).emitter).normal.y, 0.0f) << "faces the floor";
    const auto mean_error = [&](int views) {
        const Light light = make(views);
        const LightShadowMaps maps(light, scene);
        const Vec3 n(0, 1, 0);
        double error = 0.0;
        int points = 0;
        // The penumbra under the plate's edge x = 0 spans |x| < s h / (H − h) / 2 = 0.25 m.
        for (int i = 0; i < 21; ++i) {
            const Vec3 p(-0.25f + 0.5f * i / 20.0f, 0.0f, 0.0f);
            double v_map = 0.0, v_ray = 0.0;
            const int m = 32;
            for (int a = 0; a < m; ++a) {
                for (int b = 0; b < m; ++b) {
                    const Vec2 u((a + 0.5f) / m, (b + 0.5f) / m);
                    const IncidentLight in = sample_incident(light, p, u);
                    v_map += maps.visibility(p, n, in.light_position);
                    v_ray += ray_visible(scene, light, p, n, in.light_position) ? 1.0 : 0.0;
                }
            }
            error += std::abs(v_map - v_ray) / (m * m);
            ++points;
        }
        return error / points;
    };
    const double coarse = mean_error(4), fine = mean_error(32);
    EXPECT_LT(fine, coarse);
    EXPECT_LT(fine, 0.5 / std::sqrt(32.0) + 0.02);
}

}  // namespace
}  // namespace kasumi
