#include "gi/gi.h"

#include "core/error.h"
#include "gi/path_tracer.h"
#include "gi/photon/photon_gi.h"
#include "gi/radiosity_gi.h"
#include "render/scene_runtime.h"
#include "render/whitted.h"

namespace kasumi {

Rgb GiMethod::surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                               Pcg32& rng, RenderCounters& counters) const {
    return shade_hit(scene, ray, hit, rng, counters);
}

std::shared_ptr<const GiMethod> make_gi_method(const SceneRuntime& scene) {
    const SceneDesc& desc = scene.desc();
    switch (desc.render.gi) {
        case GiMode::None:
            return nullptr;
        case GiMode::Path:
            return std::make_shared<PathTracer>(scene);
        case GiMode::Radiosity:
            return std::make_shared<RadiosityGi>(scene);
        case GiMode::Photons:
            return std::make_shared<PhotonGi>(scene);
    }
    throw_input_error(desc.file + ": render.gi = " + gi_mode_name(desc.render.gi) +
                      ": not available in this build");
}

Rgb gi_surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                        Pcg32& rng, RenderCounters& counters) {
    if (const GiMethod* gi = scene.gi())
        return gi->surface_radiance(scene, ray, hit, rng, counters);
    return shade_hit(scene, ray, hit, rng, counters);
}

Rgb emitted_radiance(const Material& material, const SurfaceHit& hit, const Vec3& wo) {
    if (glm::dot(hit.geometric_normal, wo) <= 0.0f)
        return Rgb(0.0f);
    return emission(material);
}

}  // namespace kasumi
