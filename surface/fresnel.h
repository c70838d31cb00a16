#pragma once
/// Fresnel reflectance of a smooth dielectric interface and the ideal reflection and refraction
/// directions. Direction convention (pbrt-v4, yocto-gl): every direction points away from the
/// surface point, so the incident direction wi and the normal n on its side have dot(n, wi) > 0,
/// and the reflected direction is 2 dot(n, wi) n - wi.
#include "core/math.h"

#include <optional>

namespace kasumi {

/// Fresnel amplitude reflection coefficients for s (perpendicular) and p (parallel)
/// polarisation (Born & Wolf, Principles of Optics, §1.5.2, eqs. 21a-b):
///   rs = (cos θi - η cos θt) / (cos θi + η cos θt),  rp = (η cos θi - cos θt) / (η cos θi + cos
///   θt).
/// Total internal reflection gives |rs| = |rp| = 1 (reported as rs = rp = 1).
struct FresnelAmplitudes {
    float rs = 0.0f;
    float rp = 0.0f;
};

/// Amplitude coefficients at a dielectric interface. `cos_theta_i` in [0, 1] is the cosine of
/// the angle of incidence on the incident side; `eta` > 0 is η_transmitted / η_incident.
FresnelAmplitudes fresnel_amplitudes(float cos_theta_i, float eta);

/// Exact unpolarised Fresnel reflectance F = (rs² + rp²) / 2 (Born & Wolf §1.5.3; pbrt-v4
/// §9.3.6, FrDielectric), 1 beyond the critical angle (total internal reflection).
/// `cos_theta_i` in [-1, 1] is dot(n, wi) with n the normal on the side of the medium the
/// relative index `eta` = η_inside / η_outside is measured from: a negative cosine means wi is
/// inside, and the interface is then seen with 1 / eta. The transmitted fraction of power is
/// 1 - F (energy conservation; tested against the transmission coefficients).
float fresnel_dielectric(float cos_theta_i, float eta);

/// Schlick's approximation F0 + (1 - F0)(1 - cos θ)^5 (Schlick 1994, eq. 24); cos_theta in [0, 1].
float fresnel_schlick(float cos_theta, float f0);

/// Mirror direction of wi about the unit normal n: 2 dot(n, wi) n - wi (law of reflection: same
/// angle to n, coplanar with n and wi). Either orientation of n gives the same result.
Vec3 reflect(const Vec3& wi, const Vec3& n);

/// Refracted direction (Snell's law, sin θt = sin θi / eta) of the unit direction wi through an
/// interface with unit normal n on wi's side (dot(n, wi) >= 0); `eta` = η_transmitted /
/// η_incident > 0. The result is unit length and points into the other side (dot(n, wt) < 0);
/// empty under total internal reflection. pbrt-v4 §9.3.2, Refract.
std::optional<Vec3> refract(const Vec3& wi, const Vec3& n, float eta);

}  // namespace kasumi
