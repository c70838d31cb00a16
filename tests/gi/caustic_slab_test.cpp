// The caustic photon map against a closed form: a white Lambertian floor under a horizontal
// glass plate (n = 1.5, 10 cm thick, 3 m square), lit by a directional light straight down.
// Under the plate's middle the floor sees only light that crossed the plate: its irradiance is
// E_0 T with the slab's transmittance over all internal reflections, the geometric series
// T = (1 - F)² Σ F^{2k} = (1 - F) / (1 + F), F = ((n - 1)/(n + 1))² = 0.04 at normal
// incidence (Born & Wolf §1.5; incoherent multiple reflections), so the floor's radiance is
// kd/π E_0 T. No global map (global_count 0): the floor-plate-floor interreflection (light
// the floor sends back up and the plate returns, ~1% here) is not estimated, and the caustic map
// alone carries the light: photons from the light, through the plate's two faces (specular),
// to the floor. The plate's rim is 1 m from every probed point, so no kernel disc reaches its
// shadow edge and the caustic is uniform where it is estimated (no blur bias).
//
// Statistics: kRuns independent photon maps (render.seed), each probed at 32 × 32 points over
// the middle square metre (3 cm apart, about the kernel's radius: most stored photons there
// are used); the run means are i.i.d., their spread gives the standard error (Student's t,
// 11 degrees of freedom, two-sided 1e-4: t = 5.921; the seeds are fixed). Asserted: the bound
// t se is below 0.8% of the answer (small enough to catch a 2% error of the photons' power or of
// the caustic kernel's normalisation) and the mean within it plus 0.2% (the float closed form
// and the photon tracer's depth limit: F^16 < 1e-22).
#include "gi/gi.h"
#include "gi/photon/photon_gi.h"
#include "render/probe.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace kasumi {
namespace {

constexpr int kRuns = 12;
constexpr double kStudentT = 5.921;  // t_{0.99995, 11}
constexpr double kIlluminanceLux = 1000.0;

std::string scene(int seed) {
    return R"({
  "materials": {"white": {"type": "phong", "kd": 1.0},
                "glass": {"type": "dielectric", "ior": 1.5}},
  "shapes": [
    {"type": "quad", "material": "white",
     "vertices": [[-2, 0, 2], [2, 0, 2], [2, 0, -2], [-2, 0, -2]]},
    {"type": "box", "material": "glass", "min": [-1.5, 0.5, -1.5], "max": [1.5, 0.6, 1.5]}],
  "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
  "render": {"seed": )" +
           std::to_string(seed) + R"(, "gi": "photons",
    "photons": {"global_count": 0, "caustic_count": 2000000, "volume_count": 0,
                "k": 100, "max_radius_m": 0.2}}})";
}

TEST(CausticSlab, FloorUnderAGlassPlateMatchesTheSlabTransmittance) {
    const double f = 0.04;  // ((1.5 - 1) / (1.5 + 1))²
    const double exact = kIlluminanceLux * (1.0 - f) / (1.0 + f) / kPiD;
    double sum = 0.0, sum2 = 0.0;
    for (int run = 0; run < kRuns; ++run) {
        const auto runtime = runtime_from_text(scene(run + 1), make_gi_method);
        ASSERT_NE(dynamic_cast<const PhotonGi*>(runtime->gi()), nullptr);
        double run_sum = 0.0;
        for (int i = 0; i < 32; ++i) {
            for (int j = 0; j < 32; ++j) {
                const Vec3 at(-0.5f + (i + 0.5f) / 32.0f, 0.0f, -0.5f + (j + 0.5f) / 32.0f);
                run_sum += probe_radiance(*runtime, at + Vec3(0.0f, 0.25f, 0.0f),
                                          Vec3(0.0f, -1.0f, 0.0f), 4)
                               .luminance_cd_m2;
            }
        }
        const double run_mean = run_sum / 1024.0;
        sum += run_mean;
        sum2 += run_mean * run_mean;
    }
    const double mean = sum / kRuns;
    const double se = std::sqrt(std::max(0.0, (sum2 - kRuns * mean * mean) / (kRuns - 1)) / kRuns);
    std::printf("caustic under the plate: %.3f +- %.3f cd/m² (closed form %.3f, %+.2f%%)\n", mean,
                se, exact, 100.0 * (mean / exact - 1.0));
    EXPECT_LT(kStudentT * se, 0.008 * exact) << "too few photons";
    EXPECT_NEAR(mean, exact, kStudentT * se + 2e-3 * exact);
}

}  // namespace
}  // namespace kasumi
