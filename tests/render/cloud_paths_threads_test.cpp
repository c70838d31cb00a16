// render.volume.splitting "sun" and "guided", render.volume.camera_transmittance "first_flight" and
// render.volume.shadow_roulette (issue 19) in a render of data/scenes/cloud.json: the same image
// for 1 and 2 threads (the weight window's copies draw from their own pixel sample's stream; the
// light cache the roulette reads is built once, the same for any thread), and a different one
// from today's settings (so the equality is the techniques', not a fallback's).
#include "render/renderer.h"
#include "scene/plan.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"

#include <gtest/gtest.h>

#include <string>

namespace kasumi {
namespace {

Image render_cloud(const std::string& splitting, const std::string& camera, int threads,
                   const std::string& shadow_roulette = "0") {
    SceneDesc desc = load_scene(KASUMI_SOURCE_DIR "/data/scenes/cloud.json",
                                {{"/film/width", "48"},
                                 {"/film/height", "27"},
                                 {"/film/spp", "2"},
                                 {"/render/volume/splitting", "\"" + splitting + "\""},
                                 {"/render/volume/camera_transmittance", "\"" + camera + "\""},
                                 {"/render/volume/shadow_roulette", shadow_roulette}});
    const SceneRuntime runtime(std::move(desc));
    return render_image(runtime, quiet(threads)).film.to_image();
}

/// `one` and `two` (1 and 2 threads) have the same channels and pixels, and `other` (other
/// settings) differs from them somewhere.
void expect_same_and_differs_from(const Image& one, const Image& two, const Image& other) {
    ASSERT_EQ(one.channels.size(), two.channels.size());
    bool differs = false;
    for (size_t c = 0; c < one.channels.size(); ++c) {
        ASSERT_EQ(one.channels[c].name, two.channels[c].name);
        EXPECT_EQ(one.channels[c].data, two.channels[c].data) << one.channels[c].name;
        if (const ImageChannel* t = other.find(one.channels[c].name))
            differs = differs || t->data != one.channels[c].data;
    }
    EXPECT_TRUE(differs);
}

TEST(CloudPaths, RenderIsTheSameForOneAndTwoThreads) {
    expect_same_and_differs_from(render_cloud("sun", "first_flight", 1),
                                 render_cloud("sun", "first_flight", 2),
                                 render_cloud("off", "walk", 2));
}

TEST(CloudPaths, ShadowRouletteRenderIsTheSameForOneAndTwoThreads) {
    expect_same_and_differs_from(render_cloud("off", "first_flight", 1, "0.05"),
                                 render_cloud("off", "first_flight", 2, "0.05"),
                                 render_cloud("off", "first_flight", 2, "0"));
}

TEST(CloudPaths, GuidedWindowRenderIsTheSameForOneAndTwoThreads) {
    // render.volume.splitting "guided": the training passes' field and pixel estimates are the
    // same for any thread count, and so is the window's render.
    expect_same_and_differs_from(render_cloud("guided", "walk", 1),
                                 render_cloud("guided", "walk", 2), render_cloud("off", "walk", 2));
}

TEST(CloudPaths, PlanNamesTheGuidedWindow) {
    const SceneDesc desc = load_scene(KASUMI_SOURCE_DIR "/data/scenes/cloud.json",
                                      {{"/render/volume/splitting", "\"guided\""}});
    std::string reason;
    for (const PlanStage& stage : make_plan(desc).stages)
        if (stage.name == "multiple-scattering")
            reason = stage.reason;
    EXPECT_NE(reason.find("radiance learnt in 4 training passes"), std::string::npos) << reason;
}

TEST(CloudPaths, PlanNamesTheShadowRoulette) {
    const auto in_scattering = [](const std::string& share) {
        const SceneDesc desc = load_scene(KASUMI_SOURCE_DIR "/data/scenes/cloud.json",
                                          {{"/render/volume/shadow_roulette", share}});
        for (const PlanStage& stage : make_plan(desc).stages)
            if (stage.name == "volume-in-scattering")
                return stage.reason;
        return std::string();
    };
    EXPECT_NE(in_scattering("0.05").find("Russian roulette on their expected contribution"),
              std::string::npos);
    EXPECT_EQ(in_scattering("0").find("roulette"), std::string::npos);
}

}  // namespace
}  // namespace kasumi
