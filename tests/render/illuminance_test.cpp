// The illuminance probe and the surface stage under extended lights: closed forms without
// occluders, umbra and penumbra with one, and the rendered radiance of a white Lambertian floor
// equal to E/π.
#include "render/illuminance.h"
#include "render/probe.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

const std::string kScene = R"({
  "materials": {"white": {"type": "phong", "kd": 1.0}},
  "shapes": [{"type": "quad", "material": "white",
              "vertices": [[-50, 0, 50], [50, 0, 50], [50, 0, -50], [-50, 0, -50]]}
             OCCLUDER],
  "lights": [
    {"name": "panel", "type": "polygon", "luminance_cd_m2": 1000,
     "vertices": [[-0.5, 2, -0.5], [0.5, 2, -0.5], [0.5, 2, 0.5], [-0.5, 2, 0.5]]},
    {"name": "bulb", "type": "sphere", "center": [3, 1.5, 0], "radius": 0.3, "luminance_cd_m2": 500},
    {"name": "tube", "type": "line", "from": [-3, 1.8, -1], "to": [-3, 1.8, 1], "intensity_cd_per_m": 80},
    {"name": "spot", "type": "spot", "position": [0, 3, 3], "direction": [0, -1, -1],
     "intensity_cd": 400, "cone_deg": 60, "falloff_deg": 40}]})";

std::unique_ptr<SceneRuntime> scene_with(const std::string& occluder) {
    std::string text = kScene;
    text.replace(text.find("OCCLUDER"), 8, occluder);
    return runtime_from_text(text);
}

TEST(IlluminanceProbe, WithoutOccludersEveryLightMatchesItsClosedForm) {
    const auto scene = scene_with("");
    const Vec3 at(0.4f, 0.0f, 0.3f), up(0, 1, 0);
    const IlluminanceProbe analytic = probe_illuminance(*scene, at, up, false, 1);
    const IlluminanceProbe shadowed = probe_illuminance(*scene, at, up, true, 20000);
    ASSERT_EQ(analytic.per_light.size(), 4u);
    double sum = 0.0;
    for (size_t i = 0; i < 4; ++i) {
        const LightIlluminance& a = analytic.per_light[i];
        const LightIlluminance& s = shadowed.per_light[i];
        EXPECT_EQ(a.method, IlluminanceMethod::Analytic);
        const double exact = luminance(unshadowed_irradiance(scene->desc().lights[i], at, up));
        EXPECT_NEAR(a.lux, exact, 1e-9 * exact) << a.name;
        EXPECT_GT(exact, 0.0) << a.name;
        // Nothing blocks: the sampled mean agrees within 5 standard errors (false-failure rate
        // 5.7e-7 per light), a delta light's single ray exactly.
        EXPECT_EQ(s.method, i == 3 ? IlluminanceMethod::Ray : IlluminanceMethod::Sampled);
        EXPECT_NEAR(s.lux, exact, 5.0 * s.stderr_lux + 1e-5 * exact) << s.name;
        sum += a.lux;
    }
    EXPECT_NEAR(analytic.lux, sum, 1e-9 * sum);
}

TEST(IlluminanceProbe, UmbraAndPenumbraUnderAnOccluder) {
    // A 0.7 m plate at 1 m under the 1 m panel at 2 m: the umbra under its centre is dark, the
    // penumbra partly lit, and far out the panel is fully seen. Through the plate's plane the panel
    // projects to [(x − 0.5)/2, (x + 0.5)/2]: umbra for |x| <= 0.2, fully lit for |x| >= 1.2.
    const auto scene = scene_with(R"(, {"type": "quad", "material": "white",
        "vertices": [[-0.35, 1, -0.35], [0.35, 1, -0.35], [0.35, 1, 0.35], [-0.35, 1, 0.35]]})");
    const Vec3 up(0, 1, 0);
    const auto panel_lux = [&](float x) {
        return probe_illuminance(*scene, Vec3(x, 0, 0), up, true, 20000).per_light[0];
    };
    const double umbra = panel_lux(0.0f).lux;
    const LightIlluminance penumbra = panel_lux(0.6f);
    const LightIlluminance lit = panel_lux(1.5f);
    const Light& panel = scene->desc().lights[0];
    EXPECT_EQ(umbra, 0.0);
    const double open_penumbra = luminance(unshadowed_irradiance(panel, Vec3(0.6f, 0, 0), up));
    EXPECT_GT(penumbra.lux, 0.1 * open_penumbra);
    EXPECT_LT(penumbra.lux, 0.9 * open_penumbra);
    const double open_lit = luminance(unshadowed_irradiance(panel, Vec3(1.5f, 0, 0), up));
    EXPECT_NEAR(lit.lux, open_lit, 5.0 * lit.stderr_lux + 1e-5 * open_lit);
}

TEST(ExtendedLightShading, WhiteLambertianFloorShowsEOverPiWithoutNoise) {
    // The ratio estimator is exact where the lights are fully visible: one camera sample gives
    // E/π to float precision, whatever the samples drawn.
    const auto scene = scene_with("");
    for (const Vec3 at : {Vec3(0.4f, 0, 0.3f), Vec3(2.0f, 0, -1.0f), Vec3(-2.5f, 0, 0.5f)}) {
        const IlluminanceProbe e = probe_illuminance(*scene, at, Vec3(0, 1, 0), false, 1);
        const Rgb l = probe_radiance(*scene, at + Vec3(0, 0.5f, 0), Vec3(0, -1, 0), 1).radiance;
        EXPECT_NEAR(luminance(l), e.lux / kPiD, 1e-4 * e.lux / kPiD) << at.x;
    }
}

TEST(ExtendedLightShading, ShadowsNoneIgnoresTheOccluder) {
    auto desc = scene_from_text([] {
        std::string text = kScene;
        return text.replace(text.find("OCCLUDER"), 8, R"(, {"type": "quad", "material": "white",
            "vertices": [[-0.2, 1, -0.2], [0.2, 1, -0.2], [0.2, 1, 0.2], [-0.2, 1, 0.2]]})");
    }());
    for (Light& light : desc.lights)
        light.shadows = ShadowMode::None;
    const SceneRuntime scene(std::move(desc));
    const IlluminanceProbe e = probe_illuminance(scene, Vec3(0), Vec3(0, 1, 0), true, 100);
    const Rgb l = probe_radiance(scene, Vec3(0, 0.5f, 0), Vec3(0, -1, 0), 1).radiance;
    EXPECT_EQ(e.per_light[0].method, IlluminanceMethod::Analytic);
    EXPECT_NEAR(luminance(l), e.lux / kPiD, 1e-4 * e.lux / kPiD);
}

}  // namespace
}  // namespace kasumi
