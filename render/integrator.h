#pragma once
/// The per-sample integrator that composes the stages along one camera ray:
///   L = L_volume + T * (L_surface or L_background).
#include "core/film.h"
#include "core/rng.h"
#include "render/render_stats.h"
#include "render/scene_runtime.h"
#include "volume/guiding/path_guiding.h"

namespace kasumi {

/// Radiance (cd/m²) and AOVs seen along `ray` (a camera ray). Never throws; a non-finite result
/// is returned as is for the caller to count. `first_hit`, when given, is the ray's closest
/// surface hit already traced (SurfaceScene::intersect_coherent for a row of pixels).
/// `guiding`, if given, guides the volume stage's paths and collects their training records.
PixelSample trace_camera_ray(const SceneRuntime& scene, const Ray& ray, Pcg32& rng,
                             RenderCounters& counters,
                             const std::optional<SurfaceHit>* first_hit = nullptr,
                             const PathGuiding* guiding = nullptr);

/// The volume stage over one ray segment [segment.t_min, segment.t_max) (t_max: the first
/// surface, or kInfinity): transmittance and in-scattered radiance, for camera rays and for
/// Whitted's reflected and refracted rays alike. Counts one volume ray. `guiding` as
/// integrate_media's (volume/volume_path.h). `lights`, if given, replace the scene's lights
/// for this segment (render/air_and_media.h: the sun as seen from the segment). Never throws.
VolumeResult trace_volume_segment(const SceneRuntime& scene, const Ray& segment, Pcg32& rng,
                                  RenderCounters& counters, const PathGuiding* guiding = nullptr,
                                  const std::vector<Light>* lights = nullptr);

/// What is known, before any shadow ray, about whether a light is blocked by surfaces at a
/// shading point (gi/photon/photon_shadow.h decides it from shadow photons).
enum class KnownVisibility : uint8_t {
    Unknown,   ///< cast the shadow rays
    Lit,       ///< nothing blocks the light: no shadow ray
    Shadowed,  ///< the light is blocked: no shadow ray, no light
};

/// Phong shading of a surface point by the scene's lights and ambient term (no media in front);
/// black for mirrors and dielectrics (render/whitted.h traces those).
/// Media between the surface and each light attenuate it through the scene's transmittance
/// estimator (stochastic for grids; `rng` drives it). `known`, if given, holds one entry per
/// light: for lights with ray-traced shadows, Lit and Shadowed replace the occlusion test (each
/// shadow ray not cast counts in counters.shadow_rays_avoided).
Rgb shade_surface(const SceneRuntime& scene, const SurfaceHit& hit, const Vec3& wo, Pcg32& rng,
                  RenderCounters& counters, const KnownVisibility* known = nullptr);

}  // namespace kasumi
