#pragma once
/// Sphere light: a sphere of uniform Lambertian luminance.
#include "core/color.h"
#include "lights/incident_light.h"

namespace kasumi {

struct SphereLight {
    Vec3 center{0.0f};
    float radius = 1.0f;  ///< m, > 0
    Rgb luminance{0.0f};  ///< cd/m², the same seen from every direction
};

/// Unoccluded illuminance (lux) at p on a surface of unit normal n. The sphere subtends a cone
/// of half-angle σ (sin σ = R/d) at angle θ from n. Fully above the horizon (θ ≤ π/2 − σ):
/// E = π L sin²σ cos θ. Straddling it, the exact form factor of a tilted sphere (Snyder 1996,
/// "Area Light Sources for Real-Time Graphics", MSR-TR-96-11; as written in Lagarde & de
/// Rousiers 2014, "Moving Frostbite to Physically Based Rendering", §4.7), with x = cot σ,
/// y = −x cot θ:  E/L = (cos θ acos y − x sin θ √(1−y²)) sin²σ + atan(sin θ √(1−y²) / x).
/// Zero inside the sphere and fully below the horizon.
Rgb unshadowed_irradiance(const SphereLight& light, const Vec3& p, const Vec3& n);

/// A direction uniform in the cone the sphere subtends at p (pdf 1 / (2π (1 − cos σ)) per
/// steradian), with the point where it meets the sphere; irradiance L · 2π (1 − cos σ). Zero
/// inside the sphere. u goes through Shirley & Chiu's concentric disc map, so stratified u
/// gives compact strata in the cone.
IncidentLight sample_incident(const SphereLight& light, const Vec3& p, Vec2 u);

/// The cone a sphere light subtends at a point p outside it, set up once for all of that
/// point's samples: sample(u) is sample_incident(light, p, u), bit for bit (that function is
/// this one), without redoing the distance, the cone's angle and its frame per sample.
class SphereLightCone {
  public:
    SphereLightCone(const SphereLight& light, const Vec3& p);
    /// False when p is inside (or on) the sphere: no light arrives.
    bool valid() const { return m_valid; }
    IncidentLight sample(Vec2 u) const;
    /// The direction along the cone's boundary at azimuth phi (radians, about the cone's axis
    /// in its frame), with the point where it grazes the sphere as the target. Not a sample:
    /// an outline probe (docs/lights.md, "Outline probes").
    IncidentLight outline(float phi) const;
    /// True when the whole cone lies strictly above the plane through p of unit normal n
    /// (angle of the axis to n plus σ below π/2: n · axis > sin σ).
    bool above_plane(const Vec3& n) const;

  private:
    IncidentLight along(Vec2 disc, float rho2) const;

    const SphereLight* m_light;
    Vec3 m_p, m_axis{0.0f, 1.0f, 0.0f};
    float m_d = 0.0f, m_sin2_sigma = 0.0f, m_one_minus_cos = 0.0f;
    Frame m_frame{Vec3(0.0f, 1.0f, 0.0f)};
    bool m_valid = false;
};

/// The density of sample_incident's directions per steradian: 1 / (2π (1 − cos σ)) inside the
/// cone, 0 outside it (and inside the sphere).
float sample_pdf(const SphereLight& light, const Vec3& p, const Vec3& wi);

/// Luminous flux, lm: π L × 4π R².
float sphere_flux_lm(const SphereLight& light);

}  // namespace kasumi
