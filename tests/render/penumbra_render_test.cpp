// The renderer's penumbra of a sphere light behind a sphere: the radiance of a white
// Lambertian floor seen through the renderer (probe_radiance: camera ray, shade_surface, the
// sampled shadow rays and their ratio weight) against kd/π L Ω_visible, with the visible
// projected solid angle of the light integrated here by a deterministic quadrature over the
// light's cone (an independent answer: no code of the renderer or of surface/ is used for it).
#include "render/probe.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

constexpr double kLightLuminance = 1000.0;  // cd/m²
const DVec3 kLightCenter(0.0, 2.0, 0.0);
constexpr double kLightRadius = 0.3;
const DVec3 kOccluderCenter(0.0, 1.0, 0.0);
constexpr double kOccluderRadius = 0.2;

const std::string kScene = R"({
  "materials": {"white": {"type": "phong", "kd": 1.0}},
  "shapes": [
    {"type": "quad", "material": "white",
     "vertices": [[-20, 0, 20], [20, 0, 20], [20, 0, -20], [-20, 0, -20]]},
    {"type": "sphere", "material": "white", "center": [0, 1, 0], "radius": 0.2}],
  "lights": [{"type": "sphere", "center": [0, 2, 0], "radius": 0.3, "luminance_cd_m2": 1000,
              "samples": 64}]})";

/// True when the ray p + t w (t > 0) meets the occluder sphere.
bool meets_occluder(const DVec3& p, const DVec3& w) {
    const DVec3 oc = p - kOccluderCenter;
    const double b = glm::dot(oc, w);
    const double c = glm::dot(oc, oc) - kOccluderRadius * kOccluderRadius;
    const double disc = b * b - c;
    return disc > 0.0 && -b + std::sqrt(disc) > 0.0;
}

/// ∫ max(0, n·ω) V(ω) dω over the light's cone as seen from p: midpoint rule in (cos θ, φ)
/// about the cone's axis (uniform in solid angle), nodes x nodes points.
double visible_projected_solid_angle(const DVec3& p, const DVec3& n, int nodes) {
    const DVec3 to_light = kLightCenter - p;
    const double d = glm::length(to_light);
    const DVec3 axis = to_light / d;
    const double cos_sigma = std::sqrt(1.0 - (kLightRadius / d) * (kLightRadius / d));
    const DVec3 helper = std::abs(axis.x) < 0.9 ? DVec3(1, 0, 0) : DVec3(0, 0, 1);
    const DVec3 t1 = glm::normalize(glm::cross(axis, helper));
    const DVec3 t2 = glm::cross(axis, t1);
    const double cell = (1.0 - cos_sigma) * 2.0 * kPiD / (double(nodes) * nodes);
    double sum = 0.0;
    for (int i = 0; i < nodes; ++i) {
        const double c = cos_sigma + (1.0 - cos_sigma) * (i + 0.5) / nodes;
        const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
        for (int j = 0; j < nodes; ++j) {
            const double phi = 2.0 * kPiD * (j + 0.5) / nodes;
            const DVec3 w = c * axis + s * (std::cos(phi) * t1 + std::sin(phi) * t2);
            const double cos_n = glm::dot(n, w);
            if (cos_n > 0.0 && !meets_occluder(p, w))
                sum += cos_n;
        }
    }
    return sum * cell;
}

TEST(RendererPenumbra, SphereLightBehindASphereMatchesTheVisibleSolidAngle) {
    const auto scene = runtime_from_text(kScene);
    const DVec3 up(0, 1, 0);
    for (const double x : {0.2, 0.35, 0.5}) {
        const DVec3 p(x, 0.0, 0.1);
        const double omega = visible_projected_solid_angle(p, up, 1200);
        // Halving the quadrature's step moves it by far less than the 0.3% it is allowed.
        const double coarse = visible_projected_solid_angle(p, up, 600);
        ASSERT_NEAR(coarse, omega, 1e-3 * omega) << x;
        const double exact = kLightLuminance / kPiD * omega;  // kd/π L Ω, kd = 1
        const RadianceProbe probe =
            probe_radiance(*scene, Vec3(p + DVec3(0, 0.05, 0)), Vec3(0, -1, 0), 4096);
        const double rendered = probe.luminance_cd_m2;
        const double se = luminance(probe.stderr_);
        // A penumbra point: part of the light hidden, part seen (fully lit, kd/π L π sin²σ cos θ
        // is at most L (r/d)²).
        const DVec3 to_light = kLightCenter - p;
        const double d2 = glm::dot(to_light, to_light);
        const double lit = kLightLuminance * kLightRadius * kLightRadius / d2;
        EXPECT_GT(exact, 0.1 * lit) << x;
        EXPECT_LT(exact, 0.9 * lit) << x;
        // 4.5 standard errors (false-failure rate 7e-6 per point) plus the quadrature's 0.3%;
        // the bound must stay small enough to catch a 2% bias of the visible fraction.
        const double bound = 4.5 * se + 3e-3 * exact;
        std::printf("x %.2f: rendered %.5f, exact %.5f (%.3f lit), 4.5 se %.5f\n", x, rendered,
                    exact, exact / lit, 4.5 * se);
        EXPECT_LT(bound, 0.012 * exact) << x;
        EXPECT_NEAR(rendered, exact, bound) << x << ": Ω = " << omega;
    }
}

}  // namespace
}  // namespace kasumi
