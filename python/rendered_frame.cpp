#include "python/rendered_frame.h"

#include "core/error.h"
#include "gi/gi.h"

#include <chrono>

namespace kasumi::python {

namespace {

/// "albedo.R" -> "albedo"; the beauty's bare "R", "G", "B" -> "beauty", "A" -> "alpha".
std::string aov_name(const std::string& channel) {
    const size_t dot = channel.find('.');
    if (dot != std::string::npos)
        return channel.substr(0, dot);
    return channel == "A" ? "alpha" : "beauty";
}

}  // namespace

std::vector<PlaneView> plane_views(RenderedFrame& frame) {
    const Film& film = frame.result.film;
    std::vector<PlaneView> views;
    for (const FilmPlane& plane : film.planes(film.aovs())) {
        // The film is owned by `frame`, not shared with a const user: writing through the
        // views (NumPy arrays are writable) is writing to our own pixels.
        float* data = const_cast<float*>(plane.data);
        const std::string name = aov_name(plane.name);
        if (views.empty() || views.back().name != name) {
            views.push_back({name, data, 1, 0});
            continue;
        }
        PlaneView& view = views.back();
        const std::ptrdiff_t offset =
            reinterpret_cast<const char*>(data) - reinterpret_cast<const char*>(view.data);
        if (view.channels == 1)
            view.channel_stride_bytes = offset;
        // One stride for all channels of a view: the planes of one AOV lie one plane apart.
        KASUMI_CHECK(offset == view.channels * view.channel_stride_bytes);
        ++view.channels;
    }
    return views;
}

std::shared_ptr<RenderedFrame> render_frame(const SceneSource& source, int64_t frame,
                                            RenderOptions options) {
    StageTimes times;
    const auto load_start = std::chrono::steady_clock::now();
    SceneDesc desc = source.scene(frame);
    times.load_s = seconds_since(load_start);
    const auto build_start = std::chrono::steady_clock::now();
    auto runtime = std::make_shared<const SceneRuntime>(std::move(desc), make_gi_method);
    times.build_s = seconds_since(build_start);
    add_stage_parts(times, *runtime);
    options.frame = static_cast<uint32_t>(frame);
    options.aovs = kAovAll;
    RenderResult result = render_image(*runtime, options);
    times.render_s = result.seconds;
    return std::make_shared<RenderedFrame>(
        RenderedFrame{std::move(runtime), std::move(result), std::move(times), frame});
}

}  // namespace kasumi::python
