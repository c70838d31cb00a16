#include "lights/light_hit.h"

#include "lights/ray_sphere.h"

namespace kasumi {

std::optional<LightHit> intersect(const PolygonLight& light, const Ray& ray) {
    const float denom = glm::dot(light.normal, ray.direction);
    if (denom == 0.0f)
        return std::nullopt;
    const float t = glm::dot(light.normal, light.vertices[0] - ray.origin) / denom;
    if (!(t > ray.t_min && t < ray.t_max))
        return std::nullopt;
    const Vec3 x = ray.at(t);
    // Convex and counter-clockwise about the normal: inside when left of every edge.
    const size_t n = light.vertices.size();
    for (size_t i = 0; i < n; ++i) {
        const Vec3& a = light.vertices[i];
        const Vec3& b = light.vertices[(i + 1) % n];
        if (glm::dot(glm::cross(b - a, x - a), light.normal) < 0.0f)
            return std::nullopt;
    }
    const bool front = denom < 0.0f;
    return LightHit{t, front || light.two_sided ? light.luminance : Rgb(0.0f)};
}

std::optional<LightHit> intersect(const SphereLight& light, const Ray& ray) {
    // Every camera ray asks: reject the ones whose line passes well clear of the sphere in
    // float first. f·f − (f·d)² is the squared distance of the centre from the line; in float
    // its rounding error is a few ulps of f·f (≈ 1e-6 f·f even with a direction off unit length
    // by 1e-6), so a margin of 1e-4 f·f never rejects a ray the exact test below would accept.
    const Vec3 f = light.center - ray.origin;
    const float ff = glm::dot(f, f);
    const float b = glm::dot(f, ray.direction);
    if (ff - b * b > light.radius * light.radius + 1e-4f * ff)
        return std::nullopt;
    const DVec3 center(light.center);
    const DVec3 origin(ray.origin);
    const DVec3 d = origin - center;
    if (glm::dot(d, d) <= static_cast<double>(light.radius) * light.radius)
        return std::nullopt;
    const auto t =
        intersect_sphere(center, light.radius, origin, DVec3(ray.direction), ray.t_min, ray.t_max);
    if (!t)
        return std::nullopt;
    return LightHit{static_cast<float>(*t), light.luminance};
}

std::optional<LightHit> intersect(const Light& light, const Ray& ray) {
    if (const auto* polygon = std::get_if<PolygonLight>(&light.emitter))
        return intersect(*polygon, ray);
    if (const auto* sphere = std::get_if<SphereLight>(&light.emitter))
        return intersect(*sphere, ray);
    return std::nullopt;
}

float sample_pdf(const PolygonLight& light, const Vec3& p, const Vec3& wi) {
    const auto hit = intersect(light, Ray{p, wi, 0.0f, kInfinity});
    if (!hit)
        return 0.0f;
    // Area to solid angle: dω = |cos θ_light| dA / r², so p_ω = p_A r² / |cos θ_light|.
    const float cos_light = std::abs(glm::dot(light.normal, wi));
    return cos_light > 0.0f ? hit->t * hit->t / (light.area * cos_light) : 0.0f;
}

float sample_pdf(const Light& light, const Vec3& p, const Vec3& wi) {
    if (const auto* polygon = std::get_if<PolygonLight>(&light.emitter))
        return sample_pdf(*polygon, p, wi);
    if (const auto* sphere = std::get_if<SphereLight>(&light.emitter))
        return sample_pdf(*sphere, p, wi);
    return 0.0f;
}

}  // namespace kasumi
