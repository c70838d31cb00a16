#pragma once
/// Goniometric light: a point source whose intensity follows a measured IES distribution.
#include "core/color.h"
#include "lights/ies_profile.h"
#include "lights/incident_light.h"

#include <memory>

namespace kasumi {

/// The luminaire frame maps to the world by `local_to_world`: its columns are the world images
/// of the luminaire's +x (C = 0°), +y (C = 90°) and +z (up; the nadir γ = 0° is −z). The scene
/// default is +x → +x, +y → −z, +z → +y (hanging, nadir toward −y), then `rotation_deg`.
struct GoniometricLight {
    Vec3 position{0.0f};
    Mat3 local_to_world{1.0f};
    std::shared_ptr<const IesProfile> profile;
    /// Colour (unit luminance) times the flux rescale: candela = scale × table value.
    Rgb scale{1.0f};
};

/// The table's intensity toward p over r²; zero closer than 1e-6 m.
IncidentLight incident(const GoniometricLight& light, const Vec3& p);

/// Luminous flux, lm: the table's interpolated flux times the scale's luminance.
float goniometric_flux_lm(const GoniometricLight& light);

/// The default luminaire frame rotated by Euler angles in degrees about the world x, then y,
/// then z axes (R = Rz Ry Rx).
Mat3 luminaire_frame(const Vec3& rotation_deg);

}  // namespace kasumi
