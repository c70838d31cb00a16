#pragma once
/// Light shafts in the atmosphere (`render.sky.shafts`): surfaces and media (clouds, fog) hide
/// the sun from part of the air between the camera and what it sees, so that part adds no
/// single-scattered sunlight. The sky stage (sky/sky_renderer.h) integrates the air as if
/// the sun lit all of it; this stage estimates the single-scattered sunlight of the shadowed
/// air over the first `render.sky.shaft_distance_m` of a camera ray,
///
///   dL = integral over [0, D] of T_air(0, s) sum_k sigma_s,k(h(s)) p_k(mu) T_sun(x(s)) E_sun
///        (1 - V(x(s))) ds,          V = V_surfaces(x -> sun) T_media(x -> sun),
///
/// and subtracts it: L = L_air - dL + T_air L_behind. D = min(shaft_distance_m, the surface,
/// the end of the atmosphere); k runs over Rayleigh and Mie with their phase functions at
/// mu = cos(view, sun); T_sun is the air's transmittance toward the sun (with the fraction of
/// the disc above the horizon), E_sun the sun at the top of the atmosphere. The multiply
/// scattered sky light (Hillaire's table, or the reference's higher orders) and the light of
/// the ground stay unshadowed: shadows of diffuse sky light are broad and faint, and shafts are
/// single-scattering phenomena.
///
/// Quadrature: `render.sky.shaft_samples` strata of equal length over [0, D], one jittered
/// node per stratum (stratified sampling, unbiased for the integral of the piecewise-constant
/// visibility); T_air(0, s) accumulates the midpoint optical depth between nodes. Surfaces by
/// one shadow ray per node (Embree, render.shadows must be on); media by the scene's
/// transmittance estimator toward the sun. Where every node sees the sun, dL = 0 exactly and
/// the pixel equals the render without shafts.
#include "core/film.h"
#include "core/rng.h"
#include "render/render_stats.h"
#include "render/scene_runtime.h"

namespace kasumi {

/// dL for the camera ray `ray` whose first surface is at t_end (kInfinity: none), cd/m² RGB.
/// Zero without an atmosphere or with shafts off. Never throws.
Rgb shadowed_sun_scattering(const SceneRuntime& scene, const Ray& ray, float t_end, Pcg32& rng,
                            RenderCounters& counters);

/// Subtracts shadowed_sun_scattering from the sample's radiance and volume AOV (clamped at 0:
/// the estimate of dL and the sky stage's L_air come from different quadratures).
void apply_sky_shafts(const SceneRuntime& scene, const Ray& ray, float t_end, Pcg32& rng,
                      PixelSample& sample, RenderCounters& counters);

}  // namespace kasumi
