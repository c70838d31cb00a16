// The atmosphere and the scene's media as one medium along camera rays (render/air_and_media.h):
//  - a black opaque cloud and a black surface at the same distance in the air look the same (the
//    air in front of either, nothing from behind);
//  - a transparent cloud (density 0) changes nothing, bit for bit;
//  - a cloud at 2 km under a 2 deg sun is lit by the sun through the air above it: its colour is
//    that of the top-of-atmosphere sun times the air's transmittance from the cloud toward the
//    sun (the reference quadrature, independent of the fast mode's table that the render reads);
//  - the images do not depend on the thread count.
#include "core/error.h"
#include "render/integrator.h"
#include "render/probe.h"
#include "render/renderer.h"
#include "sky/sky_reference.h"
#include "tests/render/quiet_render_options.h"
#include "tests/render/trace_pair.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <string>

namespace kasumi {
namespace {

/// A camera 1 m above the ground looking along +x under a sun 20 deg up.
struct View {
    std::string materials = R"({"black": {"type": "phong", "kd": 0}})";
    std::string shapes = "[]";
    std::string media = "[]";
    bool shafts = false;
};

std::string scene_text(const View& v) {
    return R"({
        "camera": {"position": [0, 1, 0], "look_at": [1, 1, 0], "fov_deg": 40},
        "film": {"width": 64, "height": 36},
        "materials": )" +
           v.materials + R"(,
        "shapes": )" +
           v.shapes + R"(,
        "media": )" +
           v.media + R"(,
        "atmosphere": {},
        "sun": {"elevation_deg": 20, "azimuth_deg": 240},
        "render": {"sky": {"mode": "fast", "shafts": )" +
           (v.shafts ? "true" : "false") + "}}}";
}

/// A black quad facing the camera at x = d.
View black_wall(double d) {
    const std::string x = std::to_string(d);
    View v;
    v.shapes = R"([{"type": "quad", "material": "black", "vertices": [[)" + x +
               R"(, -2000, -2000], [)" + x + R"(, 2000, -2000], [)" + x + R"(, 2000, 2000], [)" +
               x + R"(, -2000, 2000]]}])";
    return v;
}

/// An absorbing box 200 m deep from x = d (optical depth 2000: opaque to float precision).
View black_cloud(double d) {
    View v;
    v.media = R"([{"type": "homogeneous", "bounds": [[)" + std::to_string(d) +
              R"(, -2000, -2000], [)" + std::to_string(d + 200.0) +
              R"(, 2000, 2000]], "sigma_a": 10, "sigma_s": 0}])";
    return v;
}

TEST(AirAndMedia, BlackOpaqueCloudLooksLikeABlackSurfaceAtTheSameDistance) {
    // Within the aerial-perspective table (2 and 20 km) and past it (40 km, marched). Before the
    // air and the media were one medium, the cloud was black (the air was composed in front of
    // the first surface only, and there was none).
    const Vec3 origin(0.0f, 1.0f, 0.0f);
    for (const double d : {2000.0, 20000.0, 40000.0}) {
        const auto wall = runtime_from_text(scene_text(black_wall(d)));
        const auto cloud = runtime_from_text(scene_text(black_cloud(d)));
        for (const Vec3 dir : {Vec3(1.0f, 0.0f, 0.0f), glm::normalize(Vec3(1.0f, 0.1f, -0.2f))}) {
            const Rgb l_wall = probe_radiance(*wall, origin, dir, 1).radiance;
            const Rgb l_cloud = probe_radiance(*cloud, origin, dir, 1).radiance;
            for (int c = 0; c < 3; ++c) {
                EXPECT_GT(l_wall[c], 1.0f) << d;  // the air in front is seen (cd/m²)
                EXPECT_NEAR(l_cloud[c], l_wall[c], 0.01f * l_wall[c]) << d << " channel " << c;
            }
        }
    }
}

/// A ground and a procedural cumulus 50-800 m up, 2-3 km ahead, with its density scaled by
/// `density_scale` (empty: no cloud), shafts on.
std::string cumulus_scene(const std::string& density_scale) {
    View v;
    v.materials = R"({"ground": {"type": "phong", "kd": 0.3}})";
    v.shapes = R"([{"type": "quad", "material": "ground",
                    "vertices": [[-5000, 0, 5000], [5000, 0, 5000], [5000, 0, -5000],
                                 [-5000, 0, -5000]]}])";
    if (!density_scale.empty()) {
        v.media = R"([{"type": "vdb", "file": "../clouds/cumulus_64.vdb", "density_scale": )" +
                  density_scale + R"(, "albedo": 0.99,
                       "transform": {"translate": [2500, -200, 0]}}])";
    }
    v.shafts = true;
    return scene_text(v);
}

