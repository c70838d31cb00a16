// The sky seen by secondary rays (render/sky_environment.h): mirrors in Whitted and in the path
// tracer show the sky and the sun's disc the camera sees, and the path tracer takes the sky as
// its environment light (a furnace-like check on a white Lambertian plane).
#include "render/sky_environment.h"
#include "gi/gi.h"
#include "render/integrator.h"
#include "render/probe.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

const Vec3 kCamera(0.0f, 2.0f, 0.0f);

/// A mirror quad in the plane through the origin with unit normal n (2 m wide), a camera at
/// kCamera.
std::string mirror_scene(const Vec3& n, const char* gi) {
    const Vec3 a =
        glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 0, 1)));
    const Vec3 b = glm::cross(n, a);
    // Off-centre, so that the probe ray does not meet the quad's diagonal (a triangle edge).
    const Vec3 c = 0.3f * a + 0.1f * b;
    const auto v = [](const Vec3& p) {
        return "[" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
               "]";
    };
    return std::string(R"({
        "camera": {"position": [0, 2, 0], "look_at": [1, 2, 0]},
        "materials": {"mirror": {"type": "mirror", "kr": [0.5, 0.7, 0.9]}},
        "shapes": [{"type": "quad", "material": "mirror", "vertices": [)") +
           v(c - a - b) + ", " + v(c + a - b) + ", " + v(c + a + b) + ", " + v(c - a + b) +
           R"(]}],
        "atmosphere": {},
        "sun": {"elevation_deg": 30, "azimuth_deg": 180},
        "render": {"gi": ")" +
           gi + R"("}})";
}

void expect_mirror_shows(const char* gi, const Vec3& normal, const Vec3& reflected) {
    const auto scene = runtime_from_text(mirror_scene(normal, gi), make_gi_method);
    // What the camera sees straight along the reflected direction (the sky-view table and the
    // disc), and through the mirror: kr times that, behind 2 m of air (relative effect < 1e-4).
    const Rgb direct = probe_radiance(*scene, kCamera, reflected, 1).radiance;
    const Rgb seen = probe_radiance(*scene, kCamera, Vec3(0, -1, 0), 1).radiance;
    const Rgb kr(0.5f, 0.7f, 0.9f);
    for (int i = 0; i < 3; ++i) {
        EXPECT_GT(direct[i], 0.0f);
        EXPECT_NEAR(seen[i], kr[i] * direct[i], 1e-3f * kr[i] * direct[i]) << gi << " " << i;
    }
}

TEST(SkyEnvironment, MirrorReflectingTheZenithShowsTheZenithSky) {
    // A horizontal mirror under a camera looking straight down reflects the zenith.
    expect_mirror_shows("none", Vec3(0, 1, 0), Vec3(0, 1, 0));
    expect_mirror_shows("path", Vec3(0, 1, 0), Vec3(0, 1, 0));
}

TEST(SkyEnvironment, MirrorShowsTheSunDisc) {
    // The mirror's normal halves the angle between up and the sun (30 deg up in the south,
    // +z): the camera looking down sees the sun's disc in it, ~1e5 times the sky beside it.
    const Vec3 sun(0.0f, 0.5f, std::sqrt(3.0f) / 2.0f);
    const Vec3 n = glm::normalize(Vec3(0, 1, 0) + sun);
    expect_mirror_shows("none", n, sun);
    expect_mirror_shows("path", n, sun);
    const auto scene = runtime_from_text(mirror_scene(n, "none"), make_gi_method);
    Pcg32 rng(1, 2);
    const Rgb disc = probe_radiance(*scene, kCamera, sun, 1).radiance;
    const Rgb beside =
        probe_radiance(*scene, kCamera, glm::normalize(sun + Vec3(0.03f, 0, 0)), 1).radiance;
    EXPECT_GT(luminance(disc), 1e4f * luminance(beside));
    // Without the disc (the path tracer after a diffuse bounce) the sun's direction shows only
    // the aureole, as bright as the sky right beside the disc.
    const Rgb no_disc = escaped_radiance(*scene, Ray{Vec3(0.0f), sun, 0.0f, kInfinity}, false, rng);
    EXPECT_LT(luminance(no_disc), 2.0f * luminance(beside));
    EXPECT_GT(luminance(no_disc), 0.5f * luminance(beside));
}

