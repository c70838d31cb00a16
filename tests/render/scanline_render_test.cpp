// "shadows": "scanline" as a render mode: the image equals the one with "ray" on every pixel
// whose footprint no shadow edge or face boundary cuts (ray tracing gives its centre and four
// corners one state, tests/surface/shadow_test_scene.h), the pass answers nearly every camera
// hit (so the equality is not the fallback's), and 1 and 2 threads give the same image. On a
// scene built in code (point and parallel light) and on data/scenes/shadow_polygons_concave.json.
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"
#include "tests/surface/shadow_test_scene.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

Image render_with(SceneDesc desc, ShadowMode mode, int threads) {
    desc.lights[0].shadows = mode;
    const SceneRuntime runtime(std::move(desc));
    return render_image(runtime, quiet(threads)).film.to_image();
}

struct Comparison {
    int compared = 0;  ///< pixels whose footprint no shadow edge cuts
    int shadowed = 0;  ///< of those, in shadow by ray tracing
    int differ = 0;    ///< of those, pixels whose value differs in any channel
    int hits = 0;      ///< camera hits at pixel centres on a light-facing side
    int by_pass = 0;   ///< of those, answered by the scanline pass
};

/// `mode`'s render against "ray" (and, for "scanline", how many camera hits the pass answered).
Comparison compare_with_rays(const SceneDesc& desc, ShadowMode mode = ShadowMode::Scanline) {
    const Image ray = render_with(desc, ShadowMode::Ray, 2);
    const Image scanline = render_with(desc, mode, 2);
    EXPECT_EQ(scanline.channels.size(), ray.channels.size());

    SceneDesc scanline_desc = desc;
    scanline_desc.lights[0].shadows = ShadowMode::Scanline;
    const SceneRuntime runtime(scanline_desc);
    const ScanlineShadows* pass = runtime.scanline_shadows()->shadows(0);
    const SurfaceScene& scene = *runtime.surfaces();
    const LightCentre light = light_centre(desc.lights[0]);
    const int w = desc.film.width, h = desc.film.height;
    PinholeView view = pinhole_view(desc.camera.position, desc.camera.look_at, w, h);
    view.half_width = float(w) / float(h) * std::tan(0.5f * radians(desc.camera.fov_deg));

    Comparison c;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int centre = ray_shadow_state(scene, light, view, x + 0.5f, y + 0.5f);
            if (centre >= 0 && mode == ShadowMode::Scanline) {
                const auto hit = scene.intersect(runtime.camera().generate_ray(x + 0.5f, y + 0.5f));
                bool answered = false;
                pass->in_shadow(*hit, offset_ray_origin(*hit, toward_light(light, hit->position)),
                                &answered);
                ++c.hits;
                c.by_pass += answered ? 1 : 0;
            }
            if (ray_shadow_state(scene, light, view, x, y) != centre ||
                ray_shadow_state(scene, light, view, x + 1, y) != centre ||
                ray_shadow_state(scene, light, view, x, y + 1) != centre ||
                ray_shadow_state(scene, light, view, x + 1, y + 1) != centre)
                continue;
            ++c.compared;
            c.shadowed += centre >= 0 ? centre & 1 : 0;
            const size_t p = size_t(y) * w + x;
            for (size_t k = 0; k < ray.channels.size(); ++k)
                if (ray.channels[k].data[p] != scanline.channels[k].data[p]) {
                    ++c.differ;
                    break;
                }
        }
    }
    return c;
}

SceneDesc code_scene() {
    SceneDesc desc = scene_from_text(R"({
        "camera": {"position": [0.7, 3.1, 6.3], "look_at": [0, 0.5, 0], "fov_deg": 40},
        "film": {"width": 320, "height": 200, "spp": 1, "jitter": false},
        "ambient": 0.1,
        "materials": {"m": {"type": "phong", "ka": 0.2, "kd": 0.7, "ks": 0.2, "n": 20}},
        "shapes": [{"type": "sphere", "center": [0, -9, 0], "radius": 1, "material": "m"}],
        "lights": [{"type": "point", "position": [0.4, 4.2, 0.9], "intensity_cd": 20}]})");
    desc.shapes = mesh_scene();  // boxes, quads, closed and open meshes (material 0)
    return desc;
}

