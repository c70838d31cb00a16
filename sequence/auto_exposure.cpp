#include "sequence/auto_exposure.h"

#include "core/exposure_meter.h"
#include "render/renderer.h"
#include "sequence/frame_runtime.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace kasumi {

double smoothed_log2_luminance(int64_t frame, const std::function<double(int64_t)>& log2_meter) {
    const double newest = log2_meter(frame);
    // Differences from the newest metering, so equal meterings give it back to the bit.
    double weighted = 0.0, weights = 1.0;
    for (int64_t j = 1; j < kAutoExposureWindowFrames && frame - j >= 0; ++j) {
        const double w = std::exp(-static_cast<double>(j) / kAutoExposureTimeConstantFrames);
        weighted += w * (log2_meter(frame - j) - newest);
        weights += w;
    }
    return newest + weighted / weights;
}

AutoExposure::AutoExposure(const SceneSource& source, const std::string& scene_path, bool reuse,
                           int threads, const std::string& store_dir)
    : m_source(source),
      m_scene_path(scene_path),
      m_reuse(reuse),
      m_threads(threads),
      m_cache(reuse),
      m_store(store_dir) {}

float AutoExposure::exposure_stops(int64_t frame) {
    return metered_exposure_stops(
        smoothed_log2_luminance(frame, [this](int64_t f) { return log2_luminance(f); }));
}

double AutoExposure::log2_luminance(int64_t frame) {
    if (const auto it = m_by_frame.find(frame); it != m_by_frame.end())
        return it->second;
    const auto start = std::chrono::steady_clock::now();
    const Json doc = std::move(m_source.frame_document(frame).json());
    std::string text = doc.dump();
    if (const auto it = m_by_document.find(text); it != m_by_document.end())
        return m_by_frame[frame] = it->second;
    if (const std::optional<double> stored = m_store.find(text)) {
        ++m_stored;
        m_by_document.emplace(std::move(text), *stored);
        return m_by_frame[frame] = *stored;
    }

    SceneDesc desc = m_source.parse(doc, frame, &m_cache);
    const double aspect =
        static_cast<double>(desc.film.height) / static_cast<double>(desc.film.width);
    desc.film.width = kMeterWidth;
    desc.film.height = std::max(1, static_cast<int>(std::lround(kMeterWidth * aspect)));
    desc.film.spp = kMeterSpp;
    const std::unique_ptr<SceneRuntime> runtime =
        build_frame_runtime(m_cache, doc, m_scene_path, std::move(desc), m_reuse);
    RenderOptions options;
    options.frame = 0;  // a function of the document alone: equal documents meter equal
    options.aovs = 0;
    options.threads = m_threads;
    options.progress = false;  // an internal render: its progress bar is not the frame's
    const RenderResult result = render_image(*runtime, options);
    m_cache.end_frame();
    const std::vector<FilmPlane> planes = result.film.planes(0);  // R, G, B, A
    const double log2_lum =
        log2_average_luminance(planes[0].data, planes[1].data, planes[2].data,
                               static_cast<size_t>(runtime->desc().film.width) *
                                   static_cast<size_t>(runtime->desc().film.height));
    ++m_renders;
    m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (std::string problem = m_store.put(text, log2_lum); m_store_problem.empty())
        m_store_problem = std::move(problem);
    m_by_document.emplace(std::move(text), log2_lum);
    return m_by_frame[frame] = log2_lum;
}

}  // namespace kasumi
