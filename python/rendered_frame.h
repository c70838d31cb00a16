#pragma once
/// One rendered frame as the Python module hands it out, and the NumPy-shaped views of its
/// pixels. Plain C++ (no Python headers), so the ownership the arrays rely on is tested under
/// AddressSanitizer (tests/python/rendered_frame_test.cpp), which cannot load the extension.
#include "render/renderer.h"
#include "render/stage_times.h"
#include "scene/scene_loader.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace kasumi::python {

/// A frame's film with the runtime that rendered it (its EXR metadata and preview settings come
/// from the runtime), the stage times and the frame number. Held by shared_ptr by the Python
/// RenderResult and by every array viewing its planes: the pixels live until the last is gone.
struct RenderedFrame {
    std::shared_ptr<const SceneRuntime> runtime;
    RenderResult result;
    StageTimes times;
    int64_t frame = 0;
};

/// Consecutive film planes seen as one (height, width, channels) float32 array. The film is
/// channel-major (plane c holds pixel i at c * width * height + i), so a channel is one plane
/// further: strides in bytes are (width * 4, 4, channel_stride_bytes).
struct PlaneView {
    std::string name;  ///< "beauty" (R, G, B), "alpha", "albedo", "depth", "surface", ...
    float* data = nullptr;
    int channels = 0;
    std::ptrdiff_t channel_stride_bytes = 0;
};

/// The film's planes grouped by AOV, in Film::planes order: beauty (R, G, B), alpha (A), then
/// each stored AOV ("albedo", "depth", "surface", "volume", "transmittance"). Writable: the
/// frame owns its film, and the views are valid while `frame` lives.
std::vector<PlaneView> plane_views(RenderedFrame& frame);

/// Renders frame `frame` of `source` the way `kasumi render` does: load (source.scene), build
/// the runtime with the GI methods of gi/gi.h, render_image with `options` (every AOV stored),
/// each timed into the frame's StageTimes. Input errors propagate as kasumi::Error.
std::shared_ptr<RenderedFrame> render_frame(const SceneSource& source, int64_t frame,
                                            RenderOptions options);

}  // namespace kasumi::python
