/// The frame the Python module's arrays view (python/rendered_frame.h): its plane views lie in
/// the film, equal the film's image, are writable, and stay valid while only a copy of the
/// frame's shared pointer lives, which is what an array's base holds after the Scene and the
/// RenderResult are gone. Run under AddressSanitizer by the asan preset, which cannot load the
/// extension itself.
#include "python/rendered_frame.h"

#include <gtest/gtest.h>

#include <memory>

namespace kasumi::python {
namespace {

/// A small fogged quad under a directional light: surfaces, media and every AOV non-trivial.
SceneSource fog_scene() {
    const Json doc = Json::parse(R"({
      "camera": {"position": [0, 1, 5], "look_at": [0, 0.5, 0], "fov_deg": 50},
      "film": {"width": 24, "height": 16, "spp": 2},
      "materials": {"grey": {"type": "phong", "kd": 0.5, "ks": 0.0}},
      "shapes": [{"type": "quad", "material": "grey",
                  "vertices": [[-3, 0, 3], [3, 0, 3], [3, 0, -3], [-3, 0, -3]]}],
      "lights": [{"type": "directional", "direction": [0.3, -1, 0.2], "illuminance_lux": 1000}],
      "media": [{"type": "homogeneous", "bounds": [[-4, -1, -4], [4, 3, 4]],
                 "sigma_a": 0.02, "sigma_s": 0.1}],
      "render": {"seed": 7}
    })");
    return SceneSource(SceneDocument(doc, "rendered_frame_test.json"), {});
}

std::shared_ptr<RenderedFrame> render_fog() {
    RenderOptions options;
    options.progress = false;
    return render_frame(fog_scene(), 0, options);
}

TEST(RenderedFrame, ViewsGroupThePlanesOfEachAov) {
    auto frame = render_fog();
    const std::vector<PlaneView> views = plane_views(*frame);
    const char* names[] = {"beauty",  "alpha",  "albedo",       "depth",
                           "surface", "volume", "transmittance"};
    const int channels[] = {3, 1, 3, 1, 3, 3, 3};
    ASSERT_EQ(views.size(), 7u);
    const std::ptrdiff_t plane_bytes = 24 * 16 * static_cast<std::ptrdiff_t>(sizeof(float));
    for (size_t i = 0; i < views.size(); ++i) {
        EXPECT_EQ(views[i].name, names[i]);
        EXPECT_EQ(views[i].channels, channels[i]) << names[i];
        if (views[i].channels > 1) {
            EXPECT_EQ(views[i].channel_stride_bytes, plane_bytes) << names[i];
        }
    }
}

TEST(RenderedFrame, ViewsHoldTheFilmsPixels) {
    auto frame = render_fog();
    const Image image = frame->result.film.to_image();
    size_t channel = 0;
    double volume_sum = 0.0;
    for (const PlaneView& view : plane_views(*frame)) {
        for (int c = 0; c < view.channels; ++c, ++channel) {
            const auto* plane = reinterpret_cast<const float*>(
                reinterpret_cast<const char*>(view.data) + c * view.channel_stride_bytes);
            const std::vector<float>& expected = image.channels.at(channel).data;
            for (size_t i = 0; i < expected.size(); ++i)
                ASSERT_EQ(plane[i], expected[i]) << image.channels[channel].name << " " << i;
            if (view.name == "volume")
                volume_sum += plane[0] + plane[expected.size() - 1];
        }
    }
    EXPECT_EQ(channel, image.channels.size());
    EXPECT_GT(volume_sum, 0.0);  // the fog scattered light: the views are not of an empty film
}

TEST(RenderedFrame, ViewsOutliveEverythingButTheirOwner) {
    std::shared_ptr<RenderedFrame> owner;  // what an array's base holds
    std::vector<PlaneView> views;
    {
        auto frame = render_fog();
        views = plane_views(*frame);
        owner = frame;
    }  // the frame handed to Python and its source are gone
    const size_t pixels = 24 * 16;
    double sum = 0.0;
    for (const PlaneView& view : views) {
        for (int c = 0; c < view.channels; ++c) {
            auto* plane = reinterpret_cast<float*>(reinterpret_cast<char*>(view.data) +
                                                   c * view.channel_stride_bytes);
            for (size_t i = 0; i < pixels; ++i)
                sum += plane[i];
            plane[0] = 1.0f;  // writable, as the arrays are
        }
    }
    EXPECT_GT(sum, 0.0);
    EXPECT_EQ(owner->result.film.to_image().channels[0].data[0], 1.0f);
}

}  // namespace
}  // namespace kasumi::python
