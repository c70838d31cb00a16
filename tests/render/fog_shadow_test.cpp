// Shadowed single scattering from a point light in homogeneous fog, against quadrature of the
// airlight integral L = ∫ sigma_s p(theta(t)) I / d(t)² exp(-sigma_t (d(t) + t)) dt over the
// lit part of the ray. A wall that hides half the ray from the light removes exactly that half:
// the shadow shaft.
#include "render/probe.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

constexpr float kSigmaA = 0.05f, kSigmaS = 0.2f, kG = 0.5f, kIntensity = 100.0f;
const Vec3 kLight(0.0f, 2.0f, 0.0f);
const Vec3 kOrigin(-6.0f, 0.5f, 0.0f);  // ray along +x at y = 0.5, inside fog x in [-6, 6]

std::string scene_text(bool wall) {
    std::string text = R"({
        "materials": {"black": {"type": "phong", "kd": 0}},
        "lights": [{"type": "point", "position": [0, 2, 0], "intensity_cd": 100}],
        "media": [{"type": "homogeneous", "bounds": [[-6, -5, -5], [6, 5, 5]], "sigma_a": 0.05,
                   "sigma_s": 0.2, "phase": {"model": "hg", "g": 0.5}}],
        "render": {"volume": {"step_m": 0.05}})";
    if (wall) {
        // A wall at y = 1 over x < 0: it hides the light from the ray exactly where x < 0.
        text += R"(, "shapes": [{"type": "quad", "material": "black",
                     "vertices": [[-60, 1, 60], [0, 1, 60], [0, 1, -60], [-60, 1, -60]]}])";
    }
    return text + "}";
}

/// Midpoint quadrature of the airlight integral over x in [x0, x1] along the ray.
double airlight(double x0, double x1) {
    const HenyeyGreenstein hg{kG};
    const int n = 200000;
    const double dx = (x1 - x0) / n;
    const double sigma_t = kSigmaA + kSigmaS;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = x0 + (i + 0.5) * dx;
        const Vec3 p(static_cast<float>(x), kOrigin.y, 0.0f);
        const Vec3 to_light = kLight - p;
        const double d = glm::length(to_light);
        const float mu = scattering_cosine(Vec3(-1, 0, 0), to_light / static_cast<float>(d));
        const double t = x - kOrigin.x;
        sum += kSigmaS * eval(hg, mu) * kIntensity / (d * d) * std::exp(-sigma_t * (d + t));
    }
    return sum * dx;
}

TEST(FogShadow, PointLightAirlightMatchesQuadratureAndWallCastsShaft) {
    const int spp = 4000;
    const auto open = runtime_from_text(scene_text(false));
    const auto walled = runtime_from_text(scene_text(true));
    const RadianceProbe lit = probe_radiance(*open, kOrigin, Vec3(1, 0, 0), spp);
    const RadianceProbe shaft = probe_radiance(*walled, kOrigin, Vec3(1, 0, 0), spp);
    const double expected_lit = airlight(-6.0, 6.0);
    const double expected_shaft = airlight(0.0, 6.0);
    // 5 standard errors (false-failure rate ~6e-7 each); the bounds must also be tight.
    EXPECT_NEAR(lit.radiance.g, expected_lit, 5.0 * lit.stderr_.g) << "stderr " << lit.stderr_.g;
    EXPECT_NEAR(shaft.radiance.g, expected_shaft, 5.0 * shaft.stderr_.g)
        << "stderr " << shaft.stderr_.g;
    EXPECT_LT(5.0 * lit.stderr_.g, 0.02 * expected_lit);
    EXPECT_LT(5.0 * shaft.stderr_.g, 0.02 * expected_shaft);
    // The shadowed half carries a large share: the shaft is visible, not a rounding effect.
    EXPECT_LT(expected_shaft, 0.8 * expected_lit);
}

}  // namespace
}  // namespace kasumi
