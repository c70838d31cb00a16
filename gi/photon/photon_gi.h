#pragma once
/// render.gi = "photons": Jensen's two-pass photon mapping as a GiMethod. Construction runs the
/// first pass (the three maps); queries are the second pass (gi/photon/photon_render.h).
#include "gi/photon/photon_tracer.h"
#include "render/gi_method.h"
#include "render/whitted.h"

namespace kasumi {

class PhotonGi final : public GiMethod, public PhongShading {
  public:
    /// Traces the photons of render.photons through `scene` (its surfaces and media must be
    /// built) and balances the maps.
    explicit PhotonGi(const SceneRuntime& scene);

    /// Whitted's shade_hit with phong_radiance below at Phong surfaces.
    Rgb surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                         Pcg32& rng, RenderCounters& counters) const override;
    /// Direct light by shadow rays + caustic map + final gathering on the global map.
    Rgb phong_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit, Pcg32& rng,
                       RenderCounters& counters) const override;
    /// In-scattered radiance from the volume map over a camera or secondary segment, added to
    /// the volume stage's single scattering. Zero when render.volume.integrator is "multiple"
    /// (the volume path tracer then carries that light itself).
    Rgb volume_radiance(const SceneRuntime& scene, const Ray& segment, Pcg32& rng) const override;
    std::string summary() const override;

    const PhotonMaps& maps() const { return m_maps; }

  private:
    PhotonMaps m_maps;
};

}  // namespace kasumi
