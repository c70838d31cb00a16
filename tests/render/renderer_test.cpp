// The renderer as a whole: plans skip what a scene does not need (and counters prove it),
// images are deterministic across thread counts, and never hold a non-finite value.
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

TEST(Plan, SceneWithoutMediaRunsNoVolumeStage) {
    const auto scene = runtime_from_text(R"({
        "film": {"width": 16, "height": 8, "spp": 2},
        "materials": {"m": {"type": "phong"}},
        "shapes": [{"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "m"}],
        "lights": [{"type": "point", "position": [0, 5, 5], "intensity_cd": 10}]})");
    EXPECT_FALSE(scene->plan().volume);
    const RenderResult r = render_image(*scene, quiet(1));
    EXPECT_EQ(r.counters.volume_rays, 0u);
    EXPECT_EQ(r.counters.volume_steps, 0u);
    EXPECT_EQ(r.counters.camera_rays, 16u * 8u * 2u);
    EXPECT_GT(r.counters.surface_shadow_rays, 0u);
}

TEST(Plan, SceneWithoutShapesBuildsNoBvh) {
    const auto scene = runtime_from_text(R"({
        "film": {"width": 8, "height": 8, "spp": 1},
        "lights": [{"type": "point", "position": [0, 1, -3], "intensity_cd": 10}],
        "media": [{"type": "homogeneous", "bounds": [[-5, -5, -10], [5, 5, 0]], "sigma_a": 0.1, "sigma_s": 0.2}]})");
    EXPECT_EQ(scene->surfaces(), nullptr);
    EXPECT_EQ(scene->occlusion(), nullptr);
    const RenderResult r = render_image(*scene, quiet(1));
    EXPECT_EQ(r.counters.surface_hits, 0u);
    EXPECT_EQ(r.counters.volume_shadow_rays, 0u);
    EXPECT_GT(r.counters.volume_steps, 0u);
}

TEST(Plan, NonScatteringMediaRunTransmittanceOnly) {
    const SceneDesc desc = scene_from_text(R"({
        "lights": [{"type": "point", "position": [0, 1, -3], "intensity_cd": 10}],
        "media": [{"type": "homogeneous", "sigma_a": 0.1, "sigma_s": 0}]})");
    const Plan plan = make_plan(desc);
    EXPECT_TRUE(plan.volume);
    EXPECT_FALSE(plan.in_scattering);
    bool found = false;
    for (const PlanStage& s : plan.stages) {
        if (s.name == "volume-in-scattering") {
            found = true;
            EXPECT_FALSE(s.enabled);
            EXPECT_NE(s.reason.find("transmittance only"), std::string::npos) << s.reason;
        }
    }
    EXPECT_TRUE(found);
}

SceneDesc small_fog_street() {
    SceneDesc desc =
        load_scene(KASUMI_SOURCE_DIR "/data/scenes/fog_street.json",
                   {{"/film/width", "48"}, {"/film/height", "27"}, {"/film/spp", "2"}});
    return desc;
}

TEST(Renderer, BitIdenticalWithOneAndTwoThreads) {
    const SceneRuntime scene(small_fog_street());
    const Image one = render_image(scene, quiet(1)).film.to_image();
    const Image two = render_image(scene, quiet(2)).film.to_image();
    ASSERT_EQ(one.channels.size(), two.channels.size());
    for (size_t c = 0; c < one.channels.size(); ++c) {
        EXPECT_EQ(one.channels[c].data, two.channels[c].data) << one.channels[c].name;
    }
}

TEST(Renderer, FogStreetIsFiniteAndFogGlows) {
    const SceneRuntime scene(small_fog_street());
    const RenderResult r = render_image(scene, quiet(0));
    EXPECT_EQ(r.counters.nonfinite_samples, 0u);
    const Image image = r.film.to_image();
    double volume_sum = 0.0;
    for (const ImageChannel& c : image.channels) {
        for (float v : c.data)
            ASSERT_TRUE(std::isfinite(v)) << c.name;
    }
    for (float v : image.find("volume.G")->data)
        volume_sum += v;
    EXPECT_GT(volume_sum, 0.0);  // lamps light the fog
    for (float t : image.find("transmittance.G")->data) {
        EXPECT_GT(t, 0.0f);
        EXPECT_LE(t, 1.0f);
    }
}

}  // namespace
}  // namespace kasumi
