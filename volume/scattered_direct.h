#pragma once
/// Next-event estimation inside media: the light of every light scattered toward the viewer at a
/// point, with shadow rays through the media's transmittance estimator (or the light cache) and
/// the surfaces' occlusion. Shared by the marched single scattering and the scattered paths.
#include "core/occlusion_query.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <optional>
#include <vector>

namespace kasumi {

/// Light from every light scattered toward wo at x per unit length (1/m · cd/m²):
/// sum_l sum_m sigma_s,m(x) p_m(mu_l) E_l T_l V_l, one sample_incident per light (extended
/// lights are sampled), the transmittance T_l by `settings.estimator`, the visibility V_l by
/// `occlusion` (null: no surfaces; lights with shadows "none" are never blocked). `known`: the
/// coefficients already looked up at x (a tracker's collision), so a single medium's sigma_s is
/// not looked up again. `path_weight`: the mean of the weight the caller multiplies the result
/// by (the path throughput; after a free flight it carries 1/sigma, so it is in metres and
/// path_weight x sigma_s p is per steradian); it steers only render.volume.shadow_roulette.
Rgb scattered_direct(const MediumSet& media, const std::vector<Light>& lights,
                     const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                     const Vec3& wo, const VolumeSettings& settings, Pcg32& rng,
                     VolumeCounters& counters, const PointCoefficients* known = nullptr,
                     float path_weight = 1.0f);

/// scattered_direct for one light (index `light_index` in the scene's list, for its light
/// cache); `step`: the march step (metres) of the transmittance estimator.
Rgb scattered_direct_one(const MediumSet& media, const Light& light, size_t light_index,
                         const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                         const Vec3& wo, const VolumeSettings& settings, float step, Pcg32& rng,
                         VolumeCounters& counters, const PointCoefficients* known = nullptr,
                         float path_weight = 1.0f);

/// render.volume.shadow_roulette's probability of tracing a shadow ray whose expected
/// contribution (before E) is `expected` = path weight x mean(sigma_s p(mu) T_cache) (1/sr):
/// q = min(1, max(kShadowSurvivalFloor, 4 pi expected / share)), i.e. every ray expected to
/// bring at least `share` of what an isotropic, fully lit, albedo-1 scatterer would is traced,
/// the others in proportion (Russian roulette, Arvo & Kirk 1990; unbiased with weight 1/q for
/// any q > 0). The variance added is at most (1/q - 1) c² <= c · share · E / (4 pi) per event:
/// summed over a path, `share` times its radiance times E / (4 pi).
float contribution_survival(float expected, float share);

/// The smallest probability contribution_survival returns: bounds the variance where the
/// light cache underestimates T (it is biased; volume/light_cache.h).
constexpr float kShadowSurvivalFloor = 0.05f;

/// What one light contributes at x once its incident light `in` and the phase-weighted
/// scattering `f` are known: f E T V, with V from `occlusion` and T from the light cache (when
/// `cache` is given and covers x: `cached`) or the transmittance estimator.
Rgb light_term(const MediumSet& media, const Light& light, const OcclusionQuery* occlusion,
               const Vec3& x, const IncidentLight& in, const Rgb& f,
               const std::optional<Rgb>& cached, const VolumeSettings& settings, float step,
               Pcg32& rng, VolumeCounters& counters);

/// Whether a surface blocks the shadow ray from x toward the light of `in` (counted as a volume
/// shadow ray); false without `occlusion`.
bool light_blocked(const OcclusionQuery* occlusion, const Vec3& x, const IncidentLight& in,
                   VolumeCounters& counters);

}  // namespace kasumi
