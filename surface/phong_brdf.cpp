#include "surface/phong_brdf.h"

#include "core/sampling.h"
#include "surface/fresnel.h"

#include <cmath>

namespace kasumi {

namespace {

/// cos α of the lobe, clipped at 0: the lobe is zero beyond 90° from the mirror direction.
float cos_alpha(const Vec3& n, const Vec3& wo, const Vec3& wi) {
    return std::max(0.0f, glm::dot(reflect(wi, n), wo));
}

}  // namespace

Rgb eval(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    const float cos_i = glm::dot(n, wi);
    if (cos_i <= 0.0f || glm::dot(n, wo) <= 0.0f)
        return Rgb(0.0f);
    Rgb f = m.kd * kInvPi;
    if (max_component(m.ks) > 0.0f) {
        f += specular_reflectance(m, cos_i) *
             ((m.n + 2.0f) * kInv2Pi * std::pow(cos_alpha(n, wo, wi), m.n));
    }
    return f;
}

float specular_lobe_probability(const PhongMaterial& m) {
    const float d = luminance(m.kd), s = luminance(m.ks);
    return d + s > 0.0f ? s / (d + s) : 0.0f;
}

float pdf(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    const float cos_i = glm::dot(n, wi);
    if (cos_i <= 0.0f || glm::dot(n, wo) <= 0.0f)
        return 0.0f;
    const float p_s = specular_lobe_probability(m);
    float density = (1.0f - p_s) * cos_i * kInvPi;
    if (p_s > 0.0f)
        density += p_s * (m.n + 1.0f) * kInv2Pi * std::pow(cos_alpha(n, wo, wi), m.n);
    return density;
}

Vec3 sample_specular_lobe(const Vec3& mirror, float exponent, Vec2 u) {
    // The cosine of α has the density (n + 1) cos^n α on [0, 1]: its CDF cos^(n+1) α inverts to
    // u^(1/(n+1)); the azimuth about the mirror direction is uniform.
    const float c = std::pow(u.x, 1.0f / (exponent + 1.0f));
    return direction_about(mirror, c, kTwoPi * u.y);
}

std::optional<PhongSample> sample(const PhongMaterial& m, const Vec3& n, const Vec3& wo,
                                  float u_lobe, Vec2 u) {
    if (!(luminance(m.kd) + luminance(m.ks) > 0.0f) || glm::dot(n, wo) <= 0.0f)
        return std::nullopt;
    const float p_s = specular_lobe_probability(m);
    const Vec3 wi = u_lobe < p_s ? sample_specular_lobe(reflect(wo, n), m.n, u)
                                 : Frame(n).to_world(sample_cosine_hemisphere(u));
    if (glm::dot(n, wi) <= 0.0f)
        return std::nullopt;
    PhongSample s;
    s.wi = glm::normalize(wi);
    s.f = eval(m, n, wo, s.wi);
    s.pdf = pdf(m, n, wo, s.wi);
    if (!(s.pdf > 0.0f))
        return std::nullopt;
    return s;
}

}  // namespace kasumi
