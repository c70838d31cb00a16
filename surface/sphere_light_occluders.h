#pragma once
/// Exact penumbrae of sphere lights (`exact_penumbra`, docs/lights.md "Exact penumbrae"): the
/// projected solid angle of the part of a sphere light a point sees past the scene's spheres,
/// boxes and quads, in closed form, or nothing when the configuration is outside what the
/// closed form covers (the caller then samples the light as usual).
#include "lights/cap_region.h"
#include "lights/polygon_light.h"
#include "lights/sphere_light.h"
#include "surface/shape.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace kasumi {

class SphereLightOccluders {
  public:
    /// At most this many occluders may overlap a point's cone of the light (inclusion-exclusion
    /// over their 2^k − 1 intersections); more, and the point falls back to sampling.
    static constexpr int kMaxOccluders = 4;

    explicit SphereLightOccluders(const std::vector<Shape>& shapes);

    /// ∫ max(0, n · ω) dω over the directions of the light's cone at p that reach the light
    /// (sr): the unshadowed value (π sin²σ (n · axis) when the cone is above the plane of n,
    /// else the cone clipped to the hemisphere above n) less the measure of the union of the
    /// occluders' solid angles inside it, each occluder a sphere (a cap), an axis-aligned box
    /// or a quad (convex spherical polygons, bounded by the great circles through p and their
    /// silhouette edges), the union by inclusion-exclusion; every region is an intersection of
    /// caps (lights/cap_region.h). E = L × this. `receiver` is the shape p lies on: skipped
    /// when it is a sphere, box or quad (a convex surface hides nothing above its tangent
    /// plane; the caller clips at the geometric horizon by passing the geometric normal, or a
    /// shading normal equal to it). Returns nothing, so the caller samples, when:
    /// - a mesh's bounding sphere meets the cone (meshes are not silhouetted),
    /// - an occluder that covers part of the cone straddles the light's distance (parts of it
    ///   nearer than the nearest point of the light, d − R, and parts farther); occluders
    ///   wholly beyond √(d² − R²), the farthest visible point of the light, are ignored,
    /// - p is inside (or on) an occluder, or on the line of a box or quad edge,
    /// - more than kMaxOccluders occluders cover part of the cone.
    /// Zero when p is inside the light or the cone is wholly below the plane of n.
    std::optional<double> visible_projected_solid_angle(const SphereLight& light, const Vec3& p,
                                                        const Vec3& n, uint32_t receiver) const;

    /// The same for a convex polygon light (its solid angle from p is the intersection of the
    /// hemispheres through p and its edges): ∫ max(0, n · ω) dω over the directions toward the
    /// polygon that reach it; 0 behind a one-sided light. An occluder wholly on p's side of it
    /// hides what it covers, one wholly on the far side nothing, one across it sends the point to
    /// the samples. Same fallbacks.
    std::optional<double> visible_projected_solid_angle(const PolygonLight& light, const Vec3& p,
                                                        const Vec3& n, uint32_t receiver) const;

  private:
    /// base: the light's region (with the hemisphere above n when clipped), its measure
    /// `unshadowed`; (axis, σ) a cone around it for culling; every direction of the region
    /// meets the light between `nearest` and `farthest` (sphere lights), or, given `plane` (unit
    /// m, m · x − plane_offset > 0 on p's side), the light lies in that plane (polygon lights).
    std::optional<double> visible_part(const SphericalCap* base, size_t base_count,
                                       double unshadowed, const DVec3& p, const DVec3& n,
                                       const DVec3& axis, double cos_sigma, double sin_sigma,
                                       double nearest, double farthest, const DVec3* plane,
                                       double plane_offset, uint32_t receiver) const;

    enum class Kind : uint8_t { Sphere, Box, Quad, Mesh };
    struct Occluder {
        Kind kind = Kind::Mesh;
        DVec3 center{0.0};  ///< of the bounding sphere (the sphere itself for spheres)
        double radius = 0.0;
        DVec3 lo{0.0}, hi{0.0};       ///< boxes
        std::array<DVec3, 4> quad{};  ///< quads, as given
    };
    std::vector<Occluder> m_occluders;
};

}  // namespace kasumi
