#pragma once
/// Warps from the unit square to common domains. Every pdf names its measure.
#include "core/math.h"

namespace kasumi {

/// Uniform direction on the unit sphere; pdf 1/(4π) per steradian.
inline Vec3 sample_uniform_sphere(Vec2 u) {
    const float z = 1.0f - 2.0f * u.x;
    const float r = safe_sqrt(1.0f - z * z);
    const float phi = kTwoPi * u.y;
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline constexpr float kUniformSpherePdf = kInv4Pi;

/// Cosine-weighted direction about +z; pdf cos(θ)/π per steradian.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
    const float r = std::sqrt(u.x);
    const float phi = kTwoPi * u.y;
    return Vec3(r * std::cos(phi), r * std::sin(phi), safe_sqrt(1.0f - u.x));
}

/// A unit vector with the given cosine to `axis` and azimuth phi about it.
inline Vec3 direction_about(const Vec3& axis, float cos_theta, float phi) {
    const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
    const Frame frame(axis);
    return frame.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
}

}  // namespace kasumi
