#pragma once
/// Counters that prove which stages ran and measure the volume hot path. Each tile counts into
/// its own RenderCounters (no sharing between threads, no atomics); tiles are merged once each.
#include <cstdint>
#include <string>

namespace kasumi {

struct RenderCounters {
    uint64_t camera_rays = 0;
    uint64_t surface_hits = 0;
    uint64_t surface_shadow_rays = 0;
    /// Shadow rays from surfaces not cast because shadow photons decided the visibility.
    uint64_t shadow_rays_avoided = 0;
    uint64_t volume_rays = 0;         ///< camera rays that ran the volume stage
    uint64_t volume_steps = 0;        ///< in-scattering samples
    uint64_t volume_shadow_rays = 0;  ///< occlusion tests from media toward lights
    uint64_t nonfinite_samples = 0;   ///< samples dropped because they were NaN or infinite
    /// Point evaluations of the media coefficients (each reads every grid the point lies in).
    uint64_t density_lookups = 0;
    /// Transmittance estimates through media: camera segments, shadow rays from media and from
    /// surfaces toward lights.
    uint64_t transmittance_rays = 0;
    uint64_t free_flights = 0;       ///< free-flight distance samples (tracking integrators)
    uint64_t scattering_events = 0;  ///< real scattering collisions
    /// Camera-ray marches whose step was lengthened to keep at most 65536 nodes (kMaxMarchSteps).
    uint64_t bounded_marches = 0;

    RenderCounters& operator+=(const RenderCounters& o) {
        camera_rays += o.camera_rays;
        surface_hits += o.surface_hits;
        surface_shadow_rays += o.surface_shadow_rays;
        shadow_rays_avoided += o.shadow_rays_avoided;
        volume_rays += o.volume_rays;
        volume_steps += o.volume_steps;
        volume_shadow_rays += o.volume_shadow_rays;
        nonfinite_samples += o.nonfinite_samples;
        density_lookups += o.density_lookups;
        transmittance_rays += o.transmittance_rays;
        free_flights += o.free_flights;
        scattering_events += o.scattering_events;
        bounded_marches += o.bounded_marches;
        return *this;
    }
};

/// Rates derived from the counters of one render: per second of wall time, and per core
/// (divided by the threads the render ran on).
struct RenderRates {
    double density_lookups_per_s = 0.0;
    double density_lookups_per_s_per_core = 0.0;
    double camera_rays_per_s = 0.0;
    /// Camera rays, transmittance rays and free flights: every ray walked through the media.
    double all_rays_per_s = 0.0;
};

inline RenderRates render_rates(const RenderCounters& c, double seconds, int threads) {
    RenderRates r;
    if (!(seconds > 0.0))
        return r;
    const double cores = threads > 0 ? static_cast<double>(threads) : 1.0;
    r.density_lookups_per_s = static_cast<double>(c.density_lookups) / seconds;
    r.density_lookups_per_s_per_core = r.density_lookups_per_s / cores;
    r.camera_rays_per_s = static_cast<double>(c.camera_rays) / seconds;
    r.all_rays_per_s =
        static_cast<double>(c.camera_rays + c.transmittance_rays + c.free_flights) / seconds;
    return r;
}

}  // namespace kasumi
