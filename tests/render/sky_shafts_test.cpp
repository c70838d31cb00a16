// Light shafts (render/sky_shafts.h) against closed forms and an independent 1D quadrature.
// Setting: a horizontal camera ray 1 m above the ground looks 400 m along +x at a black wall, so
// what it sees is the air alone. Near the ground over 400 m the air's density is constant to
// 2e-6 (the ray rises 400² / 2R = 1.3 cm above the curved ground), so the single scattering
// of the sunlit part of the ray is, per band,
//   L = integral T(0, s) (sigma_s,R p_R(mu) + sigma_s,M p_M(mu)) T_sun E ds,  T(0, s) = e^{-sigma_t
//   s}.
// The sun is 30 deg up at azimuth 300 deg: direction (-0.75, 0.5, -0.433), mu = -0.75 with the
// ray (shadow rays run back toward the camera side, away from the wall). Occluders: a black roof
// at y = 5 (a shadow ray from the node at s meets it at x = s - 6) and an absorbing slab of fog
// 2 m thick above the ray (4 m of it on the way to the sun).
#include "render/sky_shafts.h"
#include "core/error.h"
#include "render/integrator.h"
#include "render/probe.h"
#include "scene/plan.h"
#include "sky/sky_reference.h"
#include "tests/render/trace_pair.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

struct SceneOptions {
    const char* mode = "reference";
    bool shafts = true;
    std::string extra_shapes;  ///< appended to the shapes array (leading comma)
    std::string media = "[]";
    /// Appended to render.sky (leading comma); by default shafts over the whole 400 m ray.
    std::string shaft_keys = R"(, "shaft_distance_m": 1000)";
};

std::string scene_text(const SceneOptions& o) {
    return std::string(R"({
        "camera": {"position": [0, 1, 0], "look_at": [1, 1, 0]},
        "materials": {"black": {"type": "phong", "kd": 0}},
        "shapes": [
          {"type": "quad", "material": "black",
           "vertices": [[400, -10, -10], [400, 10, -10], [400, 10, 10], [400, -10, 10]]})") +
           o.extra_shapes + R"(],
        "media": )" +
           o.media +
           R"(,
        "atmosphere": {"mie": {"scattering": 2e-5, "extinction": 2.2e-5}},
        "sun": {"elevation_deg": 30, "azimuth_deg": 300},
        "render": {"sky": {"mode": ")" +
           o.mode + R"(", "orders": 1, "shafts": )" + (o.shafts ? "true" : "false") + o.shaft_keys +
           "}}}";
}

/// A black roof at y = 5 over x in [x0, 2000], z in [-1000, 1000].
std::string roof(double x0) {
    const std::string a = std::to_string(x0);
    return R"(, {"type": "quad", "material": "black",
           "vertices": [[)" +
           a + R"(, 5, -1000], [2000, 5, -1000], [2000, 5, 1000], [)" + a + R"(, 5, 1000]]})";
}

const Vec3 kOrigin(0.0f, 1.0f, 0.0f);
const Vec3 kAlong(1.0f, 0.0f, 0.0f);

Rgb probe(const SceneRuntime& scene, int spp) {
    return probe_radiance(scene, kOrigin, kAlong, spp).radiance;
}

/// Single-scattered sunlight over [a, b] of the test ray by Simpson's rule (400 intervals) with
/// the air's coefficients at 1 m and the reference sun transmittance (256 nodes): RGB cd/m².
Rgb single_scattering(const SkyScene& sky, double a, double b) {
    const Atmosphere& atm = sky.atmosphere;
    const AtmosphereCoefficients c = atmosphere_coefficients(atm, 1.0);
    const double mu = glm::dot(DVec3(kAlong), sky.sun_direction);
    Bands p_r{};
    rayleigh_phase_bands(atm, mu, p_r);
    const double p_m = eval_precise(atm.mie_phase, mu);
    constexpr int n = 400;
    const double h = (b - a) / n;
    Bands sum{};
    for (int k = 0; k <= n; ++k) {
        const double s = a + k * h;
        const double w = (k == 0 || k == n) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
        const Bands t_sun = sun_transmittance(sky, DVec3(s, 1.0, 0.0), 256);
        for (int i = 0; i < atm.bands; ++i) {
            sum[i] += w * h / 3.0 * std::exp(-c.sigma_t[i] * s) *
                      (c.sigma_s_rayleigh[i] * p_r[i] + c.sigma_s_mie[i] * p_m) * t_sun[i];
        }
    }
    return sky.to_rgb(sum);
}

TEST(SkyShafts, NoOccluderGivesExactlyTheUnshadowedAir) {
    // A box beside the ray on the side away from the sun cannot shadow it: the shadow rays are
    // cast (counted) and every pixel equals the render without shafts, bit for bit.
    SceneOptions o;
    o.mode = "fast";
    o.extra_shapes = R"(, {"type": "box", "material": "black", "min": [100, 0, 20],
                           "max": [120, 30, 40]})";
    const auto on = runtime_from_text(scene_text(o));
    o.shafts = false;
    const auto off = runtime_from_text(scene_text(o));
    for (int k = 0; k < 16; ++k) {
        const Vec3 d = glm::normalize(Vec3(1.0f, 0.02f * k - 0.1f, 0.05f * k - 0.4f));
        const TracedPair p = trace_pair(*on, *off, Ray{kOrigin, d, 0.0f, kInfinity}, 7, k);
        EXPECT_EQ(p.a.radiance, p.b.radiance) << k;
        EXPECT_EQ(p.a.volume, p.b.volume) << k;
        EXPECT_EQ(p.counters_a.surface_shadow_rays, p.counters_b.surface_shadow_rays + 16u) << k;
    }
}

