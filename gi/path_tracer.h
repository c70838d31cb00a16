#pragma once
/// The reference path tracer (render.gi = "path"): unbiased Monte Carlo estimates of the
/// rendering equation over energy-conserving Phong (surface/phong_brdf.h), mirrors and dielectrics
/// (exact Fresnel, reflection or refraction chosen with probability F), with next-event
/// estimation at Phong vertices to every light and to the emissive surfaces, combined with BSDF
/// sampling by multiple importance sampling (power heuristic, Veach & Guibas 1995) for polygon
/// lights, sphere lights and emissive triangles; Russian roulette from render.path.rr_depth,
/// at most render.path.max_depth bounces. Media along every segment go through the volume stage
/// (volume/volume_path.h: transmittance and in-scattering, single or multiple as
/// render.volume.integrator says); shadow rays through media are attenuated by the scene's
/// transmittance estimator. Polygon and sphere lights are seen by bounce rays (weighted by MIS
/// after Phong bounces), so mirrors show them and glass focuses them. Shadow rays test every
/// light whose `shadows` is not "none" (shadow maps and volumes are a direct-light technique:
/// the path tracer uses rays for them).
#include "gi/gi_emitters.h"
#include "render/gi_method.h"
#include "render/scene_runtime.h"

namespace kasumi {

class PathTracer final : public GiMethod {
  public:
    explicit PathTracer(const SceneRuntime& scene);

    /// One path from `hit` (reached along `ray`): radiance toward -ray.direction, the hit's own
    /// emission included. Never throws.
    Rgb surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                         Pcg32& rng, RenderCounters& counters) const override;
    std::string summary() const override;

  private:
    Rgb direct_light(const SceneRuntime& scene, const SurfaceHit& hit, const PhongMaterial& m,
                     const Vec3& ns, const Vec3& wo, Pcg32& rng, RenderCounters& counters) const;
    Rgb lights_hit(const SceneRuntime& scene, const Ray& ray, float t_end, bool specular,
                   float bsdf_pdf, Pcg32& rng) const;

    EmissiveTriangles m_emitters;
};

/// Rejects Phong materials with kd + ks > 1 in some channel (they would create energy),
/// naming the scene file and material; the GI methods call it before they start.
void require_energy_conserving(const SceneDesc& scene);

}  // namespace kasumi
