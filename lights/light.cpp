#include "lights/light.h"

namespace kasumi {

namespace {

IncidentLight incident(const DirectionalLight& l, const Vec3&) {
    IncidentLight in;
    in.wi = -l.direction;
    in.irradiance = l.illuminance;
    return in;
}

IncidentLight incident(const PointLight& l, const Vec3& p) {
    IncidentLight in;
    const Vec3 to_light = l.position - p;
    const float r2 = glm::dot(to_light, to_light);
    in.light_position = l.position;
    if (!(r2 > 1e-12f)) {
        in.distance = 0.0f;
        return in;
    }
    in.distance = std::sqrt(r2);
    in.wi = to_light / in.distance;
    in.irradiance = l.intensity / r2;
    return in;
}

}  // namespace

IncidentLight incident_light(const Light& light, const Vec3& p) {
    return std::visit([&](const auto& emitter) { return incident(emitter, p); }, light.emitter);
}

float luminous_flux_lm(const Light& light) {
    if (const auto* point = std::get_if<PointLight>(&light.emitter)) {
        return 4.0f * kPi * luminance(point->intensity);
    }
    return 0.0f;
}

std::string light_type_name(const Light& light) {
    return std::holds_alternative<DirectionalLight>(light.emitter) ? "directional" : "point";
}

}  // namespace kasumi
