#include "surface/fresnel.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

/// cos θt from Snell's law, or a negative value under total internal reflection. Works in
/// double: 1 - sin²θt loses digits near the critical angle in float.
double cos_transmitted(double cos_theta_i, double eta) {
    const double sin2_i = std::max(0.0, 1.0 - cos_theta_i * cos_theta_i);
    const double sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1.0)
        return -1.0;
    return std::sqrt(1.0 - sin2_t);
}

}  // namespace

FresnelAmplitudes fresnel_amplitudes(float cos_theta_i, float eta) {
    const double cos_i = std::clamp(static_cast<double>(cos_theta_i), 0.0, 1.0);
    const double e = eta;
    const double cos_t = cos_transmitted(cos_i, e);
    if (cos_t < 0.0)
        return {1.0f, 1.0f};
    const double rs = (cos_i - e * cos_t) / (cos_i + e * cos_t);
    const double rp = (e * cos_i - cos_t) / (e * cos_i + cos_t);
    return {static_cast<float>(rs), static_cast<float>(rp)};
}

float fresnel_dielectric(float cos_theta_i, float eta) {
    // Rounding can push a dot product of unit vectors just past ±1.
    double cos_i = std::clamp(static_cast<double>(cos_theta_i), -1.0, 1.0);
    double e = eta;
    if (cos_i < 0.0) {
        cos_i = -cos_i;
        e = 1.0 / e;
    }
    const double cos_t = cos_transmitted(cos_i, e);
    if (cos_t < 0.0)
        return 1.0f;
    const double rs = (cos_i - e * cos_t) / (cos_i + e * cos_t);
    const double rp = (e * cos_i - cos_t) / (e * cos_i + cos_t);
    return static_cast<float>(0.5 * (rs * rs + rp * rp));
}

float fresnel_schlick(float cos_theta, float f0) {
    const float m = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
    const float m2 = m * m;
    return f0 + (1.0f - f0) * (m2 * m2 * m);
}

Vec3 reflect(const Vec3& wi, const Vec3& n) {
    return 2.0f * glm::dot(n, wi) * n - wi;
}

std::optional<Vec3> refract(const Vec3& wi, const Vec3& n, float eta) {
    const float cos_i = std::clamp(glm::dot(n, wi), 0.0f, 1.0f);
    const double cos_t = cos_transmitted(cos_i, eta);
    if (cos_t < 0.0)
        return std::nullopt;
    // wt = -wi / η + (cos θi / η - cos θt) n: the tangential part of -wi shrinks by 1/η
    // (Snell), the normal part makes the result unit length.
    const Vec3 wt = -wi / eta + (cos_i / eta - static_cast<float>(cos_t)) * n;
    return glm::normalize(wt);
}

}  // namespace kasumi
