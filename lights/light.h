#pragma once
/// Lights, as a closed set of small value types. Units are photometric (see core/color.h for
/// how Rgb carries photometric quantities): directional lights by illuminance in lux on a
/// surface facing the light, point lights by luminous intensity in candela.
#include "core/color.h"
#include "core/math.h"

#include <string>
#include <variant>

namespace kasumi {

/// Light from infinitely far away, travelling along `direction` (unit vector).
struct DirectionalLight {
    Vec3 direction{0.0f, -1.0f, 0.0f};
    Rgb illuminance{0.0f};  ///< lux on a surface facing the light
};

/// An isotropic point source: illuminance I cos θ / r² at distance r (inverse-square law).
struct PointLight {
    Vec3 position{0.0f};
    Rgb intensity{0.0f};  ///< candela
};

struct Light {
    std::string name;
    std::variant<DirectionalLight, PointLight> emitter;
};

/// Light arriving at a point from one light, before occlusion and media.
struct IncidentLight {
    Vec3 wi{0.0f, 1.0f, 0.0f};   ///< unit direction from the point toward the light
    float distance = kInfinity;  ///< to the light; kInfinity for directional lights
    Vec3 light_position{0.0f};   ///< the light's position (point lights only)
    Rgb irradiance{0.0f};        ///< lux on a surface facing the light (normal incidence)
};

/// The light `light` delivers at point p. For a point light closer than 1e-6 m the irradiance
/// is zero rather than unbounded.
IncidentLight incident_light(const Light& light, const Vec3& p);

/// True if the light is a delta light (a single shadow ray decides its visibility).
inline bool is_delta(const Light&) {
    return true;
}

/// Luminous flux in lumens, for lights that have one (point: 4π I); 0 otherwise.
float luminous_flux_lm(const Light& light);

/// The light's type as written in scene files.
std::string light_type_name(const Light& light);

}  // namespace kasumi
