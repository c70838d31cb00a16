#include "lights/sphere_light.h"

#include "core/sampling.h"

namespace kasumi {

Rgb unshadowed_irradiance(const SphereLight& light, const Vec3& p, const Vec3& n) {
    const DVec3 to_center = DVec3(light.center) - DVec3(p);
    const double d = glm::length(to_center);
    const double radius = light.radius;
    if (!(d > radius))
        return Rgb(0.0f);
    const double sin2_sigma = (radius / d) * (radius / d);
    const double cos_theta = std::clamp(glm::dot(DVec3(n), to_center) / d, -1.0, 1.0);
    double e;
    if (cos_theta * cos_theta >= sin2_sigma) {
        e = cos_theta > 0.0 ? kPiD * sin2_sigma * cos_theta : 0.0;
    } else {
        const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
        const double x = std::sqrt(1.0 / sin2_sigma - 1.0);  // cot σ
        const double y = std::clamp(-x * cos_theta / sin_theta, -1.0, 1.0);
        const double s = sin_theta * std::sqrt(1.0 - y * y);
        e = (cos_theta * std::acos(y) - x * s) * sin2_sigma + std::atan(s / x);
    }
    return light.luminance * static_cast<float>(std::max(e, 0.0));
}

namespace {

/// Shirley & Chiu 1997, "A low distortion map between disk and square": [0, 1)² onto the unit
/// disc, area-preserving, mapping squares to compact (nearly square) cells, so stratified u
/// stays stratified in the disc (the polar map (√u, 2πu) turns strata into long slivers).
Vec2 concentric_disc(Vec2 u) {
    const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
    if (a == 0.0f && b == 0.0f)
        return Vec2(0.0f);
    float r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = 0.25f * kPi * (b / a);
    } else {
        r = b;
        phi = 0.5f * kPi - 0.25f * kPi * (a / b);
    }
    return Vec2(r * std::cos(phi), r * std::sin(phi));
}

}  // namespace

SphereLightCone::SphereLightCone(const SphereLight& light, const Vec3& p)
    : m_light(&light), m_p(p) {
    const Vec3 to_center = light.center - p;
    m_d = glm::length(to_center);
    if (!(m_d > light.radius))
        return;
    m_valid = true;
    m_sin2_sigma = (light.radius / m_d) * (light.radius / m_d);
    const float cos_sigma = safe_sqrt(1.0f - m_sin2_sigma);
    // 1 − cos σ without cancellation for small, distant spheres.
    m_one_minus_cos = m_sin2_sigma / (1.0f + cos_sigma);
    m_axis = to_center / m_d;
    m_frame = Frame(m_axis);
}

IncidentLight SphereLightCone::along(Vec2 disc, float rho2) const {
    // A point (x, y) uniform in the unit disc, ρ² = x² + y² uniform in [0, 1], becomes the
    // direction with 1 − cos θ = ρ² (1 − cos σ) (uniform in solid angle over the cone) at the
    // disc point's azimuth: sin θ / ρ = √((1 − cos σ)(2 − ρ² (1 − cos σ))).
    IncidentLight in;
    const float one_minus_cos_theta = rho2 * m_one_minus_cos;
    const float cos_theta = 1.0f - one_minus_cos_theta;
    const float sin_over_rho = safe_sqrt(m_one_minus_cos * (2.0f - one_minus_cos_theta));
    in.wi = glm::normalize(
        m_frame.to_world(Vec3(sin_over_rho * disc.x, sin_over_rho * disc.y, cos_theta)));
    // Nearest intersection of p + t wi with the sphere: t = d cos θ − √(R² − d² sin² θ).
    const float sin2_theta = std::max(0.0f, one_minus_cos_theta * (2.0f - one_minus_cos_theta));
    in.distance =
        m_d * cos_theta - safe_sqrt(m_light->radius * m_light->radius - m_d * m_d * sin2_theta);
    in.light_position = m_p + in.distance * in.wi;
    in.irradiance = m_light->luminance * (kTwoPi * m_one_minus_cos);
    return in;
}

IncidentLight SphereLightCone::sample(Vec2 u) const {
    if (!m_valid)
        return IncidentLight{};
    const Vec2 disc = concentric_disc(u);
    return along(disc, std::min(1.0f, disc.x * disc.x + disc.y * disc.y));
}

IncidentLight SphereLightCone::outline(float phi) const {
    if (!m_valid)
        return IncidentLight{};
    return along(Vec2(std::cos(phi), std::sin(phi)), 1.0f);
}

bool SphereLightCone::above_plane(const Vec3& n) const {
    const float c = glm::dot(n, m_axis);
    return m_valid && c > 0.0f && c * c > m_sin2_sigma;
}

IncidentLight sample_incident(const SphereLight& light, const Vec3& p, Vec2 u) {
    return SphereLightCone(light, p).sample(u);
}

float sample_pdf(const SphereLight& light, const Vec3& p, const Vec3& wi) {
    const Vec3 to_center = light.center - p;
    const float d = glm::length(to_center);
    if (!(d > light.radius))
        return 0.0f;
    const float sin2_sigma = (light.radius / d) * (light.radius / d);
    const float cos_sigma = safe_sqrt(1.0f - sin2_sigma);
    if (glm::dot(wi, to_center / d) < cos_sigma)
        return 0.0f;
    return 1.0f / (kTwoPi * sin2_sigma / (1.0f + cos_sigma));
}

float sphere_flux_lm(const SphereLight& light) {
    return 4.0f * kPi * kPi * light.radius * light.radius * luminance(light.luminance);
}

}  // namespace kasumi
