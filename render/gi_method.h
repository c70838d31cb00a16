#pragma once
/// The interface through which the renderer's surface stage hands a surface hit to the scene's
/// global-illumination method (render.gi). Declared here, implemented in gi/ (path tracer,
/// radiosity, photon mapping) and built there by make_gi_method (gi/gi.h), which callers pass to
/// SceneRuntime: render/ never includes gi/, and a method calls render/'s functions (Whitted,
/// shade_surface, the volume stage) only downward.
#include "core/color.h"
#include "core/rng.h"
#include "render/render_stats.h"
#include "surface/surface_scene.h"

#include <functional>
#include <memory>
#include <string>

namespace kasumi {

class SceneRuntime;

/// One global-illumination method with its view-independent precomputation (a radiosity
/// solution, photon maps), built once per scene. Thread-safe for concurrent queries.
class GiMethod {
  public:
    virtual ~GiMethod() = default;
    /// Radiance (cd/m²) leaving `hit` toward -ray.direction, emission included, for a camera ray
    /// or a ray that left the media (volume multiple scattering): the whole surface stage at a
    /// hit, mirrors and dielectrics included. Never throws.
    virtual Rgb surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                                 Pcg32& rng, RenderCounters& counters) const = 0;
    /// In-scattered radiance (cd/m²) this method adds to the volume stage over a camera or
    /// secondary segment (the photon volume map); zero by default, drawing nothing from `rng`.
    virtual Rgb volume_radiance(const SceneRuntime& /*scene*/, const Ray& /*segment*/,
                                Pcg32& /*rng*/) const {
        return Rgb(0.0f);
    }
    /// One line for the plan: what was computed (residual, solve time, photon counts, ...).
    virtual std::string summary() const = 0;
};

/// Builds a scene's render.gi method from its runtime (surfaces, media and sky built); null for
/// "none". gi/gi.h's make_gi_method is the one the library ships.
using GiFactory = std::function<std::shared_ptr<const GiMethod>(const SceneRuntime&)>;

}  // namespace kasumi
