#include "lights/sphere_light.h"

#include "core/sampling.h"

namespace kasumi {

Rgb unshadowed_irradiance(const SphereLight& light, const Vec3& p, const Vec3& n) {
    const DVec3 to_center = DVec3(light.center) - DVec3(p);
    const double d = glm::length(to_center);
    const double radius = light.radius;
    if (!(d > radius))
        return Rgb(0.0f);
    const double sin2_sigma = (radius / d) * (radius / d);
    const double cos_theta = std::clamp(glm::dot(DVec3(n), to_center) / d, -1.0, 1.0);
    double e;
    if (cos_theta * cos_theta >= sin2_sigma) {
        e = cos_theta > 0.0 ? kPiD * sin2_sigma * cos_theta : 0.0;
    } else {
        const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
        const double x = std::sqrt(1.0 / sin2_sigma - 1.0);  // cot σ
        const double y = std::clamp(-x * cos_theta / sin_theta, -1.0, 1.0);
        const double s = sin_theta * std::sqrt(1.0 - y * y);
        e = (cos_theta * std::acos(y) - x * s) * sin2_sigma + std::atan(s / x);
    }
    return light.luminance * static_cast<float>(std::max(e, 0.0));
}

IncidentLight sample_incident(const SphereLight& light, const Vec3& p, Vec2 u) {
    IncidentLight in;
    const Vec3 to_center = light.center - p;
    const float d = glm::length(to_center);
    if (!(d > light.radius))
        return in;
    const float sin2_sigma = (light.radius / d) * (light.radius / d);
    const float cos_sigma = safe_sqrt(1.0f - sin2_sigma);
    // 1 − cos σ without cancellation for small, distant spheres.
    const float one_minus_cos = sin2_sigma / (1.0f + cos_sigma);
    const float cos_theta = 1.0f - u.x * one_minus_cos;
    const Vec3 axis = to_center / d;
    in.wi = direction_about(axis, cos_theta, kTwoPi * u.y);
    // Nearest intersection of p + t wi with the sphere: t = d cos θ − √(R² − d² sin² θ).
    const float sin2_theta = std::max(0.0f, (1.0f - cos_theta) * (1.0f + cos_theta));
    in.distance = d * cos_theta - safe_sqrt(light.radius * light.radius - d * d * sin2_theta);
    in.light_position = p + in.distance * in.wi;
    in.irradiance = light.luminance * (kTwoPi * one_minus_cos);
    return in;
}

float sphere_flux_lm(const SphereLight& light) {
    return 4.0f * kPi * kPi * light.radius * light.radius * luminance(light.luminance);
}

}  // namespace kasumi
