#include "surface/surface_scene.h"

namespace kasumi {

namespace {

Vec3 offset_along_normal(const Vec3& p, const Vec3& n, const Vec3& direction, float scale) {
    const float offset = kRayOffsetRelative * (kRayOffsetFloor + scale);
    return glm::dot(n, direction) >= 0.0f ? p + offset * n : p - offset * n;
}

}  // namespace

Vec3 offset_ray_origin(const Vec3& p, const Vec3& n, const Vec3& direction) {
    return offset_along_normal(p, n, direction, max_abs_coordinate(p));
}

Vec3 offset_ray_origin(const SurfaceHit& hit, const Vec3& direction) {
    return offset_along_normal(hit.position, hit.geometric_normal, direction,
                               std::max(max_abs_coordinate(hit.position), hit.error_scale));
}

}  // namespace kasumi
