#include "surface/emitter_hit.h"

#include "lights/light_hit.h"

namespace kasumi {

std::optional<EmitterHit> intersect_emitters(const std::vector<Light>& lights, const Ray& ray) {
    std::optional<EmitterHit> nearest;
    Ray r = ray;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (const auto hit = intersect(lights[i], r)) {
            nearest = EmitterHit{hit->t, hit->radiance, i};
            r.t_max = hit->t;
        }
    }
    return nearest;
}

bool has_visible_emitters(const std::vector<Light>& lights) {
    for (const Light& light : lights)
        if (std::holds_alternative<PolygonLight>(light.emitter) ||
            std::holds_alternative<SphereLight>(light.emitter))
            return true;
    return false;
}

}  // namespace kasumi
