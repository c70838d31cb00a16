#include "lights/ray_sphere.h"

#include <cmath>
#include <utility>

namespace kasumi {

std::optional<double> intersect_sphere(const DVec3& center, double radius, const DVec3& origin,
                                       const DVec3& direction, double t_near, double t_far) {
    const double a = glm::dot(direction, direction);
    const DVec3 f = origin - center;
    const double b = -glm::dot(f, direction);
    const DVec3 perpendicular = f + (b / a) * direction;
    const double discriminant = a * (radius * radius - glm::dot(perpendicular, perpendicular));
    if (!(discriminant >= 0.0))
        return std::nullopt;
    const double length = std::sqrt(glm::dot(f, f));
    const double c = (length - radius) * (length + radius);
    const double q = b + std::copysign(std::sqrt(discriminant), b);
    double t0 = c / q;
    double t1 = q / a;
    if (q == 0.0)  // b = 0 and Δ = 0: the ray grazes the sphere at its origin, t = 0
        t0 = t1;
    if (t0 > t1)
        std::swap(t0, t1);
    if (t0 >= t_near && t0 <= t_far)
        return t0;
    if (t1 >= t_near && t1 <= t_far)
        return t1;
    return std::nullopt;
}

}  // namespace kasumi
