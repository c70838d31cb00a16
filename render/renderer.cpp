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
        const int x1 = std::min(x0 + tile, width);
        const size_t row = static_cast<size_t>(x1 - x0);
        RenderCounters local;
        // A tile's row is traced one sample index at a time: its camera rays (neighbouring
        // pixels) go through the BVH together (SurfaceScene::intersect_coherent), then each is
        // shaded with its own generator. Every pixel gets the samples, generators and sums it
        // got one pixel at a time (same images, bit for bit). With adaptive sampling only the
        // row's pixels still sampling take the next sample index.
        const SurfaceScene* surfaces = scene.surfaces();
        // render.surface "scanline": the visible surfaces at the pixel centres come from the
        // scanline renderer instead of camera rays through Embree (same hits, same shading).
        const ScanlineSurface* scanline = scene.scanline_surface();
        std::vector<int> pixel_x;
        std::vector<PixelSample> sums(row);
        std::vector<int> hits(row);
        std::vector<float> depth_sums(row);
        std::vector<PixelConvergence> convergence(row);
        std::vector<HalfSums> half_sums(denoise ? row : 0);
        std::vector<size_t> active;  // the row's pixels still sampling, left to right
        active.reserve(row);
        std::vector<CameraSample> samples;
        samples.reserve(row);
        std::vector<Ray> rays(row);
        std::vector<std::optional<SurfaceHit>> first_hits(row);
        for (int y = y0; y < std::min(y0 + tile, height) && !stopped; ++y) {
            active.clear();
            for (size_t i = 0; i < row; ++i) {
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
                    samples.push_back(camera_sample(scene, x0 + static_cast<int>(active[k]), y, s,
                                                    options.frame));
                    rays[k] = samples[k].ray;
                }
                if (scanline != nullptr) {
                    pixel_x.clear();
                    for (size_t i : active)
                        pixel_x.push_back(x0 + static_cast<int>(i));
                    scanline->first_hits(y, pixel_x.data(), rays.data(), active.size(),
                                         first_hits.data());
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
                // Each pixel decides from its own samples alone (render/adaptive_sampling.h).
                active.erase(std::remove_if(active.begin(), active.end(),
                                            [&](size_t i) {
                                                return !keeps_sampling(convergence[i], criterion);
                                            }),
                             active.end());
            }
            if (!complete)
                break;
            for (size_t i = 0; i < row; ++i) {
                result.film.set_pixel(x0 + static_cast<int>(i), y, sums[i], convergence[i].n,
                                      hits[i], depth_sums[i]);
                if (denoise)
                    halves.set_pixel(x0 + static_cast<int>(i), y, half_sums[i], convergence[i].n);
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
