#pragma once
/// Vector aliases and constants shared by every module. Units are metres; directions are unit
/// vectors in world space unless a name says otherwise (`_local`, `_index`).
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace kasumi {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using DVec3 = glm::dvec3;
using Mat3 = glm::mat3;
using Mat4 = glm::mat4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kTwoPi = 2.0f * kPi;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInv2Pi = 1.0f / (2.0f * kPi);
inline constexpr float kInv4Pi = 1.0f / (4.0f * kPi);
inline constexpr double kPiD = 3.14159265358979323846;
inline constexpr float kInfinity = 1e30f;

inline float radians(float degrees) {
    return degrees * (kPi / 180.0f);
}
inline float degrees(float radians) {
    return radians * (180.0f / kPi);
}

/// sqrt that returns 0 for the tiny negative arguments rounding produces.
inline float safe_sqrt(float x) {
    return std::sqrt(std::max(0.0f, x));
}
inline double safe_sqrt(double x) {
    return std::sqrt(std::max(0.0, x));
}

/// acos for arguments rounding may push just outside [-1, 1].
inline float safe_acos(float x) {
    return std::acos(std::clamp(x, -1.0f, 1.0f));
}

inline bool is_finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// A ray: points origin + t * direction for t in [t_min, t_max]; direction is unit length.
struct Ray {
    Vec3 origin{0.0f};
    Vec3 direction{0.0f, 0.0f, 1.0f};
    float t_min = 0.0f;
    float t_max = kInfinity;

    Vec3 at(float t) const { return origin + t * direction; }
};

/// An orthonormal frame around a unit normal (Duff et al. 2017, "Building an Orthonormal Basis,
/// Revisited", JCGT 6(1)): branch-free and continuous except at n.z = -0.
struct Frame {
    Vec3 tangent;
    Vec3 bitangent;
    Vec3 normal;

    explicit Frame(const Vec3& n) : normal(n) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        tangent = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        bitangent = Vec3(b, sign + n.y * n.y * a, -n.y);
    }
    Vec3 to_local(const Vec3& v) const {
        return Vec3(glm::dot(v, tangent), glm::dot(v, bitangent), glm::dot(v, normal));
    }
    Vec3 to_world(const Vec3& v) const { return v.x * tangent + v.y * bitangent + v.z * normal; }
};

}  // namespace kasumi
