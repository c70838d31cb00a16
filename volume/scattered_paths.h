#pragma once
/// Volumetric path tracing along a camera segment: free flights (path_radiance) or ratio-tracked
/// walks with next-event estimation at picked collisions (tracked_path_radiance), single or
/// multiple scattering as render.volume.integrator says, with Russian roulette.
#include "core/occlusion_query.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/guiding/path_guiding.h"
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <vector>

namespace kasumi {

/// What a scattered path meets when it leaves the media: render/ implements it over the
/// surfaces (their directly lit radiance) and the background.
class PathEnvironment {
  public:
    virtual ~PathEnvironment() = default;
    /// Distance along `ray` to the first surface, kInfinity if none.
    virtual float surface_distance(const Ray& ray) const = 0;
    /// Radiance arriving at ray.origin from -ray.direction from beyond the media: the first
    /// surface's outgoing radiance, or the background. cd/m².
    virtual Rgb radiance(const Ray& ray, Pcg32& rng) const = 0;
};

/// Radiance (cd/m²) scattered toward the camera along `camera_segment` by paths of free flights
/// (sample_free_flight) with next-event estimation at every scattering event; `multiple`
/// continues each by phase sampling up to max_depth and adds what it meets in `environment`
/// (null: nothing) when it leaves. `first_escape`, if given, receives the first flight's escape
/// weight (an unbiased estimate of the segment's transmittance). `guiding`, if given, guides
/// the scattering directions and collects training records (volume/guiding/path_guiding.h).
/// Never throws.
Rgb path_radiance(const MediumSet& media, const std::vector<Light>& lights,
                  const OcclusionQuery* occlusion, const PathEnvironment* environment,
                  const Ray& camera_segment, const VolumeSettings& settings, Pcg32& rng,
                  VolumeCounters& counters, Rgb* first_escape,
                  const PathGuiding* guiding = nullptr);

/// Volumetric path tracing with ratio tracking for in-scattering (track_collisions) on every
/// path segment: the segment's walk gives T^(t_i) / mu at each tentative collision t_i, and
/// with c_i = mean(throughput T^(t_i) sigma_s(t_i) / mu) (the collision's share of the
/// segment's scattered light, light left out), next-event estimation is done at `nee_points`
/// collisions picked by systematic sampling in the running sum of c_i (one uniform offset per
/// segment: collision i is picked n_i times with E[n_i] = nee_points c_i, every pick weighted
/// 1 / (nee_points c_i): unbiased, and the picks are stratified along the ray instead of one
/// free-flight point). `multiple` continues the path from the free flight that spectral
/// tracking draws on the same collisions (its weight, as sample_free_flight's); a flight that
/// escapes adds what it meets beyond the media, as path_radiance; `guiding` as there.
Rgb tracked_path_radiance(const MediumSet& media, const std::vector<Light>& lights,
                          const OcclusionQuery* occlusion, const PathEnvironment* environment,
                          const Ray& camera_segment, const VolumeSettings& settings, Pcg32& rng,
                          VolumeCounters& counters, Rgb* first_escape,
                          const PathGuiding* guiding = nullptr);

}  // namespace kasumi
