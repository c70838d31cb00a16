#include "lights/light.h"

#include "lights/point_source.h"

namespace kasumi {

namespace {

IncidentLight incident(const DirectionalLight& l, const Vec3&) {
    IncidentLight in;
    in.wi = -l.direction;
    in.irradiance = l.illuminance;
    return in;
}

IncidentLight incident(const PointLight& l, const Vec3& p) {
    IncidentLight in = point_source_incident(l.position, p);
    if (in.distance > 0.0f)
        in.irradiance = l.intensity / (in.distance * in.distance);
    return in;
}

template <typename T>
constexpr bool kIsDelta = std::is_same_v<T, DirectionalLight> || std::is_same_v<T, PointLight> ||
                          std::is_same_v<T, SpotLight> || std::is_same_v<T, GoniometricLight>;

}  // namespace

bool is_delta(const Light& light) {
    return std::visit([](const auto& e) { return kIsDelta<std::decay_t<decltype(e)>>; },
                      light.emitter);
}

bool shadows_by_stage(ShadowMode mode) {
    return mode == ShadowMode::Map || mode == ShadowMode::ShadowVolume ||
           mode == ShadowMode::ObjectSpace || mode == ShadowMode::Scanline;
}

IncidentLight incident_light(const Light& light, const Vec3& p) {
    return std::visit(
        [&](const auto& e) {
            if constexpr (kIsDelta<std::decay_t<decltype(e)>>) {
                return incident(e, p);
            } else {
                return IncidentLight{};
            }
        },
        light.emitter);
}

IncidentLight sample_incident(const Light& light, const Vec3& p, Vec2 u) {
    return std::visit(
        [&](const auto& e) {
            if constexpr (kIsDelta<std::decay_t<decltype(e)>>) {
                return incident(e, p);
            } else {
                return sample_incident(e, p, u);
            }
        },
        light.emitter);
}

IncidentLight sample_incident(const Light& light, const Vec3& p, Pcg32& rng) {
    return is_delta(light) ? incident_light(light, p) : sample_incident(light, p, rng.next_vec2());
}

float shadow_sample_weight(const Light& light, const Vec3& p, const Vec3& n, float unshadowed_sum) {
    if (is_delta(light))
        return 1.0f;
    if (!(unshadowed_sum > 0.0f))
        return 0.0f;
    return luminance(unshadowed_irradiance(light, p, n)) / unshadowed_sum;
}

Rgb unshadowed_irradiance(const Light& light, const Vec3& p, const Vec3& n) {
    return std::visit(
        [&](const auto& e) {
            if constexpr (kIsDelta<std::decay_t<decltype(e)>>) {
                const IncidentLight in = incident(e, p);
                return in.irradiance * std::max(0.0f, glm::dot(n, in.wi));
            } else {
                return unshadowed_irradiance(e, p, n);
            }
        },
        light.emitter);
}

float luminous_flux_lm(const Light& light) {
    struct Flux {
        float operator()(const DirectionalLight&) const { return 0.0f; }
        float operator()(const PointLight& l) const { return 4.0f * kPi * luminance(l.intensity); }
        float operator()(const SpotLight& l) const {
            return spot_flux_per_cd(l) * luminance(l.intensity);
        }
        float operator()(const GoniometricLight& l) const { return goniometric_flux_lm(l); }
        float operator()(const LineLight& l) const { return line_flux_lm(l); }
        float operator()(const PolygonLight& l) const { return polygon_flux_lm(l); }
        float operator()(const SphereLight& l) const { return sphere_flux_lm(l); }
    };
    return std::visit(Flux{}, light.emitter);
}

std::string light_type_name(const Light& light) {
    static const char* const kNames[] = {"directional", "point",   "spot",  "goniometric",
                                         "line",        "polygon", "sphere"};
    return kNames[light.emitter.index()];
}

}  // namespace kasumi

namespace kasumi {

int shadow_map_resolution(const Light& light) {
    if (light.shadow_map.resolution > 0)
        return light.shadow_map.resolution;
    return is_delta(light) ? 1024 : 512;
}

}  // namespace kasumi
