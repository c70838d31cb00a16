#pragma once
/// Spot light: a point source whose intensity falls smoothly to zero at the edge of a cone.
#include "lights/incident_light.h"

namespace kasumi {

/// I(θ) = I0 s(cos θ) with θ the angle from the axis and s = smoothstep(cos_cone, cos_falloff,
/// cos θ) (the cubic 3t² − 2t³, as pbrt-v4's SpotLight): full intensity inside the falloff
/// angle, zero outside the cone, C¹-smooth in cos θ between. cos_falloff == cos_cone is a
/// hard edge.
struct SpotLight {
    Vec3 position{0.0f};
    Vec3 direction{0.0f, -1.0f, 0.0f};  ///< unit axis, the way the light travels
    Rgb intensity{0.0f};                ///< candela on the axis
    float cos_cone = 0.0f;              ///< cos of the half-angle outside which I = 0
    float cos_falloff = 0.0f;           ///< cos of the half-angle inside which I = I0; >= cos_cone
};

/// s(cos θ) in [0, 1].
float spot_falloff(const SpotLight& light, float cos_theta);

/// Luminous flux per candela on the axis, lm/cd: 2π ∫ s(μ) dμ = 2π [1 − (cos_falloff +
/// cos_cone) / 2] (the smoothstep integrates to half of its band).
float spot_flux_per_cd(const SpotLight& light);

/// Intensity toward p over r², the inverse-square law; zero closer than 1e-6 m.
IncidentLight incident(const SpotLight& light, const Vec3& p);

}  // namespace kasumi
