#pragma once
/// The volume stage for every estimator and integrator: transmittance of a camera segment and
/// the light scattered toward the camera, single (next-event estimation to every light) or
/// multiple (volumetric path tracing with next-event estimation and Russian roulette).
#include "core/rng.h"
#include "core/occlusion_query.h"
#include "lights/light.h"
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

/// Light from every light scattered toward wo at x per unit length (1/m · cd/m²):
/// sum_l sum_m sigma_s,m(x) p_m(mu_l) E_l T_l V_l, one sample_incident per light (extended
/// lights are sampled), the transmittance T_l by `settings.estimator`, the visibility V_l by
/// `occlusion` (null: no surfaces; lights with shadows "none" are never blocked). `known`: the
/// coefficients already looked up at x (a tracker's collision), so a single medium's sigma_s is
/// not looked up again.
Rgb scattered_direct(const MediumSet& media, const std::vector<Light>& lights,
                     const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                     const Vec3& wo, const VolumeSettings& settings, Pcg32& rng,
                     VolumeCounters& counters, const PointCoefficients* known = nullptr);

/// The volume stage over the camera segment [ray.t_min, ray.t_max) (t_max: the first surface):
/// - `march` + `single` with only homogeneous media: integrate_volume (exact per stretch);
/// - `march` + `single` with grids: fixed-step marched single scattering (biased, O(step));
/// - otherwise: transmittance by the estimator and scattered light by spectral tracking, with
///   shadow rays through the estimator; `multiple` continues paths by phase sampling up to
///   max_depth, adding what they meet in `environment` (null: nothing) when they leave.
/// `nothing_behind`: no light arrives from beyond the segment (no surface, black background),
/// so the transmittance is only an AOV; the trackers then take it from the first free flight's
/// escape weight (unbiased, noisier) instead of a separate walk. Never throws.
VolumeResult integrate_media(const MediumSet& media, const std::vector<Light>& lights,
                             const OcclusionQuery* occlusion, const PathEnvironment* environment,
                             const Ray& ray, const VolumeSettings& settings, bool in_scatter,
                             Pcg32& rng, VolumeCounters& counters, bool nothing_behind = false);

}  // namespace kasumi