TEST(SkyShafts, FullyShadowedRayKeepsNoSingleScattering) {
    // Reference mode, single scattering only: with the roof over the whole ray the air sends
    // nothing, L_on = 0 up to the difference of two quadratures of the same integral.
    SceneOptions o;
    o.extra_shapes = roof(-2000.0);
    const auto on = runtime_from_text(scene_text(o));
    o.shafts = false;
    const auto off = runtime_from_text(scene_text(o));
    const Rgb l_off = probe(*off, 1);
    const Rgb l_on = probe(*on, 16);
    const Rgb expected = single_scattering(on->sky()->sky(), 0.0, 400.0);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(l_off[i], expected[i], 2e-3f * expected[i]) << i;  // the reference agrees
        EXPECT_GT(l_off[i], 0.0f);
        EXPECT_LE(l_on[i], 1e-3f * l_off[i]) << i;
    }
}

TEST(SkyShafts, FullyShadowedRayKeepsTheMultipleScatteringOfFastMode) {
    // Fast mode: the air over the segment (< 1 km) is the closed form
    // L = (1 - e^{-sigma_t L}) / sigma_t (sum sigma_s p T_sun E + sigma_s Psi_ms E) at its middle;
    // shafts remove the first term and leave the multiply scattered light, unshadowed.
    SceneOptions o;
    o.mode = "fast";
    o.extra_shapes = roof(-2000.0);
    const auto on = runtime_from_text(scene_text(o));
    o.shafts = false;
    const auto off = runtime_from_text(scene_text(o));
    const Rgb l_off = probe(*off, 1);
    const Rgb l_on = probe(*on, 16);
    const SkyScene& sky = on->sky()->sky();
    const Atmosphere& atm = sky.atmosphere;
    const DVec3 middle(200.0, 1.0, 0.0);
    const double r = atm.radius(middle);
    const AtmosphereCoefficients c = atmosphere_coefficients(atm, r - atm.ground_radius_m);
    Bands ms{}, l_ms{};
    on->sky()->luts()->multiple_scattering(
        r, glm::dot(glm::normalize(middle - atm.center()), sky.sun_direction), ms);
    for (int i = 0; i < atm.bands; ++i) {
        const double path = -std::expm1(-c.sigma_t[i] * 400.0) / c.sigma_t[i];
        l_ms[i] = path * (c.sigma_s_rayleigh[i] + c.sigma_s_mie[i]) * ms[i];
    }
    const Rgb expected = sky.to_rgb(l_ms);
    for (int i = 0; i < 3; ++i) {
        EXPECT_GT(l_off[i] - expected[i], 0.3f * l_off[i]) << i;  // a third is single scattering
        EXPECT_NEAR(l_on[i], expected[i], 3e-3f * l_off[i]) << i;
    }
}

