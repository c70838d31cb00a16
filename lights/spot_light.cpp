#include "lights/spot_light.h"

#include "lights/point_source.h"

namespace kasumi {

float spot_falloff(const SpotLight& light, float cos_theta) {
    if (cos_theta >= light.cos_falloff)
        return 1.0f;
    if (cos_theta <= light.cos_cone)
        return 0.0f;
    const float t = (cos_theta - light.cos_cone) / (light.cos_falloff - light.cos_cone);
    return t * t * (3.0f - 2.0f * t);
}

float spot_flux_per_cd(const SpotLight& light) {
    return kTwoPi * (1.0f - 0.5f * (light.cos_falloff + light.cos_cone));
}

IncidentLight incident(const SpotLight& light, const Vec3& p) {
    IncidentLight in = point_source_incident(light.position, p);
    if (in.distance > 0.0f) {
        const float cos_theta = -glm::dot(in.wi, light.direction);
        in.irradiance =
            light.intensity * (spot_falloff(light, cos_theta) / (in.distance * in.distance));
    }
    return in;
}

}  // namespace kasumi
