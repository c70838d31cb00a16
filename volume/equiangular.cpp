#include "volume/equiangular.h"

namespace kasumi {

EquiangularSegment make_equiangular(const Vec3& o, const Vec3& dir, const Vec3& c, float t_a,
                                    float t_b) {
    EquiangularSegment s;
    s.delta = glm::dot(c - o, dir);
    const Vec3 closest = o + s.delta * dir;
    // 1e-6 relative to the scale keeps d > 0 without changing any resolvable geometry.
    s.d = std::max(glm::length(closest - c), 1e-6f * (1.0f + std::abs(s.delta)));
    s.theta_a = std::atan((t_a - s.delta) / s.d);
    s.theta_b = std::atan((t_b - s.delta) / s.d);
    return s;
}

float EquiangularSegment::sample(float u) const {
    const float theta = theta_a + u * (theta_b - theta_a);
    return delta + d * std::tan(theta);
}

float EquiangularSegment::pdf(float t) const {
    const float x = t - delta;
    return d / ((theta_b - theta_a) * (d * d + x * x));
}

}  // namespace kasumi
