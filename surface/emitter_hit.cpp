#include "surface/emitter_hit.h"

#include "surface/ray_sphere.h"

namespace kasumi {

namespace {

std::optional<float> intersect(const PolygonLight& light, const Ray& ray) {
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
    return t;
}

std::optional<float> intersect(const SphereLight& light, const Ray& ray) {
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
    return static_cast<float>(*t);
}

}  // namespace

std::optional<EmitterHit> intersect_emitters(const std::vector<Light>& lights, const Ray& ray) {
    std::optional<EmitterHit> nearest;
    Ray r = ray;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (const auto* polygon = std::get_if<PolygonLight>(&lights[i].emitter)) {
            if (const auto t = intersect(*polygon, r)) {
                const bool front = glm::dot(polygon->normal, ray.direction) < 0.0f;
                nearest =
                    EmitterHit{*t, front || polygon->two_sided ? polygon->luminance : Rgb(0.0f), i};
                r.t_max = *t;
            }
        } else if (const auto* sphere = std::get_if<SphereLight>(&lights[i].emitter)) {
            if (const auto t = intersect(*sphere, r)) {
                nearest = EmitterHit{*t, sphere->luminance, i};
                r.t_max = *t;
            }
        }
    }
    return nearest;
}

bool has_visible_emitters(const std::vector<Light>& lights) {
    for (const Light& light : lights)
        if (std::holds_alternative<PolygonLight>(light.emitter) ||
            std::holds_alternative<SphereLight>(light.emitter))
            return true;
    return false;
}

}  // namespace kasumi
