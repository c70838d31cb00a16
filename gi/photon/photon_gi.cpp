#include "gi/photon/photon_gi.h"

#include "gi/photon/photon_render.h"
#include "render/scene_runtime.h"

#include <cstdio>

namespace kasumi {

PhotonGi::PhotonGi(const SceneRuntime& scene)
    : m_maps(build_photon_maps(scene, scene.desc().render.photons, scene.desc().render.seed,
                               scene.desc().render.threads)) {}

Rgb PhotonGi::surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                               Pcg32& rng, RenderCounters& counters) const {
    return shade_hit(scene, ray, hit, rng, counters, this);
}

Rgb PhotonGi::phong_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                             Pcg32& rng, RenderCounters& counters) const {
    const PhotonRenderContext context{scene, m_maps, scene.desc().render.photons};
    return photon_phong_radiance(context, hit, -ray.direction, rng, counters);
}

Rgb PhotonGi::volume_radiance(const SceneRuntime& scene, const Ray& segment, Pcg32& rng) const {
    if (m_maps.volume.empty() || !scene.plan().in_scattering ||
        scene.desc().render.volume.integrator == VolumeIntegrator::Multiple)
        return Rgb(0.0f);
    const PhotonRenderContext context{scene, m_maps, scene.desc().render.photons};
    return volume_map_radiance(context, segment, rng);
}

std::string PhotonGi::summary() const {
    char text[320];
    std::snprintf(text, sizeof(text),
                  "global %zu stored of %llu emitted, caustic %zu of %llu, volume %zu "
                  "of %llu; tracing %.2f s, kd-trees %.2f s",
                  m_maps.global.size(), static_cast<unsigned long long>(m_maps.global_emitted),
                  m_maps.caustic.size(), static_cast<unsigned long long>(m_maps.caustic_emitted),
                  m_maps.volume.size(), static_cast<unsigned long long>(m_maps.volume_emitted),
                  m_maps.trace_seconds, m_maps.build_seconds);
    std::string out = text;
    if (m_maps.shadow_emitted > 0)
        out += "; shadow map " + std::to_string(m_maps.shadow.size()) +
               " direct and shadow photons of " + std::to_string(m_maps.shadow_emitted) +
               " emitted";
    return out;
}

}  // namespace kasumi
