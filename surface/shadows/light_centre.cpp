#include "surface/shadows/light_centre.h"

namespace kasumi {

LightCentre light_centre(const Light& light) {
    const IncidentLight in = incident_light(light, Vec3(0.0f));
    LightCentre c;
    if (in.distance >= kInfinity) {
        c.at_infinity = true;
        c.direction = in.wi;
    } else {
        c.position = in.light_position;
    }
    return c;
}

LightCentre point_centre(const Vec3& position) {
    LightCentre c;
    c.position = position;
    return c;
}

LightCentre parallel_centre(const Vec3& direction_to_light) {
    LightCentre c;
    c.at_infinity = true;
    c.direction = glm::normalize(direction_to_light);
    return c;
}

Vec3 toward_light(const LightCentre& light, const Vec3& p) {
    return light.at_infinity ? light.direction : glm::normalize(light.position - p);
}

double light_height(const LightCentre& light, const DVec3& on_plane, const DVec3& normal) {
    return light.at_infinity ? glm::dot(normal, DVec3(light.direction))
                             : glm::dot(normal, DVec3(light.position) - on_plane);
}

}  // namespace kasumi
