#pragma once
/// The second pass of photon mapping (Jensen 2001, ch. 9; Jensen & Christensen 1998): distribution
/// ray tracing where the radiance at a Phong surface is
///   direct light by shadow rays (shade_surface) + caustics from the caustic map
///   + indirect light by final gathering on the global map,
/// mirrors and glass are followed as in Whitted tracing, and along every ray through media the
/// light scattered once straight from the lights comes from shadow rays (the volume stage with
/// single scattering) and the rest from the volume map, ray-marched.
#include "core/rng.h"
#include "gi/photon/photon_tracer.h"
#include "render/render_stats.h"
#include "render/scene_runtime.h"
#include "scene/photon_settings.h"

namespace kasumi {

/// What the second pass reads: the scene, its maps and the estimate settings.
struct PhotonRenderContext {
    const SceneRuntime& scene;
    const PhotonMaps& maps;
    const PhotonSettings& settings;
};

/// Radiance (cd/m²) a Phong surface reflects at `hit` toward wo: direct light by shadow rays
/// (shade_surface), caustics from the caustic map and indirect light by final gathering
/// (render.photons.final_gather_samples rays; 0: the global map read directly). Emission is
/// not included. Never throws.
Rgb photon_phong_radiance(const PhotonRenderContext& context, const SurfaceHit& hit, const Vec3& wo,
                          Pcg32& rng, RenderCounters& counters);

/// In-scattered radiance from the volume map along a ray segment [t_min, t_max): the march
/// Σ h T(t_i) σ_s ∫ p L dω at nodes t_i spaced h = render.volume.step_m with one random offset
/// per ray (unbiased in the march for a given estimate; the estimate itself is biased by its
/// radius).
Rgb volume_map_radiance(const PhotonRenderContext& context, const Ray& segment, Pcg32& rng);

}  // namespace kasumi
