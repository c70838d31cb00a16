#pragma once
/// Renders a scene into a film: tiles in parallel (oneTBB), each pixel sample with its own
/// generator keyed by (pixel, sample, frame, seed), so the image is bit-identical for any
/// thread count or tile order.
#include "core/film.h"
#include "render/render_stats.h"
#include "render/scene_runtime.h"

#include <atomic>

namespace kasumi {

struct RenderOptions {
    int threads = 0;  ///< 0: the scene's render.threads (0 there: all hardware threads)
    uint32_t frame = 0;
    bool progress = true;
    const std::atomic<bool>* cancel =
        nullptr;  ///< set asynchronously to stop after the current tiles
    /// FilmAov bits the film stores (only those can be written); samples only when adaptive
    uint32_t aovs = kAovAll | kAovSamples;
};

struct RenderResult {
    Film film;
    RenderCounters counters;
    double seconds = 0.0;
    int threads = 1;           ///< worker threads the render ran on (for per-core rates)
    bool interrupted = false;  ///< tiles not rendered are black
};

RenderResult render_image(const SceneRuntime& scene, const RenderOptions& options);

}  // namespace kasumi
