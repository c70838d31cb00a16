#pragma once
/// The volume stage along one camera ray: transmittance and single-scattered radiance of the
/// scene's media over [0, t_end), with light reaching each sample attenuated by the media and
/// blocked by surfaces.
#include "core/rng.h"
#include "core/scene_queries.h"
#include "lights/light.h"
#include "volume/medium_set.h"

#include <vector>

namespace kasumi {

/// How each march sample gathers light.
enum class LightSampling {
    All,  ///< a shadow ray to every light
    One,  ///< one light, chosen in proportion to its unshadowed contribution; one shadow ray
};

struct VolumeSettings {
    float step_m = 0.25f;  ///< longest march step, metres
    LightSampling light_sampling = LightSampling::One;
};

struct VolumeResult {
    Rgb radiance{0.0f};       ///< in-scattered radiance reaching the ray origin, cd/m²
    Rgb transmittance{1.0f};  ///< exp(-tau) over [ray.t_min, ray.t_max]
};

struct VolumeCounters {
    uint64_t steps = 0;        ///< in-scattering samples taken
    uint64_t shadow_rays = 0;  ///< surface occlusion tests toward lights
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
