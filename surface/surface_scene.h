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

namespace kasumi {

/// A ray-surface intersection. Normals are unit length and point out of the shape (for quads:
/// toward the front side); the integrator flips them toward the viewer as needed.
struct SurfaceHit {
    float t = 0.0f;
    Vec3 position{0.0f};
    Vec3 geometric_normal{0.0f, 0.0f, 1.0f};
    Vec3 shading_normal{0.0f, 0.0f, 1.0f};
    uint32_t shape = 0;
    uint32_t material = 0;
};

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
    /// True if anything is hit with t in (ray.t_min, ray.t_max).
    bool occluded(const Ray& ray) const;

    Bounds3 bounds() const;
    SurfaceStats stats() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// Origin for a ray leaving a surface point p with geometric normal n toward `direction`:
/// offset along n to the side `direction` leaves from, by an amount that scales with |p| so
/// float rounding of the hit point cannot cause self-intersection (acne) at any scene scale,
/// yet small enough (~1e-4 relative) that contact shadows do not detach (peter-panning).
Vec3 offset_ray_origin(const Vec3& p, const Vec3& n, const Vec3& direction);

}  // namespace kasumi
