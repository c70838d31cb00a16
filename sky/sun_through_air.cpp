#include "sky/sun_through_air.h"

#include "sky/sky_reference.h"

namespace kasumi {

Bands sun_transmittance_at(const SkyRenderer& renderer, const DVec3& x) {
    const SkyScene& sky = renderer.sky();
    if (const SkyLuts* luts = renderer.luts()) {
        Bands t{};
        luts->sun_transmittance(sky, x, t);
        return t;
    }
    return sun_transmittance(sky, x, sky.settings.sun_steps);
}

Rgb sun_illuminance_at(const SkyRenderer& renderer, const DVec3& x) {
    return renderer.sky().to_rgb(sun_transmittance_at(renderer, x));
}

std::optional<size_t> find_sun_light(const SkyScene& sky, const std::vector<Light>& lights) {
    const Vec3 toward_ground(-sky.sun_direction);
    for (size_t i = 0; i < lights.size(); ++i) {
        const auto* d = std::get_if<DirectionalLight>(&lights[i].emitter);
        if (d != nullptr && lights[i].name == "sun" && d->direction == toward_ground)
            return i;
    }
    return std::nullopt;
}

}  // namespace kasumi
