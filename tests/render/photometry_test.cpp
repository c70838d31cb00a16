// Exact answers for the surface stage: photometric units, the cosine and inverse-square laws,
// Phong's specular lobe, shadows, and Beer-Lambert in front of a surface.
#include "render/probe.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

constexpr const char* kFloor = R"(
  "materials": {"white": {"type": "phong", "kd": 1.0}, "grey": {"type": "phong", "kd": 0.5}},
  "shapes": [{"type": "quad", "material": "white",
              "vertices": [[-50, 0, 50], [50, 0, 50], [50, 0, -50], [-50, 0, -50]]})";

Rgb look_down_at(const SceneRuntime& scene, Vec3 point, int spp = 1) {
    return probe_radiance(scene, point + Vec3(0.0f, 3.0f, 0.0f), Vec3(0, -1, 0), spp).radiance;
}

TEST(Photometry, DirectionalLightOnWhiteLambertianGivesEOverPi) {
    const auto scene = runtime_from_text(std::string("{") + kFloor + R"(],
        "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}]})");
    const Rgb l = look_down_at(*scene, Vec3(1.0f, 0.0f, 2.0f));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(l[c], 1000.0f / kPi, 1e-3f);
}

TEST(Photometry, DirectionalLightFollowsCosineLaw) {
    for (float angle_deg : {0.0f, 30.0f, 60.0f, 85.0f}) {
        const float a = radians(angle_deg);
        const std::string dir =
            "[" + std::to_string(std::sin(a)) + ", " + std::to_string(-std::cos(a)) + ", 0]";
        const auto scene = runtime_from_text(std::string("{") + kFloor + R"(],
            "lights": [{"type": "directional", "direction": )" +
                                             dir + R"(, "illuminance_lux": 500}]})");
        EXPECT_NEAR(look_down_at(*scene, Vec3(0.0f)).g, 500.0f * std::cos(a) / kPi, 2e-3f)
            << angle_deg;
    }
}

TEST(Photometry, PointLightInverseSquareAndCosine) {
    const auto scene = runtime_from_text(std::string("{") + kFloor + R"(],
        "lights": [{"type": "point", "position": [0, 2, 0], "intensity_cd": 50}]})");
    for (float x : {0.0f, 1.5f, 4.0f, 10.0f}) {
        const float r2 = 4.0f + x * x;
        const float cos_theta = 2.0f / std::sqrt(r2);
        const float expected = 50.0f * cos_theta / r2 / kPi;
        EXPECT_NEAR(look_down_at(*scene, Vec3(x, 0.0f, 0.0f)).r, expected, 1e-5f * expected + 1e-7f)
            << x;
    }
}

TEST(Photometry, PhongSpecularPeakMatchesNormalisedLobe) {
    // Light from 45°, viewer in the mirror direction: L = (kd/π + ks (n+2)/(2π)) E cos θ.
    const auto scene = runtime_from_text(R"({
        "materials": {"shiny": {"type": "phong", "kd": 0.2, "ks": 0.5, "n": 30}},
        "shapes": [{"type": "quad", "material": "shiny",
                    "vertices": [[-50, 0, 50], [50, 0, 50], [50, 0, -50], [-50, 0, -50]]}],
        "lights": [{"type": "directional", "direction": [1, -1, 0], "illuminance_lux": 100}]})");
    const Vec3 target(0.0f);
    const Vec3 view_dir = glm::normalize(Vec3(-1.0f, -1.0f, 0.0f));  // wo = (1, 1, 0)/√2
    const Rgb l = probe_radiance(*scene, target - 4.0f * view_dir, view_dir, 1).radiance;
    const float expected =
        (0.2f / kPi + 0.5f * 32.0f / (2.0f * kPi)) * 100.0f * std::cos(kPi / 4.0f);
    EXPECT_NEAR(l.g, expected, 1e-4f * expected);
}

