#pragma once
/// The atmosphere and the scene's media as one medium along a camera ray. Without it the air
/// is composed in front of the first surface only, so a cloud 20 km away would be seen through
/// no air at all and the air behind it would shine through it.
///
/// Along the ray, with the media's extent [t_in, t_out] (their first and last non-empty
/// majorant stretch) and the air's camera-referenced in-scattering L_air(0, t) and
/// transmittance T_air(0, t) (the aerial-perspective table, sky/aerial_perspective.h):
///
///   L = L_air(0, t_in)
///     + sum_k M_k [ s_air,k dL_air,k + T_air(0, a_k) s_med,k L_med,k ]
///     + M_n [ dL_air(t_out, t_end) + T_air(0, t_end) L_behind ],
///
/// over pieces [a_k, b_k] of [t_in, t_out] (each max(250 m, a_k / 8) long, at most 24), where
/// L_med,k, T_med,k are the media's scattered light and transmittance over the piece (the
/// scene's volume stage, render/integrator.h), M_k = prod_{j<k} T_med,j, dL_air,k =
/// L_air(0, b_k) - L_air(0, a_k) and L_behind is the surface or, for a ray that meets none,
/// the sky beyond t_out (SkyRenderer::environment from x(t_out), sun disc included). Inside a
/// piece the air and the media are mixed: with optical depths tau_a = -ln T_air,k and
/// tau_m = -ln T_med,k, each one's light is scaled by its share of a homogeneous mixture,
///   s_air = g(tau_a + tau_m) / g(tau_a),  s_med = g(tau_a + tau_m) / g(tau_m),
///   g(x) = (1 - e^{-x}) / x,
/// exact when both are homogeneous over the piece (their source terms then add, and the
/// mixture's light is (S_a + S_m) l g(tau_a + tau_m)); an opaque piece of cloud (T_med = 0)
/// thus hides the air behind its entry, so a black cloud looks like a black surface at the same
/// distance. (With a noisy T_med the shares are a nonlinear function of an unbiased estimate:
/// slightly biased, O(piece length) in the air's optical depth.)
///
/// The media in piece k are lit by the sun as seen from its midpoint x_k: the scene's sun light
/// (make_sun_light, evaluated at the origin) takes the illuminance sun_illuminance_at(x_k)
/// (sky/sun_through_air.h: the top-of-atmosphere sun times T_air(x_k -> sun), with Earth's
/// shadow), so cloud tops redden at sunset and go dark after it. The sky's light reaches the
/// media through the volume stage's own paths: with integrator "multiple" a path that leaves
/// the media takes the sky's radiance seen from where it leaves (PathEnvironment); "single"
/// scattering has no sky light on the media.
///
/// Russian roulette ends the pieces once max(M) < 0.05 (survival max(M) / 0.05, the
/// survivors reweighted: unbiased). Light shafts (render/sky_shafts.h) are subtracted from each
/// part of the air, attenuated like it (clamped at 0 as apply_sky_shafts is). A ray that
/// crosses no media is composed exactly as in a scene without media.
#include "core/film.h"
#include "core/rng.h"
#include "render/render_stats.h"
#include "render/scene_runtime.h"
#include "volume/guiding/path_guiding.h"

namespace kasumi {

/// Composes the air (scene.sky(), not null), the media and what lies behind them into
/// `sample` for the camera ray `ray` whose first surface (or visible light) is at t_end
/// (kInfinity: none); sample.surface, hit, depth and albedo are set by the caller. Writes
/// radiance, volume, transmittance (and surface: the sky behind, for rays that meet nothing).
/// Never throws.
void compose_air_and_media(const SceneRuntime& scene, const Ray& ray, float t_end, Pcg32& rng,
                           RenderCounters& counters, const PathGuiding* guiding,
                           PixelSample& sample);

}  // namespace kasumi
