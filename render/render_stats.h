#pragma once
/// Counters that prove which stages ran. Summed per tile, merged at the end.
#include <cstdint>
#include <string>

namespace kasumi {

struct RenderCounters {
    uint64_t camera_rays = 0;
    uint64_t surface_hits = 0;
    uint64_t surface_shadow_rays = 0;
    uint64_t volume_rays = 0;         ///< camera rays that ran the volume stage
    uint64_t volume_steps = 0;        ///< in-scattering samples
    uint64_t volume_shadow_rays = 0;  ///< occlusion tests from media toward lights
    uint64_t nonfinite_samples = 0;   ///< samples dropped because they were NaN or infinite

    RenderCounters& operator+=(const RenderCounters& o) {
        camera_rays += o.camera_rays;
        surface_hits += o.surface_hits;
        surface_shadow_rays += o.surface_shadow_rays;
        volume_rays += o.volume_rays;
        volume_steps += o.volume_steps;
        volume_shadow_rays += o.volume_shadow_rays;
        nonfinite_samples += o.nonfinite_samples;
        return *this;
    }
};

}  // namespace kasumi
