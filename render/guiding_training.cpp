#include "render/guiding_training.h"

#include "render/camera_sample.h"
#include "render/integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <mutex>
#include <variant>
#include <vector>

namespace kasumi {

bool guiding_applies(const SceneRuntime& scene) {
    const VolumeSettings& volume = scene.desc().render.volume;
    return (volume.guiding.enabled || volume.splitting == PathSplitting::Guided) &&
           scene.plan().in_scattering && volume.integrator == VolumeIntegrator::Multiple &&
           !scene.media().media().empty();
}

GuidingField train_guiding_field(const SceneRuntime& scene, uint32_t frame,
                                 RenderCounters& counters) {
    GuidingField field;
    if (!guiding_applies(scene))
        return field;
    const SceneDesc& desc = scene.desc();
    const GuidingSettings& settings = desc.render.volume.guiding;
    const int width = desc.film.width, height = desc.film.height;
    std::vector<std::vector<GuidingRecord>> rows(static_cast<size_t>(height));
    // Each pixel's summed volume luminance over the passes (the window's centres).
    std::vector<double> pixel_sums(static_cast<size_t>(width) * static_cast<size_t>(height), 0.0);
    std::mutex counters_mutex;
    for (int pass = 0; pass < settings.training_passes; ++pass) {
        const PathGuiding previous{field.empty() ? nullptr : &field, settings.mix, nullptr};
        tbb::parallel_for(
            tbb::blocked_range<int>(0, height, 1), [&](const tbb::blocked_range<int>& r) {
                RenderCounters local;
                for (int y = r.begin(); y < r.end(); ++y) {
                    std::vector<GuidingRecord>& records = rows[static_cast<size_t>(y)];
                    records.clear();
                    PathGuiding guiding = previous;
                    guiding.records = &records;
                    for (int x = 0; x < width; ++x) {
                        for (int s = 0; s < settings.training_spp; ++s) {
                            const int sample = static_cast<int>(kGuidingTrainingSampleBase) +
                                               pass * settings.training_spp + s;
                            CameraSample c = camera_sample(scene, x, y, sample, frame);
                            const PixelSample p =
                                trace_camera_ray(scene, c.ray, c.rng, local, nullptr, &guiding);
                            const double y_volume = luminance(p.volume);
                            if (std::isfinite(y_volume))
                                pixel_sums[static_cast<size_t>(y * width + x)] += y_volume;
                        }
                    }
                }
                std::lock_guard<std::mutex> lock(counters_mutex);
                counters += local;
            });
        std::vector<GuidingRecord> records;
        for (const auto& row : rows)
            records.insert(records.end(), row.begin(), row.end());
        field = GuidingField(records, settings.leaf_records, settings.uniform);
    }
    if (desc.render.volume.splitting == PathSplitting::Guided) {
        // The first medium's phase function turns the learnt L_i into in-scattered radiance.
        field.convolve(std::visit([](const auto& m) -> const PhaseFunction& { return m.phase; },
                                  scene.media().media().front().model));
        const double samples = static_cast<double>(settings.training_passes) *
                               static_cast<double>(settings.training_spp);
        std::vector<float> means(pixel_sums.size());
        for (size_t i = 0; i < means.size(); ++i)
            means[i] = static_cast<float>(pixel_sums[i] / samples);
        field.set_pixel_estimates(PixelEstimates(scene.camera(), width, height, means));
    }
    return field;
}

}  // namespace kasumi
