#pragma once
/// The second pass of photon mapping (Jensen 2001, ch. 9; Jensen & Christensen 1998): distribution
/// ray tracing where the radiance at a Phong surface is
///   direct light by shadow rays (shade_surface) + caustics from the caustic map
///   + indirect light by final gathering on the global map,
/// mirrors and glass are followed as in Whitted tracing, and along every ray through media the
/// light scattered once straight from the lights comes from shadow rays (the volume stage with
/// single scattering) and the rest from the volume map, ray-marched.
#include "core/film.h"
#include "core/rng.h"
#include "render/photon_settings.h"
#include "render/photon_tracer.h"
#include "render/render_stats.h"
#include "render/scene_runtime.h"

namespace kasumi {

/// What the second pass reads: the scene, its maps and the estimate settings.
struct PhotonRenderContext {
    const SceneRuntime& scene;
    const PhotonMaps& maps;
    const PhotonSettings& settings;
};

/// A camera sample: radiance and AOVs as trace_camera_ray returns them. Never throws.
PixelSample trace_photon_camera_ray(const PhotonRenderContext& context, const Ray& ray, Pcg32& rng,
                                    RenderCounters& counters);

/// Radiance (cd/m²) arriving at ray.origin along -ray.direction: the first surface's outgoing
/// radiance behind the media, or the background. `depth` counts specular bounces (limited by
/// render.whitted.max_depth, as are branch weights by render.whitted.min_weight).
Rgb photon_ray_radiance(const PhotonRenderContext& context, const Ray& ray, Pcg32& rng,
                        RenderCounters& counters, int depth = 0, float weight = 1.0f);

/// Reflected radiance at a Phong hit toward wo read from the global map alone (the estimate a
/// final-gather ray uses), with the map's full Phong BRDF.
Rgb global_map_radiance(const PhotonRenderContext& context, const SurfaceHit& hit, const Vec3& wo);

/// In-scattered radiance from the volume map along a ray segment [t_min, t_max): the march
/// Σ h T(t_i) σ_s ∫ p L dω at nodes t_i spaced h = render.volume.step_m with one random offset
/// per ray (unbiased in the march for a given estimate; the estimate itself is biased by its
/// radius).
Rgb volume_map_radiance(const PhotonRenderContext& context, const Ray& segment, Pcg32& rng);

}  // namespace kasumi
