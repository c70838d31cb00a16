#pragma once
/// Marched single scattering (render.volume.estimator "march" with integrator "single" over
/// grids or a height fog): nodes along the camera segment with a jittered step, next-event
/// estimation to every light at each, the camera transmittance by the trapezoid rule; fast paths
/// for one grey grid lit by cached directional lights and for a lone height fog.
#include "core/occlusion_query.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <vector>

namespace kasumi {

/// Transmittance and single-scattered radiance (cd/m²) over [ray.t_min, ray.t_max) by marching
/// at march_step_m (biased, O(step); unbiased for a lone height fog); the march stops once the
/// camera transmittance of every channel is below 1e-4. Never throws.
VolumeResult march_single(const MediumSet& media, const std::vector<Light>& lights,
                          const OcclusionQuery* occlusion, const Ray& ray,
                          const VolumeSettings& settings, Pcg32& rng, VolumeCounters& counters);

}  // namespace kasumi
