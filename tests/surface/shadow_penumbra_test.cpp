// Soft shadows of area lights behind a straight occluder edge: the penumbra on the floor lies
// where similar triangles put it, and the sampled shadowed illuminance is an unbiased estimate
// of Lambert's formula for the visible part of the polygon.
//
// Geometry: a floor y = 0, an opaque half-plane y = h, x < 0 (edge along z at x = 0), and a
// light centred above the edge at height H. A floor point (x, 0) sees the light point
// (x_l, H) past the edge iff x + (x_l − x) h/H ≥ 0, i.e. x_l ≥ x (1 − H/h).
#include "core/rng.h"
#include "lights/light.h"
#include "surface/surface_scene.h"
#include "tests/sample_mean.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

constexpr float kH = 3.0f;  // light height, m
constexpr float kh = 1.0f;  // occluder height, m
constexpr float kS = 1.0f;  // side of the square light, m

std::vector<Shape> edge_scene() {
    Shape floor, plate;
    floor.geometry = QuadShape{{Vec3(-8, 0, 8), Vec3(8, 0, 8), Vec3(8, 0, -8), Vec3(-8, 0, -8)}};
    plate.geometry =
        QuadShape{{Vec3(-8, kh, 8), Vec3(0, kh, 8), Vec3(0, kh, -8), Vec3(-8, kh, -8)}};
    return {floor, plate};
}

/// The square light's part with x ≥ x_cut, wound like the light (emitting downward).
std::vector<Vec3> square(float x_lo) {
    const float x_hi = kS / 2;
    return {Vec3(x_lo, kH, kS / 2), Vec3(x_lo, kH, -kS / 2), Vec3(x_hi, kH, -kS / 2),
            Vec3(x_hi, kH, kS / 2)};
}

Light square_light() {
    Light l;
    l.emitter = make_polygon_light(square(-kS / 2), Rgb(1000.0f), false);
    return l;
}

struct Estimate {
    double mean = 0.0;
    double standard_error = 0.0;
    int visible = 0;
    int blocked = 0;
};

/// Mean of luminance(E_k) cos θ_k V_k over n samples of the light from the floor point (x, 0, 0).
Estimate shadowed_illuminance(const SurfaceScene& scene, const Light& light, float x, int n,
                              uint64_t seed) {
    const Vec3 p(x, 0.0f, 0.0f), normal(0.0f, 1.0f, 0.0f);
    Pcg32 rng(seed, 11);
    SampleMean samples;
    Estimate e;
    for (int k = 0; k < n; ++k) {
        const IncidentLight in = sample_incident(light, p, rng.next_vec2());
        const float cos_theta = std::max(0.0f, glm::dot(normal, in.wi));
        const Vec3 o = offset_ray_origin(p, normal, in.wi);
        const bool blocked =
            scene.occluded(Ray{o, in.wi, 0.0f, glm::length(in.light_position - o) * (1 - 1e-5f)});
        (blocked ? e.blocked : e.visible) += 1;
        samples.add(blocked ? 0.0 : luminance(in.irradiance) * cos_theta);
    }
    const MeanAndError r = samples.result();
    e.mean = r.mean;
    e.standard_error = r.stderr_;
    return e;
}