TEST(SkyShafts, HalfShadowedRayLosesTheShadowedStretch) {
    // The roof starts at x = 154: shadow rays from nodes past s = 160 meet it. The boundary lies
    // inside a stratum (25 m strata), so the estimate is noisy there: 512 samples, tolerance 5
    // standard errors plus 0.2% for the quadratures (false-failure rate < 1e-6, normal
    // approximation; the seeds are fixed).
    SceneOptions o;
    o.extra_shapes = roof(154.0);
    const auto on = runtime_from_text(scene_text(o));
    o.shafts = false;
    const auto off = runtime_from_text(scene_text(o));
    const Rgb l_off = probe(*off, 1);
    const RadianceProbe p_on = probe_radiance(*on, kOrigin, kAlong, 512);
    const Rgb lost = single_scattering(on->sky()->sky(), 160.0, 400.0);
    for (int i = 0; i < 3; ++i) {
        EXPECT_GT(lost[i], 0.4f * l_off[i]);
        EXPECT_NEAR(l_off[i] - p_on.radiance[i], lost[i], 5.0f * p_on.stderr_[i] + 2e-3f * l_off[i])
            << i;
    }
}

TEST(SkyShafts, FogSlabDimsTheShaftsByItsTransmittance) {
    // An absorbing slab (sigma_a = 0.2 /m, 2 m thick, 10-12 m up) between the ray and the sun:
    // every node sees the sun through 4 m of it, V = e^{-0.8}, so L_on = V L_off (Beer-Lambert
    // is exact for homogeneous media).
    SceneOptions o;
    o.media = R"([{"type": "homogeneous", "bounds": [[-2000, 10, -2000], [2000, 12, 2000]],
                   "sigma_a": 0.2, "sigma_s": 0}])";
    const auto on = runtime_from_text(scene_text(o));
    o.shafts = false;
    const auto off = runtime_from_text(scene_text(o));
    const Rgb l_off = probe(*off, 1);
    const Rgb l_on = probe(*on, 16);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(l_on[i], std::exp(-0.8f) * l_off[i], 1e-3f * l_off[i]) << i;
}

TEST(SkyShafts, ShaftDistanceBoundsTheShadowedStretch) {
    // Shafts only over the first 100 m: the roof over everything removes [0, 100] alone.
    SceneOptions o;
    o.extra_shapes = roof(-2000.0);
    o.shaft_keys = R"(, "shaft_distance_m": 100)";
    const auto on = runtime_from_text(scene_text(o));
    o.shafts = false;
    const auto off = runtime_from_text(scene_text(o));
    const Rgb l_off = probe(*off, 1);
    const Rgb l_on = probe(*on, 16);
    const Rgb kept = single_scattering(on->sky()->sky(), 100.0, 400.0);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(l_on[i], kept[i], 2e-3f * l_off[i]) << i;
}

const PlanStage* find_stage(const Plan& plan, const std::string& name) {
    for (const PlanStage& s : plan.stages) {
        if (s.name == name)
            return &s;
    }
    return nullptr;
}

TEST(SkyShafts, PlanSaysWhenShaftsRunAndWhy) {
    SceneOptions o;
    o.media = R"([{"type": "homogeneous", "bounds": [[-1, 10, -1], [1, 12, 1]],
                   "sigma_a": 0.2, "sigma_s": 0}])";
    const Plan on = make_plan(scene_from_text(scene_text(o)));
    const PlanStage* s = find_stage(on, "sky-shafts");
    ASSERT_NE(s, nullptr);
    EXPECT_TRUE(s->enabled);
    EXPECT_NE(s->reason.find("surfaces"), std::string::npos) << s->reason;
    EXPECT_NE(s->reason.find("media"), std::string::npos) << s->reason;
    EXPECT_NE(s->reason.find("1000 m"), std::string::npos) << s->reason;
    o.shafts = false;
    const Plan off = make_plan(scene_from_text(scene_text(o)));
    s = find_stage(off, "sky-shafts");
    ASSERT_NE(s, nullptr);
    EXPECT_FALSE(s->enabled);
    EXPECT_NE(s->reason.find("render.sky.shafts is false"), std::string::npos) << s->reason;
}

TEST(SkyShafts, BadKeysNameTheirPointer) {
    SceneOptions o;
    o.shaft_keys = R"(, "shaft_samples": 0)";
    try {
        (void)scene_from_text(scene_text(o));
        FAIL() << "accepted 0 samples";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/render/sky/shaft_samples"), std::string::npos)
            << e.what();
    }
    o.shaft_keys = R"(, "shaft_distance_m": -5)";
    EXPECT_THROW((void)scene_from_text(scene_text(o)), Error);
}

}  // namespace
}  // namespace kasumi
