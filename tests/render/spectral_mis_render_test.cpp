// render.volume.spectral_mis in the renderer: the plan names it, and the image is the same for
// any thread count.
#include "render/renderer.h"
#include "scene/plan.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

/// fog_street.json (chromatic fog: sigma_s 0.05, 0.052, 0.055 /m) by multiple scattering with
/// ratio tracking, small.
SceneDesc small_street(bool mis) {
    return load_scene(KASUMI_SOURCE_DIR "/data/scenes/fog_street.json",
                      {{"/film/width", "32"},
                       {"/film/height", "18"},
                       {"/film/spp", "4"},
                       {"/render/volume/integrator", "\"multiple\""},
                       {"/render/volume/estimator", "\"ratio\""},
                       {"/render/volume/spectral_mis", mis ? "true" : "false"}});
}

std::string in_scattering_reason(const SceneDesc& desc) {
    for (const PlanStage& s : make_plan(desc).stages)
        if (s.name == "volume-in-scattering")
            return s.reason;
    return {};
}

TEST(SpectralMisRender, PlanNamesIt) {
    EXPECT_NE(in_scattering_reason(small_street(true)).find("spectral MIS"), std::string::npos)
        << in_scattering_reason(small_street(true));
    EXPECT_EQ(in_scattering_reason(small_street(false)).find("spectral MIS"), std::string::npos);
}

TEST(SpectralMisRender, BitIdenticalWithOneAndTwoThreads) {
    const SceneRuntime scene(small_street(true));
    const Image one = render_image(scene, quiet(1)).film.to_image();
    const Image two = render_image(scene, quiet(2)).film.to_image();
    ASSERT_EQ(one.channels.size(), two.channels.size());
    for (size_t c = 0; c < one.channels.size(); ++c)
        EXPECT_EQ(one.channels[c].data, two.channels[c].data) << one.channels[c].name;
    // The setting is in effect: the image differs from spectral tracking's at the same seed.
    const Image tracked = render_image(SceneRuntime(small_street(false)), quiet(1)).film.to_image();
    bool differs = false;
    for (size_t c = 0; c < one.channels.size(); ++c)
        differs = differs || one.channels[c].data != tracked.channels[c].data;
    EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace kasumi
