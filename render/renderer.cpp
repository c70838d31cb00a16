#include "render/renderer.h"

#include "core/progress.h"
#include "render/adaptive_sampling.h"
#include "render/camera_sample.h"
#include "render/denoise/half_buffers.h"
#include "render/denoise/nlm_filter.h"
#include "render/guiding_training.h"
#include "render/integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

namespace kasumi {

namespace {

bool is_finite_sample(const PixelSample& s) {
    return is_finite(s.radiance) && is_finite(s.surface) && is_finite(s.volume) &&
           is_finite(s.transmittance) && std::isfinite(s.depth);
}

}  // namespace

RenderResult render_image(const SceneRuntime& scene, const RenderOptions& options) {
    const SceneDesc& desc = scene.desc();
    const int width = desc.film.width, height = desc.film.height;
    const AdaptiveCriterion criterion = adaptive_criterion(desc.film);
    // A uniform render's sample count is film.spp everywhere: no plane for it.
    uint32_t aovs = criterion.threshold > 0.0 ? options.aovs : options.aovs & ~kAovSamples;
    // film.denoise: the raw beauty is kept as noisy.R/G/B (if asked for); the half buffers
    // (render/denoise/half_buffers.h) feed the filter after the last tile.
    const bool denoise = desc.film.denoise.enabled;
    aovs = denoise ? aovs : aovs & ~kAovNoisy;
    HalfBuffers halves = denoise ? HalfBuffers(width, height) : HalfBuffers();
    const int tile = desc.render.tile_size;
    const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
    const int threads = options.threads > 0 ? options.threads : desc.render.threads;

    RenderResult result{Film(width, height, aovs), {}, 0.0, 1, false};
    std::mutex counters_mutex;
    std::atomic<bool> stopped{false};
    Progress progress("render", static_cast<uint64_t>(tiles_x) * tiles_y, options.progress);
    const auto start = std::chrono::steady_clock::now();

    // Cancellation is polled before every sample (one relaxed atomic load, nothing next to a
    // camera ray): a pixel of 2^20 samples stops within one sample, not at the end of its tile.
    // A pixel cut short is left unwritten, like the tiles never started.
    const auto cancelled = [&] {
        if (options.cancel == nullptr || !options.cancel->load(std::memory_order_relaxed))
            return false;
        stopped = true;
        return true;
    };
    // Volume path guiding: the field is trained (deterministically) before the first tile.
    GuidingField field;
    PathGuiding guiding_state;
    const PathGuiding* guiding = nullptr;
    auto render_tile = [&](int tile_index) {
        if (cancelled())
            return;
        const int x0 = (tile_index % tiles_x) * tile, y0 = (tile_index / tiles_x) * tile;
        const int x1 = std::min(x0 + tile, width), y1 = std::min(y0 + tile, height);
        const int row = x1 - x0;
        RenderCounters local;
        // Batches of rows are traced one sample index at a time: their camera rays
        // (neighbouring pixels) go through the BVH together (SurfaceScene::intersect_coherent),
        // then each is shaded with its own generator. Every pixel gets the samples, generators
        // and sums it got one pixel at a time (same images, bit for bit). A uniform render's
        // batch is one row of the tile; with adaptive sampling it is the whole tile (a pixel's
        // count reads its neighbours in the tile, render/adaptive_sampling.h), and only the
        // pixels still sampling take the next sample index.
        const int batch_rows = criterion.threshold > 0.0 ? tile : 1;
        const size_t batch = static_cast<size_t>(row) * batch_rows;
        const SurfaceScene* surfaces = scene.surfaces();
        // render.surface "scanline": the visible surfaces at the pixel centres come from the
        // scanline renderer instead of camera rays through Embree (same hits, same shading).
        const ScanlineSurface* scanline = scene.scanline_surface();
        std::vector<int> pixel_x;
        std::vector<PixelSample> sums(batch);
        std::vector<int> hits(batch);
        std::vector<float> depth_sums(batch);
        std::vector<PixelConvergence> convergence(batch);
        std::vector<int> planned;  // window >= 1: each pixel's count, fixed after the pilot
        std::vector<HalfSums> half_sums(denoise ? batch : 0);
        std::vector<size_t> active;  // the batch's pixels still sampling, row-major
        active.reserve(batch);
        std::vector<CameraSample> samples;
        samples.reserve(batch);
        std::vector<Ray> rays(batch);
        std::vector<std::optional<SurfaceHit>> first_hits(batch);
        for (int yb = y0; yb < y1 && !stopped; yb += batch_rows) {
            const int rows = std::min(batch_rows, y1 - yb);
            const size_t pixels = static_cast<size_t>(row) * rows;
            const auto pixel_of = [&](size_t i) {
                return std::pair<int, int>(x0 + static_cast<int>(i % row),
                                           yb + static_cast<int>(i / row));
            };
            active.clear();
            planned.clear();
            for (size_t i = 0; i < pixels; ++i) {
                sums[i] = PixelSample{};
                sums[i].transmittance = Rgb(0.0f);
                hits[i] = 0;
                depth_sums[i] = 0.0f;
                convergence[i] = PixelConvergence{};
                if (denoise)
                    half_sums[i] = HalfSums{};
                active.push_back(i);
            }
            bool complete = true;
            for (int s = 0; !active.empty(); ++s) {
                if (cancelled()) {
                    complete = false;
                    break;
                }
                samples.clear();
                for (size_t k = 0; k < active.size(); ++k) {
                    const auto [x, y] = pixel_of(active[k]);
                    samples.push_back(camera_sample(scene, x, y, s, options.frame));
                    rays[k] = samples[k].ray;
                }
                if (scanline != nullptr) {
                    // One call per row of the batch (active is row-major).
                    for (size_t k0 = 0; k0 < active.size();) {
                        const int y = pixel_of(active[k0]).second;
                        pixel_x.clear();
                        size_t k1 = k0;
                        for (; k1 < active.size() && pixel_of(active[k1]).second == y; ++k1)
                            pixel_x.push_back(pixel_of(active[k1]).first);
                        scanline->first_hits(y, pixel_x.data(), rays.data() + k0, k1 - k0,
                                             first_hits.data() + k0);
                        k0 = k1;
                    }
                } else if (surfaces != nullptr)
                    surfaces->intersect_coherent(rays.data(), active.size(), first_hits.data());
                for (size_t k = 0; k < active.size(); ++k) {
                    const size_t i = active[k];
                    const PixelSample p =
                        trace_camera_ray(scene, rays[k], samples[k].rng, local,
                                         surfaces != nullptr ? &first_hits[k] : nullptr, guiding);
                    if (!is_finite_sample(p)) {
                        ++local.nonfinite_samples;
                        convergence[i].add(0.0);  // counted, as zero: the mean stays unbiased
                        continue;
                    }
                    convergence[i].add(luminance(p.radiance));
                    PixelSample& sum = sums[i];
                    sum.radiance += p.radiance;
                    sum.surface += p.surface;
                    sum.volume += p.volume;
                    sum.transmittance += p.transmittance;
                    sum.albedo += p.albedo;
                    if (p.hit) {
                        ++hits[i];
                        depth_sums[i] += p.depth;
                    }
                    if (denoise)
                        half_sums[i].add(s, p);
                }
                // The stopping rule (render/adaptive_sampling.h): window 0 reads each pixel's
                // own samples after every round; a window fixes every count once, when the
                // whole batch has its pilot (all pixels sample until then).
                if (criterion.window > 0 && criterion.threshold > 0.0) {
                    if (s + 1 == criterion.min_spp)
                        planned = neighbourhood_sample_counts(
                            std::vector<PixelConvergence>(convergence.begin(),
                                                          convergence.begin() + pixels),
                            row, rows, criterion);
                    const int taken = s + 1;
                    active.erase(
                        std::remove_if(active.begin(), active.end(),
                                       [&](size_t i) {
                                           return taken >= criterion.max_spp ||
                                                  (!planned.empty() && taken >= planned[i]);
                                       }),
                        active.end());
                } else
                    active.erase(
                        std::remove_if(
                            active.begin(), active.end(),
                            [&](size_t i) { return !keeps_sampling(convergence[i], criterion); }),
                        active.end());
            }
            if (!complete)
                break;
            for (size_t i = 0; i < pixels; ++i) {
                const auto [x, y] = pixel_of(i);
                result.film.set_pixel(x, y, sums[i], convergence[i].n, hits[i], depth_sums[i]);
                if (denoise)
                    halves.set_pixel(x, y, half_sums[i], convergence[i].n);
            }
        }
        {
            std::lock_guard<std::mutex> lock(counters_mutex);
            result.counters += local;
        }
        progress.advance();
    };

    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.initialize();
    result.threads = arena.max_concurrency();
    arena.execute([&] {
        if (guiding_applies(scene)) {
            field = train_guiding_field(scene, options.frame, result.counters);
            guiding_state = PathGuiding{&field, desc.render.volume.guiding.mix, nullptr};
            guiding = &guiding_state;
        }
        tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
                          [&](const tbb::blocked_range<int>& r) {
                              for (int i = r.begin(); i < r.end(); ++i)
                                  render_tile(i);
                          });
        // The filter's time is the render's (a study compares denoised and raw renders at
        // their full cost). An interrupted render is left raw.
        if (denoise && !stopped) {
            const DenoisedBeauty beauty = denoise_beauty(halves, desc.film.denoise);
            const float* rgb[3] = {beauty.rgb[0].data(), beauty.rgb[1].data(),
                                   beauty.rgb[2].data()};
            result.film.replace_beauty(rgb);
        }
    });
    progress.finish();
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.interrupted = stopped.load();
    return result;
}

}  // namespace kasumi
