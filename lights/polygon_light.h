#pragma once
/// Polygon light: a planar convex polygon of uniform luminance.
#include "core/color.h"
#include "lights/incident_light.h"

#include <string>
#include <vector>

namespace kasumi {

inline constexpr size_t kMaxPolygonVertices = 64;

/// A convex planar polygon that emits luminance L from its front: the side toward which its
/// vertices wind counter-clockwise (the right-hand rule: `normal` = normalised Σ v_i × v_{i+1}),
/// or from both sides when two_sided. Build with make_polygon_light.
struct PolygonLight {
    std::vector<Vec3> vertices;
    Vec3 normal{0.0f, 0.0f, 1.0f};  ///< unit front normal
    float area = 0.0f;              ///< m²
    /// Cumulative area fractions of the fan triangles (v0, v_i, v_{i+1}), i = 1..n−2; last = 1.
    std::vector<float> fan_cdf;
    Rgb luminance{0.0f};  ///< cd/m², uniform and Lambertian
    bool two_sided = false;
};

/// Why `vertices` cannot be a polygon light (fewer than 3 or more than kMaxPolygonVertices, zero
/// area, not planar to 1e-4 of its size, not convex, repeated vertices), or "" when they can.
std::string polygon_problem(const std::vector<Vec3>& vertices);

/// Precomputes normal, area and the fan CDF; `vertices` must pass polygon_problem.
PolygonLight make_polygon_light(std::vector<Vec3> vertices, const Rgb& luminance, bool two_sided);

/// Unoccluded illuminance (lux) at p on a surface of unit normal n by Lambert's boundary formula
/// (Lambert 1760; Baum, Rushmeier & Winget 1989, eq. 3): with the polygon first clipped to the
/// receiver's upper half-space n·(x − p) ≥ 0 and r_i = v_i − p ordered counter-clockwise as seen
/// from p (the emitting side facing p),
///     E = L/2 Σ_i Θ_i n·(r_{i+1} × r_i)/|r_{i+1} × r_i|,   Θ_i = angle(r_i, r_{i+1}).
/// Zero behind a one-sided light and in the polygon's plane.
Rgb unshadowed_irradiance(const PolygonLight& light, const Vec3& p, const Vec3& n);

/// One point uniform in area on the polygon (pdf 1/A per m²), returned with the normal-incidence
/// irradiance L |cos θ_light| A / r² (zero from behind a one-sided light).
IncidentLight sample_incident(const PolygonLight& light, const Vec3& p, Vec2 u);

/// Luminous flux, lm: π L A per emitting side.
float polygon_flux_lm(const PolygonLight& light);

}  // namespace kasumi
