#pragma once
/// The frame every global-illumination method plugs into (render.gi): a method is built once per
/// scene (its view-independent precomputation: a radiosity solution, photon maps) and then asked
/// for the radiance leaving each surface hit. trace_camera_ray calls gi_surface_radiance, which
/// dispatches to the scene's method; with render.gi = "none" it is the Whitted shade_hit.
#include "core/rng.h"
#include "render/render_stats.h"
#include "surface/material.h"
#include "surface/surface_scene.h"

#include <memory>
#include <string>

namespace kasumi {

class SceneRuntime;

/// One global-illumination method, built by make_gi_method. Thread-safe for concurrent queries.
class GiMethod {
  public:
    virtual ~GiMethod() = default;
    /// Radiance (cd/m²) leaving `hit` toward -ray.direction, for a camera ray or a ray that left
    /// the media (volume multiple scattering). Default: Whitted's shade_hit, which recurses
    /// through mirrors and dielectrics and calls phong_radiance at Phong surfaces.
    virtual Rgb surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                                 Pcg32& rng, RenderCounters& counters) const;
    /// Radiance (cd/m²) reflected by a Phong surface at `hit` toward -ray.direction (emission
    /// excluded: shade_hit adds it), direct and indirect light as this method computes them.
    virtual Rgb phong_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                               Pcg32& rng, RenderCounters& counters) const = 0;
    /// One line for the plan: what was computed (residual, solve time, photon counts, ...).
    virtual std::string summary() const = 0;
};

/// Builds the scene's render.gi method (null for "none"); runs its precomputation. Throws an
/// input error naming the scene file for a method this build does not have.
std::shared_ptr<const GiMethod> make_gi_method(const SceneRuntime& scene);

/// Radiance (cd/m²) leaving `hit` toward -ray.direction by the scene's GI method, or Whitted's
/// shade_hit without one. The dispatch point of trace_camera_ray. Never throws.
Rgb gi_surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                        Pcg32& rng, RenderCounters& counters);

/// Radiance (cd/m²) a surface point emits toward wo: the material's emission on the front side
/// (dot(geometric normal, wo) > 0: the side a quad's or triangle's vertices wind
/// counter-clockwise toward, the outside of boxes and spheres, as for polygon lights), zero on
/// the back. Lambertian: the same in every front direction.
Rgb emitted_radiance(const Material& material, const SurfaceHit& hit, const Vec3& wo);

}  // namespace kasumi
