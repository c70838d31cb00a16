#pragma once
/// The volume stage along one camera ray: transmittance and single-scattered radiance of the
/// scene's media over [0, t_end), with light reaching each sample attenuated by the media and
/// blocked by surfaces.
#include "core/occlusion_query.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/guiding/guiding_settings.h"
#include "volume/medium_set.h"
#include "volume/path_settings.h"

#include <vector>

namespace kasumi {

/// How each march sample gathers light.
enum class LightSampling {
    All,  ///< a shadow ray to every light
    One,  ///< one light, chosen in proportion to its unshadowed contribution; one shadow ray
};

/// Transmittance estimator (docs/volumes.md states each one's bias and variance).
enum class Estimator {
    March,          ///< fixed jittered step, trapezoid rule for tau: biased, O(step²)
    Delta,          ///< delta tracking: unbiased, binary (0 or 1) per channel
    Ratio,          ///< ratio tracking (Novák et al. 2014): unbiased
    ResidualRatio,  ///< residual ratio tracking with the minorant as control: unbiased
    UnbiasedMarch,  ///< debiased jittered march (Kettunen et al. 2021): unbiased, signed
    /// unbiased-march for transmittance; with integrator "single", the camera ray marched and
    /// debiased about the march and the light cache (volume/debiased_march_single.h): unbiased
    DebiasedMarch,
};

/// How the path tracer samples free flights in media (render.volume.free_flight).
enum class FreeFlightSampling {
    Tracking,       ///< spectral (delta) tracking against the majorant (Kutz et al. 2017, §3)
    Decomposition,  ///< decomposition tracking: the minorant sampled analytically (§4)
};

/// How light scattered in media reaches the camera.
enum class VolumeIntegrator {
    Single,    ///< single scattering: next-event estimation to every light
    Multiple,  ///< volumetric path tracing with next-event estimation and Russian roulette
};

struct VolumeSettings {
    float step_m = 0.25f;  ///< longest march step, metres
    LightSampling light_sampling = LightSampling::One;
    /// > 0: march step in voxels of the finest grid (replaces step_m when grids are present).
    float step_voxels = 0.0f;
    Estimator estimator = Estimator::March;
    bool estimator_given = false;  ///< false: chosen from the media by the loader
    VolumeIntegrator integrator = VolumeIntegrator::Single;
    int max_depth = 256;  ///< scattering events per path (multiple scattering)
    /// Directional lights' transmittance through a single grid medium from a precomputed cache
    /// (volume/light_cache.h; biased, stated there) instead of the estimator.
    bool light_cache = false;
    /// Russian roulette on next-event estimation (volume/volume_path.cpp, nee_survival): the
    /// shadow ray toward a light is traced with probability q = min(1, max(0.1, 4 pi p(mu)))
    /// and weighted 1/q, so scattering that sends less light toward the eye than an isotropic
    /// phase would mostly skips its transmittance walk. Unbiased.
    bool nee_roulette = false;
    /// > 0: Russian roulette on next-event estimation by each shadow ray's expected
    /// contribution (render.volume.shadow_roulette; volume/scattered_direct.cpp,
    /// contribution_survival): the path weight x sigma_s p(mu) x the light cache's T, against
    /// this share of an isotropic, fully lit, albedo-1 scatterer's. Replaces nee_roulette where
    /// a light cache exists (a directional light through one grid). 0: off. Unbiased.
    float shadow_roulette = 0.0f;
    /// > 0: the trackers' paths use ratio tracking for in-scattering with next-event
    /// estimation at this many collisions per path segment (volume/volume_path.cpp,
    /// tracked_path_radiance); 0: one free-flight scattering point per segment.
    int nee_points = 0;
    /// > 0: point lights' shadows by the lit intervals along the ray (K = this many equal
    /// parts of the equiangular span, bisection at each lit/shadow boundary, the interpolant
    /// integrated exactly over the lit parts; volume/shadow_intervals.h): deterministic,
    /// biased as bounded there. 0: stratified shadow-ray samples (unbiased).
    int shadow_intervals = 0;
    /// Chromatic media (sigma_t differing per channel): the path tracer's free flights by
    /// spectral MIS (volume/spectral_mis_flight.h; Miller, Georgiev & Jarosz 2019) instead of
    /// spectral tracking. Unbiased either way; grey or emitting media keep spectral tracking.
    bool spectral_mis = false;
    GuidingSettings guiding{};  ///< volume path guiding of multiple scattering (off by default)
    /// The path tracer's free flights (volume/decomposition_tracking.h): decomposition tracking
    /// draws the collisions of each segment's minorant without a density lookup. Unbiased.
    FreeFlightSampling free_flight = FreeFlightSampling::Tracking;
    /// Stochastic (one-voxel) trilinear filtering of the trackers' grid lookups
    /// (render.volume.density_filter "stochastic"; MediumSet::set_stochastic_filter,
    /// docs/volumes.md): unbiased for the trackers; the march and the light cache keep
    /// trilinear lookups. false: trilinear everywhere.
    bool stochastic_filter = false;
    CameraTransmittance camera_transmittance = CameraTransmittance::Walk;
    PathSplitting splitting = PathSplitting::Off;
};

struct VolumeResult {
    Rgb radiance{0.0f};       ///< in-scattered radiance reaching the ray origin, cd/m²
    Rgb transmittance{1.0f};  ///< exp(-tau) over [ray.t_min, ray.t_max]
};

struct VolumeCounters {
    uint64_t steps = 0;            ///< in-scattering samples taken
    uint64_t shadow_rays = 0;      ///< surface occlusion tests toward lights
    uint64_t density_lookups = 0;  ///< point evaluations of the media coefficients
    uint64_t transmittance_estimates = 0;
    uint64_t scattering_events = 0;  ///< real scattering collisions (tracking integrators)
    uint64_t free_flights = 0;       ///< free-flight distance samples (tracking integrators)
    /// Rays (or stretches) whose march step was lengthened to keep at most 65536 nodes
    /// (kMaxMarchSteps in volume/march_walk.h).
    uint64_t bounded_marches = 0;
};

/// Single scattering by ray marching. Each march step [a, a + dt] inside a stretch of constant
/// coefficients takes one sample at a distance drawn in proportion to the (mean-channel)
/// transmittance within the step, with the offset u shared by the ray's steps (stratified), and
/// weights it by T / pdf per channel: unbiased for homogeneous media, with variance that falls
/// as the step shrinks. Transmittance itself is exact (Beer-Lambert per stretch).
/// `occlusion` may be null (no surfaces).
VolumeResult integrate_volume(const MediumSet& media, const std::vector<Light>& lights,
                              const OcclusionQuery* occlusion, const Ray& ray,
                              const VolumeSettings& settings, bool in_scatter, Pcg32& rng,
                              VolumeCounters& counters);

}  // namespace kasumi
