// Volume paths that leave the media see the sky, without the sun's disc (next-event estimation
// takes the sun): render/integrator.cpp, RenderPathEnvironment::radiance (commit c33e8dd).
//
// A thin rod of albedo-1, isotropic medium (sigma = 0.02/m, 5 m long, 0.2 m across) lies along
// the view under the default atmosphere with the sun 30 deg up. Light scattered in the rod
// leaves it within ~0.1 m (attenuation and multiple scattering there ~2e-3), so the rod adds to
// what the camera sees along w
//   dL = (1 - exp(-sigma d)) [E_sun / (4 pi) + (1 / (4 pi)) integral over the sphere of
//        L_sky(w') dw' - L_sky(w)]
// (single scattering of the sun's directional light and of the escaped sky, minus the sky the
// rod hides). With the disc counted twice (escaped paths seeing it as well as NEE) the sun term
// doubles; with the old constant background (black here) the sky term vanishes. The sky term is
// several times the test's bound (5 standard errors + 0.5% of dL): both mistakes fail it.
#include "render/probe.h"
#include "render/sky_environment.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

std::string scene_text(bool medium) {
    return std::string(R"({
        "camera": {"position": [-1, 2, 0], "look_at": [1, 2, 0]},
        "atmosphere": {},
        "sun": {"elevation_deg": 30, "azimuth_deg": 180},
        "media": [)") +
           (medium ? R"({"type": "homogeneous", "bounds": [[0, 1.9, -0.1], [5, 2.1, 0.1]],
                         "sigma_a": 0, "sigma_s": 0.02, "phase": {"model": "isotropic"}})"
                   : "") +
           R"(],
        "render": {"seed": 11, "volume": {"integrator": "multiple", "max_depth": 8}}})";
}

TEST(EscapedSky, ThinMediumAddsTheSkyOnceAndTheSunOnce) {
    const auto with = runtime_from_text(scene_text(true));
    const auto without = runtime_from_text(scene_text(false));
    const Vec3 origin(-1.0f, 2.0f, 0.0f), w(1.0f, 0.0f, 0.0f);
    const double scattered = -std::expm1(-0.02 * 5.0);  // 1 - exp(-sigma d)

    Rgb e_sun(0.0f);
    for (const Light& light : with->desc().lights) {
        if (const auto* sun = std::get_if<DirectionalLight>(&light.emitter))
            e_sun += sun->illuminance;
    }
    ASSERT_GT(luminance(e_sun), 0.0f);
    // The sky over the whole sphere (midpoint rule in cos theta and phi, 256 x 512 cells; the
    // escaped radiance without the disc, as the paths see it).
    Pcg32 rng(5, 6);
    glm::dvec3 e_sky(0.0);
    constexpr int kRows = 256, kCols = 512;
    for (int j = 0; j < kRows; ++j) {
        const double c = -1.0 + 2.0 * (j + 0.5) / kRows;
        const double s = std::sqrt(1.0 - c * c);
        for (int i = 0; i < kCols; ++i) {
            const double phi = 2.0 * kPiD * (i + 0.5) / kCols;
            const Vec3 wi(static_cast<float>(s * std::cos(phi)), static_cast<float>(c),
                          static_cast<float>(s * std::sin(phi)));
            const Rgb l = escaped_radiance(*with, Ray{origin, wi, 0.0f, kInfinity}, false, rng);
            e_sky += glm::dvec3(l) * (4.0 * kPiD / (kRows * kCols));
        }
    }
    const Rgb l_sky = probe_radiance(*without, origin, w, 1).radiance;
    const RadianceProbe p = probe_radiance(*with, origin, w, 200000);
    for (int i = 0; i < 3; ++i) {
        const double sun_term = scattered * e_sun[i] / (4.0 * kPiD);
        const double sky_term = scattered * e_sky[i] / (4.0 * kPiD);
        const double hidden = scattered * l_sky[i];
        const double expected = sun_term + sky_term - hidden;
        const double measured = p.radiance[i] - l_sky[i];
        std::printf(
            "channel %d: dL %.5g (s.e. %.2g), expected %.5g = sun %.5g + sky %.5g - "
            "hidden %.5g\n",
            i, measured, p.stderr_[i], expected, sun_term, sky_term, hidden);
        // 5 standard errors (false-failure rate < 1e-6 per channel, normal approximation) plus
        // 0.5% for the rod's own attenuation and multiple scattering (~2e-3) and the quadrature.
        const double bound = 5.0 * p.stderr_[i] + 0.005 * expected;
        EXPECT_NEAR(measured, expected, bound) << i;
        // Teeth: leaving the sky out, or counting the sun twice, falls outside the bound.
        EXPECT_GT(sky_term, 2.0 * bound) << i;
    }
}

}  // namespace
}  // namespace kasumi
