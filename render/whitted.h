#pragma once
/// Whitted ray tracing (Whitted 1980): the radiance a surface hit sends back along a ray, with
/// mirrors and dielectrics followed recursively through reflected and refracted rays, and the
/// volume stage (fog) applied to every secondary segment exactly as to camera rays.
#include "core/rng.h"
#include "render/render_stats.h"
#include "render/scene_runtime.h"

namespace kasumi {

/// What a Phong surface reflects at a hit Whitted reaches, emission excluded: null in shade_hit
/// means direct light (shade_surface, or Gouraud-interpolated); a GI method (radiosity, photon
/// mapping) passes itself and keeps Whitted's recursion through mirrors and dielectrics.
class PhongShading {
  public:
    virtual ~PhongShading() = default;
    /// Radiance (cd/m²) reflected by the Phong surface at `hit` toward -ray.direction, emission
    /// excluded. Never throws.
    virtual Rgb phong_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                               Pcg32& rng, RenderCounters& counters) const = 0;
};

/// Radiance (cd/m²) a surface point emits toward wo: the material's emission on the front side
/// (dot(geometric normal, wo) > 0: the side a quad's or triangle's vertices wind
/// counter-clockwise toward, the outside of boxes and spheres, as for polygon lights), zero on
/// the back. Lambertian: the same in every front direction.
Rgb emitted_radiance(const Material& material, const SurfaceHit& hit, const Vec3& wo);

/// Radiance (cd/m²) leaving `hit` toward -ray.direction, for the hit of `ray` (a camera ray or a
/// secondary ray at recursion depth `depth`, carrying the path weight `weight` in (0, 1]):
/// - Phong: `phong`'s phong_radiance; without it (null) direct lighting (shade_surface), with
///   Gouraud shading evaluated at the hit triangle's vertices (their normals, the view
///   direction toward ray.origin) and interpolated with the barycentrics. No recursion.
/// - mirror: kr L(reflected ray).
/// - dielectric: F L(reflected) + (1 - F) tint / η² L(refracted) with F the exact Fresnel
///   reflectance and η = η_refracted side / η_viewer side (radiance scales by 1/η² across the
///   interface; the factors cancel on a path that leaves the medium again); total internal
///   reflection sends everything into the reflected ray.
/// A secondary ray is traced only while depth < render.whitted.max_depth and its weight (the
/// product of kr, F or (1 - F) tint along the path; the largest channel) stays at or above
/// render.whitted.min_weight; a branch cut off contributes nothing (black). Shadow rays treat
/// mirrors and dielectrics as opaque (no caustics). Never throws.
Rgb shade_hit(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit, Pcg32& rng,
              RenderCounters& counters, const PhongShading* phong = nullptr, int depth = 0,
              float weight = 1.0f);

/// Radiance (cd/m²) arriving at ray.origin along -ray.direction through the scene: the first
/// surface's shade_hit (else the sky with the sun's disc when the scene has an atmosphere, or
/// the background), behind the media between (the volume stage over [ray.t_min, hit)) and the
/// air's aerial perspective (render/sky_environment.h). `phong`, `depth` and `weight` as for
/// shade_hit. Never throws.
Rgb trace_whitted_ray(const SceneRuntime& scene, const Ray& ray, Pcg32& rng,
                      RenderCounters& counters, const PhongShading* phong, int depth, float weight);

}  // namespace kasumi
