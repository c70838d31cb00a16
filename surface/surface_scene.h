#pragma once
/// The scene's surfaces on Embree 3: closest hit and occlusion queries. Built only when the
/// scene has shapes. Thread-safe for concurrent queries after construction.
#include "core/bounds.h"
#include "surface/shape.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

struct RTCRayHit;  // Embree's (global namespace); its headers stay in surface_scene.cpp

namespace kasumi {

/// A ray-surface intersection. Normals are unit length and point out of the shape (boxes and
/// spheres: outward; quads and meshes: toward the side their vertices wind counter-clockwise
/// toward, normalize(cross(v1 - v0, v2 - v0))); the integrator flips them toward the viewer.
/// A mesh with vertex normals is the exception: its authored normals define the outside
/// (pbrt-v4's convention), and the geometric normal is flipped to their side.
struct SurfaceHit {
    float t = 0.0f;       ///< metres along the (unit) ray direction
    Vec3 position{0.0f};  ///< world space; projected onto the hit sphere or triangle plane
    Vec3 geometric_normal{0.0f, 0.0f, 1.0f};
    Vec3 shading_normal{0.0f, 0.0f, 1.0f};  ///< interpolated vertex normal, else geometric
    uint32_t shape = 0;                     ///< index into the shapes the scene was built from
    uint32_t material = 0;                  ///< the shape's material index
    uint32_t primitive = 0;                 ///< triangle index within the shape (spheres: 0)
    /// Embree's barycentrics of the hit in its triangle: p = (1 - u - v) p0 + u p1 + v p2
    /// (spheres: 0, 0).
    float u = 0.0f;
    float v = 0.0f;
    Shading shading = Shading::Phong;  ///< the shape's shading mode
    /// Metres: the largest coordinate magnitude that entered the hit computation in float (the
    /// hit triangle's vertices; spheres are intersected in double and contribute ~0). The hit's
    /// rounding error scales with it, so offset_ray_origin(hit, direction) uses it.
    float error_scale = 0.0f;
};

/// The hit triangle's vertices (world space) and the unit normals its shading uses at them: the
/// mesh's vertex normals (authored, or angle-weighted when the file has none), the face normal
/// for quads and boxes. Vertex i has barycentrics (u, v) = (0, 0), (1, 0), (0, 1).
struct HitTriangle {
    std::array<Vec3, 3> positions;
    std::array<Vec3, 3> normals;
};

class SphereLightOccluders;

struct SurfaceStats {
    uint64_t closest_rays = 0;
    uint64_t shadow_rays = 0;
    uint64_t primitives = 0;
};

class SurfaceScene {
  public:
    explicit SurfaceScene(const std::vector<Shape>& shapes);
    ~SurfaceScene();
    SurfaceScene(const SurfaceScene&) = delete;
    SurfaceScene& operator=(const SurfaceScene&) = delete;

    /// Closest hit with t in (ray.t_min, ray.t_max).
    std::optional<SurfaceHit> intersect(const Ray& ray) const;
    /// intersect() of `count` rays into hits[0 .. count): for coherent rays (camera rays of
    /// neighbouring pixels), traced together through the BVH.
    void intersect_coherent(const Ray* rays, size_t count, std::optional<SurfaceHit>* hits) const;
    /// True if anything is hit with t in (ray.t_min, ray.t_max).
    bool occluded(const Ray& ray) const;
    /// The hit of `ray` on triangle `primitive` of shape `shape` (not a sphere) at t metres with
    /// barycentrics (u, v), found by other means than Embree (render.surface "scanline",
    /// surface/scanline/scanline_surface.h): built exactly as intersect() builds Embree's hits.
    SurfaceHit hit_on_triangle(const Ray& ray, uint32_t shape, uint32_t primitive, float t, float u,
                               float v) const;
    /// The triangle `hit` lies on; empty for spheres.
    std::optional<HitTriangle> triangle(const SurfaceHit& hit) const;

    Bounds3 bounds() const;
    SurfaceStats stats() const;
    /// The shapes as analytic occluders of sphere lights (`exact_penumbra`).
    const SphereLightOccluders& sphere_light_occluders() const;

  private:
    struct Impl;
    /// The SurfaceHit of Embree's answer for `ray` (none if it hit nothing).
    std::optional<SurfaceHit> hit_from(const Ray& ray, const RTCRayHit& rayhit) const;
    /// A triangle's hit (hit_from's and hit_on_triangle's); `fallback_normal`: the normal of a
    /// degenerate triangle.
    SurfaceHit triangle_hit(const Ray& ray, uint32_t shape, uint32_t primitive, float t, float u,
                            float v, const DVec3& fallback_normal) const;
    std::unique_ptr<Impl> m_impl;
};

/// max(|v.x|, |v.y|, |v.z|): the scale that sets a point's float rounding error.
inline float max_abs_coordinate(const Vec3& v) {
    return std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
}

/// Relative size of the ray-origin offset: 2^-18 ≈ 3.8e-6, i.e. 64 float ulps (2^-24) of the
/// scale. An Embree triangle hit is off its plane by a few ulps of the largest coordinate
/// involved (vertices and ray origin); measured: self-hits vanish from 4 ulps on
/// (tests/surface/ray_offset_test.cpp), so 64 leaves a 16x margin, while staying ~25x below
/// 1e-4 so shadow edges move by only offset / tan(elevation) (no peter-panning).
inline constexpr float kRayOffsetRelative = 0x1p-18f;
/// Metres: the smallest scale the offset assumes, so points near the origin (tiny coordinates)
/// still clear primitives of metre size: the offset is never below 3.8 µm.
inline constexpr float kRayOffsetFloor = 1.0f;

/// Origin for a ray leaving a surface point p with unit geometric normal n toward `direction`:
/// p moved along n to the side `direction` leaves from (+n if dot(n, direction) >= 0) by
///   kRayOffsetRelative * (kRayOffsetFloor + max(|p.x|, |p.y|, |p.z|))   [metres].
/// Knowing only p, it cannot see a large primitive's vertices: it is safe for primitives up to
/// ~20 m across (or any size if axis-aligned); prefer the SurfaceHit overload, which is not
/// limited so.
Vec3 offset_ray_origin(const Vec3& p, const Vec3& n, const Vec3& direction);

/// As above along hit.geometric_normal, with the scale max(|p|, hit.error_scale) covering the
/// hit primitive: no self-intersection for primitives of any size (a tilted 20 km ground quad
/// hit near the origin included).
Vec3 offset_ray_origin(const SurfaceHit& hit, const Vec3& direction);

}  // namespace kasumi
