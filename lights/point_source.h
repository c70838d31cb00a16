#pragma once
/// Geometry shared by every light that emits from one point (point, spot, goniometric).
#include "lights/incident_light.h"

namespace kasumi {

/// wi, distance and light_position from p toward a source at `position`, irradiance zero.
/// A point closer than 1e-6 m gets distance 0 (callers then leave the irradiance zero rather
/// than unbounded).
inline IncidentLight point_source_incident(const Vec3& position, const Vec3& p) {
    IncidentLight in;
    const Vec3 to_light = position - p;
    const float r2 = glm::dot(to_light, to_light);
    in.light_position = position;
    if (!(r2 > 1e-12f)) {
        in.distance = 0.0f;
        return in;
    }
    in.distance = std::sqrt(r2);
    in.wi = to_light / in.distance;
    return in;
}

}  // namespace kasumi
