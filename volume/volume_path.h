#pragma once
/// The volume stage for every estimator and integrator: transmittance of a camera segment and
/// the light scattered toward the camera, single (next-event estimation to every light) or
/// multiple (volumetric path tracing with next-event estimation and Russian roulette).
#include "core/occlusion_query.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/in_scattering.h"
#include "volume/medium_set.h"
#include "volume/scattered_paths.h"

#include <vector>

namespace kasumi {

/// The volume stage over the camera segment [ray.t_min, ray.t_max) (t_max: the first surface):
/// - `march` + `single` with only homogeneous media: integrate_volume (exact per stretch);
/// - `march` + `single` with grids: fixed-step marched single scattering (biased, O(step));
/// - otherwise: transmittance by the estimator and scattered light by spectral tracking, with
///   shadow rays through the estimator; `multiple` continues paths by phase sampling up to
///   max_depth, adding what they meet in `environment` (null: nothing) when they leave.
/// `nothing_behind`: no light arrives from beyond the segment (no surface, black background),
/// so the transmittance is only an AOV; the trackers then take it from the first free flight's
/// escape weight (unbiased, noisier) instead of a separate walk, as they always do with
/// render.volume.camera_transmittance "first_flight". `guiding`, if given, guides the
/// tracked paths' scattering directions and collects training records
/// (volume/guiding/path_guiding.h; the marched single-scattering paths take no directions).
/// Never throws.
VolumeResult integrate_media(const MediumSet& media, const std::vector<Light>& lights,
                             const OcclusionQuery* occlusion, const PathEnvironment* environment,
                             const Ray& ray, const VolumeSettings& settings, bool in_scatter,
                             Pcg32& rng, VolumeCounters& counters, bool nothing_behind = false,
                             const PathGuiding* guiding = nullptr);

}  // namespace kasumi