TEST(ScanlineRenderTest, EqualsRayTracedImageOffShadowEdgesInACodeScene) {
    SceneDesc desc = code_scene();
    for (const bool parallel : {false, true}) {
        if (parallel)
            desc.lights[0].emitter =
                DirectionalLight{glm::normalize(Vec3(0.5f, -1.0f, -0.6f)), Rgb(3.0f)};
        const Comparison c = compare_with_rays(desc);
        EXPECT_GT(c.compared, 55000) << parallel;
        EXPECT_GT(c.shadowed, 800) << parallel;
        EXPECT_GT(c.by_pass, c.hits * 98 / 100) << parallel;
        EXPECT_EQ(c.differ, 0) << parallel << ": " << c.compared << " compared, " << c.shadowed
                               << " shadowed, " << c.by_pass << " of " << c.hits << " by the pass";
    }
}

TEST(ScanlineRenderTest, EqualsRayTracedImageOffShadowEdgesOnTheConcaveScene) {
    const SceneDesc desc =
        load_scene(KASUMI_SOURCE_DIR "/data/scenes/shadow_polygons_concave.json",
                   {{"/film/width", "320"}, {"/film/height", "200"}, {"/film/jitter", "false"}});
    const Comparison c = compare_with_rays(desc);
    EXPECT_GT(c.compared, 55000);
    EXPECT_GT(c.shadowed, 800);
    EXPECT_GT(c.by_pass, c.hits * 98 / 100);
    EXPECT_EQ(c.differ, 0) << c.compared << " compared, " << c.shadowed << " shadowed, "
                           << c.by_pass << " of " << c.hits << " by the pass";
}

// The object-space method on the same JSON scene, loaded through the scene loader.
TEST(ObjectSpaceRenderTest, EqualsRayTracedImageOffShadowEdgesOnTheConcaveScene) {
    const SceneDesc desc =
        load_scene(KASUMI_SOURCE_DIR "/data/scenes/shadow_polygons_concave.json",
                   {{"/film/width", "320"}, {"/film/height", "200"}, {"/film/jitter", "false"}});
    const Comparison c = compare_with_rays(desc, ShadowMode::ObjectSpace);
    EXPECT_GT(c.compared, 55000);
    EXPECT_GT(c.shadowed, 800);
    EXPECT_EQ(c.differ, 0);
}

TEST(ScanlineRenderTest, OneAndTwoThreadsGiveTheSameImage) {
    const SceneDesc desc = code_scene();
    const Image one = render_with(desc, ShadowMode::Scanline, 1);
    const Image two = render_with(desc, ShadowMode::Scanline, 2);
    ASSERT_EQ(one.channels.size(), two.channels.size());
    for (size_t k = 0; k < one.channels.size(); ++k)
        EXPECT_EQ(one.channels[k].data, two.channels[k].data) << one.channels[k].name;
}

TEST(ScanlineRenderTest, PlanNamesTheStageAndItsFallback) {
    SceneDesc desc = code_scene();
    desc.lights[0].shadows = ShadowMode::Scanline;
    const Plan plan = make_plan(desc);
    EXPECT_TRUE(plan.scanline_shadows);
    bool found = false;
    for (const PlanStage& s : plan.stages)
        if (s.name == "scanline-shadows") {
            found = true;
            EXPECT_TRUE(s.enabled);
            EXPECT_NE(s.reason.find("secondary rays"), std::string::npos) << s.reason;
            EXPECT_EQ(s.reason.find("jittered"), std::string::npos) << s.reason;
        }
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace kasumi