TEST(Photometry, ShadowRemovesExactlyTheBlockedLight) {
    // Two point lights; a box hangs between the first and the probed point.
    const std::string lights = R"(
        "lights": [{"name": "a", "type": "point", "position": [0, 4, 0], "intensity_cd": 80},
                   {"name": "b", "type": "point", "position": [3, 4, 0], "intensity_cd": 40}])";
    const std::string blocker =
        R"(, {"type": "box", "material": "white", "min": [-0.5, 1.5, -0.5], "max": [0.5, 2, 0.5]}])";
    const auto open = runtime_from_text(std::string("{") + kFloor + "]," + lights + "}");
    const auto shadowed =
        runtime_from_text(std::string("{") + kFloor + blocker + "," + lights + "}");
    const auto only_b = runtime_from_text(std::string("{") + kFloor + R"(],
        "lights": [{"type": "point", "position": [3, 4, 0], "intensity_cd": 40}]})");
    const Vec3 p(0.0f);
    // Probe from the side so the ray is not blocked by the box itself.
    const Vec3 eye(-3.0f, 0.5f, 0.0f);
    const Rgb l_open = probe_radiance(*open, eye, p - eye, 1).radiance;
    const Rgb l_shadow = probe_radiance(*shadowed, eye, p - eye, 1).radiance;
    const Rgb l_b = probe_radiance(*only_b, eye, p - eye, 1).radiance;
    const float a_alone = 80.0f / 16.0f / kPi;  // light a straight above at 4 m
    EXPECT_NEAR(l_open.g, a_alone + l_b.g, 1e-5f);
    EXPECT_NEAR(l_shadow.g, l_b.g, 1e-6f);  // unshadowed minus the blocked light

    // With only the blocked light, the point receives exactly nothing.
    const auto single = runtime_from_text(std::string("{") + kFloor + blocker + R"(,
        "lights": [{"type": "point", "position": [0, 4, 0], "intensity_cd": 80}]})");
    EXPECT_EQ(probe_radiance(*single, eye, p - eye, 1).radiance, Rgb(0.0f));
}

TEST(Photometry, AbsorbingFogDimsBySurfaceBeerLambert) {
    // Purely absorbing fog: L = exp(-sigma_a d) L_surface, and no in-scattering runs.
    const auto scene = runtime_from_text(std::string("{") + kFloor + R"(],
        "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
        "media": [{"type": "homogeneous", "bounds": [[-100, 0.5, -100], [100, 100, 100]],
                   "sigma_a": [0.1, 0.2, 0.4], "sigma_s": 0}]})");
    EXPECT_FALSE(scene->plan().in_scattering);
    const Rgb l = probe_radiance(*scene, Vec3(0.0f, 3.0f, 0.0f), Vec3(0, -1, 0), 1).radiance;
    // Camera ray crosses 2.5 m of fog; the sunlight crosses 99.5 m before reaching the floor.
    const Rgb sigma(0.1f, 0.2f, 0.4f);
    for (int c = 0; c < 3; ++c) {
        const float expected =
            std::exp(-sigma[c] * 2.5f) * std::exp(-sigma[c] * 99.5f) * 1000.0f / kPi;
        EXPECT_NEAR(l[c], expected, 1e-4f * expected + 1e-12f) << c;
    }
}

TEST(Photometry, AmbientTermIsKaTimesAmbient) {
    const auto scene = runtime_from_text(R"({
        "ambient": [0.5, 1.0, 2.0],
        "materials": {"m": {"type": "phong", "ka": 0.4, "kd": 0.0}},
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
    const Rgb l = probe_radiance(*scene, Vec3(0.0f, 0.0f, 5.0f), Vec3(0, 0, -1), 1).radiance;
    EXPECT_NEAR(l.r, 0.2f, 1e-6f);
    EXPECT_NEAR(l.b, 0.8f, 1e-6f);
}

}  // namespace
}  // namespace kasumi
