#pragma once
/// Unbiased marched single scattering (render.volume.estimator "debiased-march" with integrator
/// "single"): the biased march's nodes and its cached shadow depths kept as controls, and every
/// transmittance debiased about them (Kettunen, d'Eon, Pantaleoni & Novák 2021, §4–5; the
/// telescoping view of Misso, Li, Burley, Teece & Jarosz 2022, "Unbiased and consistent
/// rendering using biased estimators": a biased estimate plus an unbiased estimate of its error).
///
/// The radiance along the camera ray is L = integral of sum_l f_l(t) E_l V_l T_cam(t) T_l(t) dt,
/// f_l = sigma_s(t) p(mu_l) (scattering per unit length and steradian). Estimator:
///   L^ = sum_k h f(t_k) T^_cam(t_k) T^_l(t_k),   t_k = t_min + (u + k) h, one u per ray.
/// Unbiased: given u (the nodes and every lookup at them fixed), T^_cam(t_k) and T^_l(t_k) are
/// unbiased and drawn from independent random numbers, so E[T^_cam T^_l | u] = T_cam T_l; and
/// E_u[sum_k h g(t_k)] = integral of g for the deterministic g = f T_cam T_l (each t in the ray
/// is a node for exactly one k and u). The factors:
/// - T^_cam(t_k) = debiased_exp_about(tau_trap(t_k), ...): the pivot is the march's own trapezoid
///   depth (a function of u only), the N_cam corrections (one roulette per ray, SeriesRoulette
///   {0.4, 2}: six rays in ten take none) are independent jittered residual marches of the
///   camera ray, whose running sums are unbiased depths for every prefix [t_min, t_k) at once
///   (volume/unbiased_march.h, ResidualMarch::Prefix).
/// - T^_l(t_k) for a directional light over a grid medium with a light cache
///   (volume/light_cache.h): debiased_exp_about(sigma_t D_cache(x_k), ...) with N_l independent
///   residual marches along the shadow ray (SeriesRoulette {0.5, 1}): the cached depth is only a
///   control, so the cache's bias (Simpson, blur) no longer reaches the image; it only sets the
///   variance. N_l is drawn by inversion from v_k = frac(v_0 + k phi) (phi = 0.618..., v_0
///   uniform per ray and light, k the lit node's index): each v_k is uniform and independent of
///   that node's marches and of T^_cam, so each node's factor stays unbiased (the expectation of
///   the sum is the sum of the nodes' expectations; only the variance sees the correlation), and
///   the corrected nodes are spread evenly along the ray instead of clumping. Other lights, and
///   points off the cache's lattice, take the unbiased-march estimator of the shadow ray
///   (light_term, scattered_direct_one).
/// - The camera march stops without bias: once the pivot's depth passes kTailDepth (T = 1e-4)
///   the ray continues with probability 1/10 and weight 10, then again every ln 10 of depth
///   (Russian roulette; Arvo & Kirk 1990).
/// The transmittance returned is the same running estimate at the ray's end (0 for a ray the
/// roulette ended). Single estimates are signed; their mean is the single scattering.
/// For one grid medium with grey extinction, no emission and only cached directional lights
/// (a cloud under the sun) the camera march walks the grid's bricks (volume/march_grid_walk.h,
/// the biased march's fast path: the same nodes and trapezoid depth as march_walk), so the
/// estimator is the same and only cheaper.
#include "core/occlusion_query.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <optional>
#include <vector>

namespace kasumi {

/// Unbiased single-scattered radiance (cd/m²) and transmittance over [ray.t_min, ray.t_max),
/// nodes every march_step_m (render.volume.step_m / step_voxels); see above. std::nullopt,
/// having drawn no random number, when a segment of the ray is endless (an unbounded fog: the
/// caller takes the trackers). Never throws.
std::optional<VolumeResult> debiased_march_single(const MediumSet& media,
                                                  const std::vector<Light>& lights,
                                                  const OcclusionQuery* occlusion, const Ray& ray,
                                                  const VolumeSettings& settings, Pcg32& rng,
                                                  VolumeCounters& counters);

}  // namespace kasumi
