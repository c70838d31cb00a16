#include "gi/gi_phong.h"

#include "core/sampling.h"
#include "surface/fresnel.h"

#include <cmath>

namespace kasumi {

namespace {

float cos_alpha(const Vec3& n, const Vec3& wo, const Vec3& wi) {
    return std::max(0.0f, glm::dot(reflect(wi, n), wo));
}

}  // namespace

Rgb phong_eval(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
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

float phong_specular_probability(const PhongMaterial& m) {
    const float d = luminance(m.kd), s = luminance(m.ks);
    return d + s > 0.0f ? s / (d + s) : 0.0f;
}

float phong_pdf(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    const float cos_i = glm::dot(n, wi);
    if (cos_i <= 0.0f)
        return 0.0f;
    const float p_s = phong_specular_probability(m);
    float pdf = (1.0f - p_s) * cos_i * kInvPi;
    if (p_s > 0.0f)
        pdf += p_s * (m.n + 1.0f) * kInv2Pi * std::pow(cos_alpha(n, wo, wi), m.n);
    return pdf;
}

std::optional<PhongSample> phong_sample(const PhongMaterial& m, const Vec3& n, const Vec3& wo,
                                        float u_lobe, Vec2 u) {
    if (!(luminance(m.kd) + luminance(m.ks) > 0.0f))
        return std::nullopt;
    const float p_s = phong_specular_probability(m);
    Vec3 wi;
    if (u_lobe < p_s) {
        // cos α = u^(1/(n+1)) has density (n + 1)/(2π) cos^n α about the mirror direction.
        const Vec3 mirror = reflect(wo, n);
        const float c = std::pow(u.x, 1.0f / (m.n + 1.0f));
        wi = direction_about(mirror, c, kTwoPi * u.y);
    } else {
        wi = Frame(n).to_world(sample_cosine_hemisphere(u));
    }
    if (glm::dot(n, wi) <= 0.0f)
        return std::nullopt;
    PhongSample s;
    s.wi = glm::normalize(wi);
    s.f = phong_eval(m, n, wo, s.wi);
    s.pdf = phong_pdf(m, n, wo, s.wi);
    if (!(s.pdf > 0.0f))
        return std::nullopt;
    return s;
}

}  // namespace kasumi
