// Volume path guiding in the renderer (render/guiding_training.h): the trained field and so the
// image are the same for any thread count, and the guided image agrees with the unguided one.
#include "core/error.h"
#include "render/guiding_training.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

/// cloud.json (multiple scattering through a VDB cloud) at 48x27, guided or not.
SceneDesc small_cloud(int spp, int seed, bool guided) {
    return load_scene(KASUMI_SOURCE_DIR "/data/scenes/cloud.json",
                      {{"/film/width", "48"},
                       {"/film/height", "27"},
                       {"/film/spp", std::to_string(spp)},
                       {"/render/seed", std::to_string(seed)},
                       {"/render/volume/guiding", guided ? "true" : "false"}});
}

TEST(VolumeGuiding, BitIdenticalWithOneAndTwoThreads) {
    const SceneRuntime scene(small_cloud(8, 7, true));
    ASSERT_TRUE(guiding_applies(scene));
    const Image one = render_image(scene, quiet(1)).film.to_image();
    const Image two = render_image(scene, quiet(2)).film.to_image();
    ASSERT_EQ(one.channels.size(), two.channels.size());
    for (size_t c = 0; c < one.channels.size(); ++c)
        EXPECT_EQ(one.channels[c].data, two.channels[c].data) << one.channels[c].name;
}

TEST(VolumeGuiding, TrainingBuildsAFieldInsideTheCloud) {
    const SceneRuntime scene(small_cloud(1, 7, true));
    RenderCounters counters;
    const GuidingField field = train_guiding_field(scene, 0, counters);
    EXPECT_FALSE(field.empty());
    EXPECT_GE(field.leaf_count(), 1u);
    EXPECT_GT(counters.camera_rays, 0u);
    EXPECT_FALSE(guiding_applies(SceneRuntime(small_cloud(1, 7, false))));
}

// The guided image's mean volume radiance against an unguided render of another seed, over
// the image: within 4 standard errors of the difference, each render's pixel variances
// estimated from a second render of its kind ((a - b)² / 2 per pixel). Guiding is unbiased;
// its weights are heavy-tailed in this forward-scattering cloud, which the second guided
// render's variance carries into the bound.
TEST(VolumeGuiding, GuidedMeanMatchesUnguided) {
    const auto volume_y = [](const SceneDesc& desc) {
        const Image image = render_image(SceneRuntime(desc), quiet(0)).film.to_image();
        const auto& r = image.find("volume.R")->data;
        const auto& g = image.find("volume.G")->data;
        const auto& b = image.find("volume.B")->data;
        std::vector<double> y(r.size());
        for (size_t i = 0; i < y.size(); ++i)
            y[i] = luminance(Rgb(r[i], g[i], b[i]));
        return y;
    };
    const auto guided = volume_y(small_cloud(64, 7, true));
    const auto guided_again = volume_y(small_cloud(64, 10, true));
    const auto plain = volume_y(small_cloud(64, 8, false));
    const auto plain_again = volume_y(small_cloud(64, 9, false));
    double sum_guided = 0.0, sum_plain = 0.0, variance = 0.0;
    for (size_t i = 0; i < plain.size(); ++i) {
        sum_guided += guided[i];
        sum_plain += plain[i];
        variance += 0.5 * (plain[i] - plain_again[i]) * (plain[i] - plain_again[i]) +
                    0.5 * (guided[i] - guided_again[i]) * (guided[i] - guided_again[i]);
    }
    ASSERT_GT(sum_plain, 0.0);
    const double n = static_cast<double>(plain.size());
    EXPECT_NEAR(sum_guided / n, sum_plain / n, 4.0 * std::sqrt(variance) / n);
}

TEST(VolumeGuiding, SettingsAreRangeChecked) {
    const auto guiding = [](const std::string& value) {
        return scene_from_text(R"({"render": {"volume": {"guiding": )" + value + "}}}")
            .render.volume.guiding;
    };
    EXPECT_TRUE(guiding("true").enabled);
    EXPECT_FALSE(guiding("false").enabled);
    const GuidingSettings object = guiding(R"({"mix": 0.3, "training_passes": 2})");
    EXPECT_TRUE(object.enabled);
    EXPECT_FLOAT_EQ(object.mix, 0.3f);
    EXPECT_EQ(object.training_passes, 2);
    EXPECT_FALSE(guiding(R"({"enabled": false})").enabled);
    for (const char* bad : {R"({"mix": 1})", R"({"mix": 0})", R"({"uniform": 1})",
                            R"({"training_passes": 0})", R"({"bins": 4})", "0.5"}) {
        try {
            guiding(bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input) << bad;
            EXPECT_NE(std::string(e.what()).find("/render/volume/guiding"), std::string::npos)
                << e.what();
        }
    }
}

}  // namespace
}  // namespace kasumi
