#pragma once
/// Line light: a segment that emits like a thin diffuse tube.
#include "core/color.h"
#include "lights/incident_light.h"

namespace kasumi {

/// A segment from `from` to `to` whose element dl has intensity I_l sin α dl toward a direction
/// at angle α to the segment (Lambertian in angle: the projected width of a thin diffuse
/// cylinder), I_l = `intensity_per_m` perpendicular to the line. Flux π² I_l per metre.
struct LineLight {
    Vec3 from{0.0f};
    Vec3 to{0.0f};
    Rgb intensity_per_m{0.0f};  ///< cd/m perpendicular to the line
};

/// Unoccluded illuminance (lux) at p on a surface of unit normal n, in closed form:
/// E = I_l h ∫ n·(x(s) − p) / r(s)⁴ ds over the part of the segment above the tangent plane,
/// with h the distance from p to the line and r² = s² + h² (derivation in docs/lights.md).
/// Zero closer than 1e-7 m to the line.
Rgb unshadowed_irradiance(const LineLight& light, const Vec3& p, const Vec3& n);

/// One point on the segment, chosen uniformly in the angle it subtends at p (pdf h / (r² Δφ)
/// per metre), or uniformly in length (pdf 1/L per metre) when p is on the line's axis. The
/// returned irradiance is I_l sin α / r² / pdf.
IncidentLight sample_incident(const LineLight& light, const Vec3& p, Vec2 u);

/// Luminous flux, lm: π² I_l L.
float line_flux_lm(const LineLight& light);

}  // namespace kasumi
