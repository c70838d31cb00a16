// The reference path tracer (gi/path_tracer.h); its Phong BRDF is tested in
// tests/surface/phong_brdf_test.cpp.
#include "gi/path_tracer.h"
#include "core/error.h"
#include "core/sampling.h"
#include "render/probe.h"
#include "tests/gi/gi_test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

TEST(PathTracerTest, RejectsMaterialsThatCreateEnergy) {
    const std::string scene = R"({
      "materials": {"hot": {"type": "phong", "kd": 0.8, "ks": 0.4}},
      "shapes": [{"type": "quad", "material": "hot",
                  "vertices": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]}],
      "render": {"gi": "path"}})";
    try {
        gi_runtime_from_text(scene);
        FAIL() << "expected an input error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        EXPECT_NE(std::string(e.what()).find("/materials/hot"), std::string::npos) << e.what();
    }
}

TEST(PathTracerTest, PointLightOnALoneLambertianPlaneIsDirectLightOnly) {
    // One plane under a point light: no interreflection, so the path tracer must give the
    // direct light ρ/π · I cos θ / r² exactly as the direct renderer does (render.gi none).
    const auto make = [](const char* gi) {
        return gi_runtime_from_text(std::string(R"({
          "materials": {"floor": {"type": "phong", "kd": 0.5}},
          "shapes": [{"type": "quad", "material": "floor",
                      "vertices": [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]}],
          "lights": [{"type": "point", "position": [0, 2, 0], "intensity_cd": 100}],
          "render": {"gi": ")") + gi +
                                    R"("}})");
    };
    const auto path = make("path");
    const Vec3 origin(1, 1, 1), target(0.5f, 0, 0.2f);
    const RadianceProbe p = probe_radiance(*path, origin, glm::normalize(target - origin), 16);
    const Vec3 to_light = Vec3(0, 2, 0) - target;
    const float r2 = glm::dot(to_light, to_light);
    const float expected = 0.5f / kPi * 100.0f * (to_light.y / std::sqrt(r2)) / r2;
    EXPECT_NEAR(p.radiance.g, expected, 1e-4f * expected);
    EXPECT_EQ(p.stderr_.g, 0.0f);  // one delta light, one plane: no randomness left
}

TEST(PathTracerTest, MirrorShowsThePolygonLightAndDirectLightAgreesWithMis) {
    // A polygon light seen in a mirror (only bounce rays can reach it: delta BSDF, weight 1),
    // and a diffuse floor lit by the same light through NEE + BSDF sampling (MIS): the floor's
    // centre must get L F ρ with F from Howell B-3; 4 standard errors (false-failure ≈ 6e-5).
    const auto runtime = gi_runtime_from_text(R"({
      "materials": {"floor": {"type": "phong", "kd": 0.5},
                    "mirror": {"type": "mirror", "kr": 0.9}},
      "shapes": [{"type": "quad", "material": "floor",
                  "vertices": [[-0.5, 0, -0.5], [-0.5, 0, 0.5], [0.5, 0, 0.5], [0.5, 0, -0.5]]},
                 {"type": "quad", "material": "mirror",
                  "vertices": [[3, -1, -1], [3, -1, 1], [3, 3, 1], [3, 3, -1]]}],
      "lights": [{"type": "polygon", "luminance_cd_m2": 1000,
                  "vertices": [[-0.5, 1, -0.5], [0.5, 1, -0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]]}],
      "render": {"gi": "path"}})");
    // The light (at y = 1, facing down) seen in the mirror x = 3 from below it.
    const Vec3 eye(2.0f, 0.5f, 0.0f);
    const Vec3 mirrored_light(6.0f, 1.0f, 0.0f);  // the light's centre reflected in x = 3
    const RadianceProbe seen =
        probe_radiance(*runtime, eye, glm::normalize(mirrored_light - eye), 16);
    EXPECT_NEAR(seen.radiance.g, 0.9f * 1000.0f, 0.9f);
    // The floor's centre.
    const double x = 0.5, f = 4.0 / (2.0 * kPiD) *
                              (x / std::sqrt(1 + x * x) * std::atan(x / std::sqrt(1 + x * x)) * 2);
    const Vec3 origin(1.5f, 0.3f, 0.1f);
    const RadianceProbe p = probe_radiance(*runtime, origin, glm::normalize(-origin), 4000);
    const double expected = 0.5 * f * 1000.0;
    EXPECT_NEAR(p.radiance.g, expected, 4.0 * p.stderr_.g + 1e-3 * expected)
        << "stderr " << p.stderr_.g;
}

}  // namespace
}  // namespace kasumi
