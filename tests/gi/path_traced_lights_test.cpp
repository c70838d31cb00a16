// The path tracer (render.gi = "path") under a sphere light and a polygon light over a white
// Lambertian floor, the only surface (no interreflection): the floor's radiance is
// kd/π (E_sphere + E_polygon), with the closed forms π L (r/d)² cos θ (a sphere of radiance L
// seen at distance d, wholly above the horizon) and Lambert's polygon formula (lights/,
// checked against Howell's catalogue in lights_unit_test). Light sampling, BSDF sampling and
// their MIS weights must add up to it. 20000 paths per point; bound 4.5 s.e. (two-sided
// false-failure rate 6.8e-6 per point, 3 points), asserted under 0.6% of the answer so that a
// 2% error of either light's share shows.
#include "gi/gi.h"
#include "lights/light.h"
#include "render/probe.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace kasumi {
namespace {

TEST(PathTracedLights, SphereAndPolygonLightsOverAFloorMatchTheClosedForms) {
    const auto scene = runtime_from_text(R"({
  "materials": {"white": {"type": "phong", "kd": 1.0}},
  "shapes": [{"type": "quad", "material": "white",
              "vertices": [[-50, 0, 50], [50, 0, 50], [50, 0, -50], [-50, 0, -50]]}],
  "lights": [
    {"type": "sphere", "center": [1, 1.5, 0], "radius": 0.4, "luminance_cd_m2": 1000},
    {"type": "polygon", "luminance_cd_m2": 500,
     "vertices": [[-1.5, 2, -0.5], [-0.5, 2, -0.5], [-0.5, 2, 0.5], [-1.5, 2, 0.5]]}],
  "render": {"gi": "path"}})",
                                         make_gi_method);
    const Vec3 up(0, 1, 0);
    for (const Vec3 at : {Vec3(0.0f, 0.0f, 0.2f), Vec3(1.0f, 0.0f, -0.5f), Vec3(-1.2f, 0, 0.3f)}) {
        double e = 0.0;
        for (const Light& light : scene->desc().lights)
            e += luminance(unshadowed_irradiance(light, at, up));
        const double exact = e / kPiD;
        const RadianceProbe p = probe_radiance(*scene, at + Vec3(0, 0.3f, 0), -up, 20000);
        const double se = luminance(p.stderr_);
        std::printf("(%.1f, %.1f): path %.4f +- %.4f, closed form %.4f (%+.2f%%)\n", at.x, at.z,
                    p.luminance_cd_m2, se, exact, 100.0 * (p.luminance_cd_m2 / exact - 1.0));
        EXPECT_LT(4.5 * se, 0.006 * exact) << "too few paths";
        EXPECT_NEAR(p.luminance_cd_m2, exact, 4.5 * se) << at.x << ", " << at.z;
    }
}

}  // namespace
}  // namespace kasumi
