#pragma once
/// Axis-aligned boxes in world space (metres).
#include "core/math.h"

#include <optional>
#include <utility>

namespace kasumi {

struct Bounds3 {
    Vec3 min{kInfinity};
    Vec3 max{-kInfinity};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void extend(const Vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const Bounds3& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    bool contains(const Vec3& p) const {
        return p.x >= min.x && p.y >= min.y && p.z >= min.z && p.x <= max.x && p.y <= max.y &&
               p.z <= max.z;
    }
    Vec3 extent() const { return max - min; }

    /// The parametric interval where the ray is inside the box, clipped to [t_min, t_max];
    /// empty when it misses. Slab method; IEEE infinities handle axis-parallel rays.
    std::optional<std::pair<float, float>> clip(const Ray& ray) const {
        float t0 = ray.t_min, t1 = ray.t_max;
        for (int axis = 0; axis < 3; ++axis) {
            const float inv = 1.0f / ray.direction[axis];
            float near = (min[axis] - ray.origin[axis]) * inv;
            float far = (max[axis] - ray.origin[axis]) * inv;
            if (near > far)
                std::swap(near, far);
            // NaN (0 * inf on a slab face) compares false and leaves t0/t1 unchanged.
            if (near > t0)
                t0 = near;
            if (far < t1)
                t1 = far;
            if (t0 > t1)
                return std::nullopt;
        }
        return std::make_pair(t0, t1);
    }
};

}  // namespace kasumi