// The umbra ends and the full light begins at x = ∓ s h / (2 (H − h)) = ∓0.25 m (similar
// triangles through the edge). 1 cm outside, all of 8192 samples agree (blocked / visible); 1 cm
// inside, 2% of the light is on the other side, so both kinds occur (a false failure needs
// 0.98^8192 ≈ 1e-72).
TEST(PenumbraTest, PolygonPenumbraWidthMatchesSimilarTriangles) {
    const SurfaceScene scene(edge_scene());
    const Light light = square_light();
    const float half_width = kS * kh / (2.0f * (kH - kh));
    const float d = 0.01f;
    const Estimate umbra = shadowed_illuminance(scene, light, -half_width - d, 8192, 1);
    EXPECT_EQ(umbra.visible, 0);
    const Estimate umbra_edge = shadowed_illuminance(scene, light, -half_width + d, 8192, 2);
    EXPECT_GT(umbra_edge.visible, 0);
    EXPECT_GT(umbra_edge.blocked, 0);
    const Estimate lit = shadowed_illuminance(scene, light, half_width + d, 8192, 3);
    EXPECT_EQ(lit.blocked, 0);
    const Estimate lit_edge = shadowed_illuminance(scene, light, half_width - d, 8192, 4);
    EXPECT_GT(lit_edge.blocked, 0);
    EXPECT_GT(lit_edge.visible, 0);
}

// Across the penumbra the mean of the samples equals Lambert's formula for the visible part
// x_l ≥ x (1 − H/h) of the light (at x = 0 exactly half of it is hidden), within 5 standard
// errors: a two-sided false-failure rate of 5.7e-7 per point. 40000 samples keep the standard
// error under 1% of the unoccluded illuminance, so a bias of 5% would fail.
TEST(PenumbraTest, SampledSoftShadowIsUnbiasedAgainstLambert) {
    const SurfaceScene scene(edge_scene());
    const Light light = square_light();
    const Vec3 normal(0.0f, 1.0f, 0.0f);
    uint64_t seed = 10;
    for (const float x : {-0.2f, -0.1f, 0.0f, 0.1f, 0.2f}) {
        const float x_cut = x * (1.0f - kH / kh);
        const PolygonLight visible = make_polygon_light(square(x_cut), Rgb(1000.0f), false);
        const Vec3 p(x, 0.0f, 0.0f);
        const double expected = luminance(unshadowed_irradiance(visible, p, normal));
        const double unoccluded = luminance(unshadowed_irradiance(light, p, normal));
        const Estimate e = shadowed_illuminance(scene, light, x, 40000, ++seed);
        EXPECT_LT(e.standard_error, 0.01 * unoccluded);
        EXPECT_NEAR(e.mean, expected, 5.0 * e.standard_error)
            << "x = " << x << ", unoccluded " << unoccluded;
        if (x == 0.0f) {
            EXPECT_NEAR(expected, 0.5 * unoccluded, 1e-3 * unoccluded) << "symmetric halves";
        }
    }
}

// A sphere light of radius R: the planes through the edge tangent to the sphere bound the
// penumbra, at |x| = R h / √((H − h)² − R²) (distance from the centre (0, H) to the plane
// through the edge and (x, 0) equals R). 1 cm outside, all samples agree; 1 cm inside, about 1%
// of the visible disc lies across the edge (a cap of depth 2 cm / R), so both kinds occur in
// 8192 samples (a false failure needs 0.99^8192 ≈ 1e-36).
TEST(PenumbraTest, SpherePenumbraWidthMatchesTangentPlanes) {
    const SurfaceScene scene(edge_scene());
    Light light;
    const float radius = 0.3f;
    light.emitter = SphereLight{Vec3(0.0f, kH, 0.0f), radius, Rgb(1000.0f)};
    const float edge = radius * kh / std::sqrt((kH - kh) * (kH - kh) - radius * radius);
    const float d = 0.01f;
    EXPECT_EQ(shadowed_illuminance(scene, light, -edge - d, 8192, 21).visible, 0);
    const Estimate inner = shadowed_illuminance(scene, light, -edge + d, 8192, 22);
    EXPECT_GT(inner.visible, 0);
    EXPECT_GT(inner.blocked, 0);
    EXPECT_EQ(shadowed_illuminance(scene, light, edge + d, 8192, 23).blocked, 0);
    const Estimate outer = shadowed_illuminance(scene, light, edge - d, 8192, 24);
    EXPECT_GT(outer.visible, 0);
    EXPECT_GT(outer.blocked, 0);
}

}  // namespace
}  // namespace kasumi