TEST(AirAndMedia, TransparentCloudChangesNothingBitForBit) {
    const auto with = runtime_from_text(cumulus_scene("0"));
    const auto without = runtime_from_text(cumulus_scene(""));
    ASSERT_TRUE(with->plan().volume);
    ASSERT_FALSE(without->plan().volume);
    const Vec3 origin(0.0f, 1.0f, 0.0f);
    for (int k = 0; k < 24; ++k) {
        // Rays to the ground, through the cloud's box and to the sky.
        const Vec3 d = glm::normalize(Vec3(1.0f, 0.04f * k - 0.3f, 0.03f * k - 0.36f));
        const TracedPair p = trace_pair(*with, *without, Ray{origin, d, 0.0f, kInfinity}, 11, k);
        EXPECT_EQ(p.a.radiance, p.b.radiance) << k;
        EXPECT_EQ(p.a.volume, p.b.volume) << k;
        EXPECT_EQ(p.a.transmittance, p.b.transmittance) << k;
        EXPECT_EQ(p.a.surface, p.b.surface) << k;
    }
}

TEST(AirAndMedia, CloudAt2kmTakesTheSunsColourThroughTheAirAboveIt) {
    // A thin grey scattering slab (20 m, sigma_s 0.05 /m, isotropic, single scattering) 2 km up,
    // 10 m in front of the camera, a black wall behind it; the sun 2 deg up behind the camera.
    // The slab's light is grey-weighted sunlight, so its colour (R/G, B/G) is the sun's at the
    // slab: the top-of-atmosphere sun times T_air(slab -> sun). The 31 m of air in front and
    // within add ~1e-3 of the slab's light.
    const std::string text = R"({
        "camera": {"position": [0, 2000, 0], "look_at": [1, 2000, 0], "fov_deg": 40},
        "film": {"width": 64, "height": 36},
        "materials": {"black": {"type": "phong", "kd": 0}},
        "shapes": [{"type": "quad", "material": "black",
                    "vertices": [[31, 1900, -100], [31, 2100, -100], [31, 2100, 100],
                                 [31, 1900, 100]]}],
        "media": [{"type": "homogeneous", "bounds": [[10, 1990, -10], [30, 2010, 10]],
                   "sigma_a": 0, "sigma_s": 0.05, "phase": {"model": "isotropic"}}],
        "atmosphere": {},
        "sun": {"elevation_deg": 2, "azimuth_deg": 270},
        "render": {"sky": {"mode": "fast"}, "volume": {"integrator": "single"}}})";
    const auto scene = runtime_from_text(text);
    const SkyScene& sky = scene->sky()->sky();
    const Rgb l =
        probe_radiance(*scene, Vec3(0.0f, 2000.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 64).radiance;
    const Rgb sun_at_cloud = sky.to_rgb(sun_transmittance(sky, DVec3(20.0, 2000.0, 0.0), 512));
    const Rgb sun_at_origin = sky.to_rgb(sun_transmittance(sky, DVec3(0.0, 1.0, 0.0), 512));
    const auto blue_over_green = [](const Rgb& c) { return c.b / c.g; };
    const auto red_over_green = [](const Rgb& c) { return c.r / c.g; };
    // The test can tell the two apart: the sun at the ground is far redder.
    ASSERT_GT(blue_over_green(sun_at_cloud), 1.2f * blue_over_green(sun_at_origin));
    EXPECT_NEAR(blue_over_green(l), blue_over_green(sun_at_cloud),
                0.01f * blue_over_green(sun_at_cloud));
    EXPECT_NEAR(red_over_green(l), red_over_green(sun_at_cloud),
                0.01f * red_over_green(sun_at_cloud));
}

TEST(AirAndMedia, BitIdenticalWithOneAndTwoThreads) {
    SceneDesc desc = scene_from_text(cumulus_scene("0.01"));
    desc.film.width = 48;
    desc.film.height = 27;
    desc.film.spp = 2;
    const SceneRuntime scene(std::move(desc));
    const RenderResult one = render_image(scene, quiet(1));
    const RenderResult two = render_image(scene, quiet(2));
    // The cloud is on screen: the volume stage ran.
    EXPECT_GT(one.counters.volume_rays, 0u);
    const Image a = one.film.to_image(), b = two.film.to_image();
    ASSERT_EQ(a.channels.size(), b.channels.size());
    for (size_t c = 0; c < a.channels.size(); ++c)
        EXPECT_EQ(a.channels[c].data, b.channels[c].data) << a.channels[c].name;
}

}  // namespace
}  // namespace kasumi