TEST(SkyEnvironment, WhiteLambertianPlaneUnderTheSkyReflectsItsIrradiance) {
    // Furnace-like check of the path tracer's environment light: a white Lambertian plane
    // (kd = 1) 100 km wide under the sky and the sun 30 deg up. It sees only the upper
    // hemisphere, so L = (E_sky(up) + E_sun sin 30) / pi, with E_sun the sun's directional
    // light (next-event estimation) and E_sky = integral of L_sky cos over the hemisphere by
    // cosine-sampled bounces.
    const auto scene = runtime_from_text(R"({
        "camera": {"position": [0.3, 1.5, 0.1], "look_at": [1, 1.5, 0]},
        "materials": {"white": {"type": "phong", "kd": 1, "ks": 0}},
        "shapes": [{"type": "quad", "material": "white",
           "vertices": [[-50000, 0, -50000], [-50000, 0, 50000], [50000, 0, 50000],
                        [50000, 0, -50000]]}],
        "atmosphere": {},
        "sun": {"elevation_deg": 30, "azimuth_deg": 180},
        "render": {"gi": "path", "seed": 3}})",
                                         make_gi_method);
    Rgb e_sun(0.0f);
    for (const Light& light : scene->desc().lights) {
        if (const auto* d = std::get_if<DirectionalLight>(&light.emitter))
            e_sun += d->illuminance * 0.5f;
    }
    ASSERT_GT(luminance(e_sun), 0.0f);
    // Independent quadrature of the environment over the upper hemisphere (midpoint rule in
    // cos theta and phi, 256 x 512 cells; the sky is smooth there, the disc left out):
    // E = sum L cos dw.
    Pcg32 rng(5, 6);
    glm::dvec3 e_quadrature(0.0);
    constexpr int kRows = 256, kCols = 512;
    for (int j = 0; j < kRows; ++j) {
        const double c = (j + 0.5) / kRows;
        const double s = std::sqrt(1.0 - c * c);
        for (int i = 0; i < kCols; ++i) {
            const double phi = 2.0 * kPiD * (i + 0.5) / kCols;
            const Vec3 w(static_cast<float>(s * std::cos(phi)), static_cast<float>(c),
                         static_cast<float>(s * std::sin(phi)));
            const Rgb l =
                escaped_radiance(*scene, Ray{Vec3(0, 0.01f, 0), w, 0.0f, kInfinity}, false, rng);
            e_quadrature += glm::dvec3(l) * c * (2.0 * kPiD / (kRows * kCols));
        }
    }
    const Rgb e_table = scene->sky()->irradiance(Vec3(0, 1, 0));
    const RadianceProbe p = probe_radiance(*scene, Vec3(0.3f, 1.5f, 0.1f), Vec3(0, -1, 0), 8192);
    std::printf(
        "path %.2f %.2f %.2f (stderr %.2f %.2f %.2f); quadrature sky E/pi %.2f %.2f %.2f; "
        "table sky E/pi %.2f %.2f %.2f; sun E/pi %.2f %.2f %.2f\n",
        p.radiance.r, p.radiance.g, p.radiance.b, p.stderr_.r, p.stderr_.g, p.stderr_.b,
        e_quadrature.x / kPiD, e_quadrature.y / kPiD, e_quadrature.z / kPiD, e_table.r * kInvPi,
        e_table.g * kInvPi, e_table.b * kInvPi, e_sun.r * kInvPi, e_sun.g * kInvPi,
        e_sun.b * kInvPi);
    for (int i = 0; i < 3; ++i) {
        const float from_quadrature = (static_cast<float>(e_quadrature[i]) + e_sun[i]) * kInvPi;
        const float from_table = (e_table[i] + e_sun[i]) * kInvPi;
        // The path tracer against the quadrature of the very radiance it samples: statistical
        // error only, 5 standard errors (false-failure rate < 1e-6, normal approximation) plus
        // 2e-4 for the quadrature and the 1.5 m of air in front of the plane.
        EXPECT_NEAR(p.radiance[i], from_quadrature, 5.0f * p.stderr_[i] + 2e-4f * from_quadrature)
            << i;
        EXPECT_LT(p.stderr_[i], 0.01f * p.radiance[i]) << i;
        // ... and against the sky irradiance table the Whitted renderer uses (24 x 48 directions
        // marched from 1 m above the origin instead of the camera's sky-view table): within the
        // table's own quadrature error, 2% of the sky term.
        EXPECT_NEAR(e_quadrature[i], e_table[i], 0.02 * e_table[i]) << i;
        EXPECT_NEAR(p.radiance[i], from_table, 5.0f * p.stderr_[i] + 0.02f * e_table[i] * kInvPi)
            << i;
    }
}

}  // namespace
}  // namespace kasumi
