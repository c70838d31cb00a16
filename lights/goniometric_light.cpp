#include "lights/goniometric_light.h"

#include "lights/point_source.h"

namespace kasumi {

IncidentLight incident(const GoniometricLight& light, const Vec3& p) {
    IncidentLight in = point_source_incident(light.position, p);
    if (in.distance > 0.0f && light.profile) {
        // The frame is orthonormal: its transpose takes world directions to the luminaire's.
        const Vec3 emitted_local = glm::transpose(light.local_to_world) * (-in.wi);
        const float candela = ies_candela(*light.profile, emitted_local);
        in.irradiance = light.scale * (candela / (in.distance * in.distance));
    }
    return in;
}

float goniometric_flux_lm(const GoniometricLight& light) {
    return light.profile ? static_cast<float>(ies_flux_lm(*light.profile)) * luminance(light.scale)
                         : 0.0f;
}

Mat3 luminaire_frame(const Vec3& rotation_deg) {
    const auto rotation = [](int axis, float deg) {
        const float c = std::cos(radians(deg)), s = std::sin(radians(deg));
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        Mat3 r(1.0f);  // column-major: r[col][row]
        r[a][a] = c;
        r[b][b] = c;
        r[a][b] = s;
        r[b][a] = -s;
        return r;
    };
    const Mat3 hanging(Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(0, 1, 0));
    return rotation(2, rotation_deg.z) * rotation(1, rotation_deg.y) * rotation(0, rotation_deg.x) *
           hanging;
}

}  // namespace kasumi
