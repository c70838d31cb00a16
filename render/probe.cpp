#include "render/probe.h"

#include "render/integrator.h"

namespace kasumi {

RadianceProbe probe_radiance(const SceneRuntime& scene, const Vec3& origin, const Vec3& direction,
                             int spp) {
    RenderCounters counters;
    glm::dvec3 sum(0.0), sum_sq(0.0);
    const Ray ray{origin, glm::normalize(direction), 0.0f, kInfinity};
    for (int s = 0; s < spp; ++s) {
        Pcg32 rng = pixel_rng(0xffffffffu, 0xffffffffu, static_cast<uint32_t>(s), 0u,
                              scene.desc().render.seed);
        const Rgb l = trace_camera_ray(scene, ray, rng, counters).radiance;
        sum += glm::dvec3(l);
        sum_sq += glm::dvec3(l) * glm::dvec3(l);
    }
    RadianceProbe probe;
    probe.samples = spp;
    const glm::dvec3 mean = sum / static_cast<double>(spp);
    probe.radiance = Rgb(mean);
    if (spp > 1) {
        const glm::dvec3 var =
            glm::max(sum_sq / static_cast<double>(spp) - mean * mean, glm::dvec3(0.0)) *
            (static_cast<double>(spp) / (spp - 1));
        probe.stderr_ = Rgb(glm::sqrt(var / static_cast<double>(spp)));
    }
    probe.luminance_cd_m2 = luminance(probe.radiance);
    return probe;
}

}  // namespace kasumi
