#include "render/whitted.h"

#include "render/integrator.h"
#include "render/sky_environment.h"
#include "surface/emitter_hit.h"
#include "surface/fresnel.h"

#include <algorithm>

namespace kasumi {

namespace {

/// Lighting at the hit triangle's three vertices with their normals, interpolated with the
/// hit's barycentrics (Gouraud 1971). The view direction at each vertex points to ray.origin,
/// as a rasteriser computes it per vertex.
Rgb shade_gouraud(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit, Pcg32& rng,
                  RenderCounters& counters) {
    const std::optional<HitTriangle> triangle = scene.surfaces()->triangle(hit);
    if (!triangle)
        return shade_surface(scene, hit, -ray.direction, rng, counters);
    std::array<Rgb, 3> vertex_radiance;
    for (int k = 0; k < 3; ++k) {
        SurfaceHit vertex = hit;
        vertex.position = triangle->positions[k];
        vertex.geometric_normal = triangle->normals[k];
        vertex.shading_normal = triangle->normals[k];
        const Vec3 to_origin = ray.origin - vertex.position;
        const float length = glm::length(to_origin);
        const Vec3 wo = length > 0.0f ? to_origin / length : -ray.direction;
        vertex_radiance[k] = shade_surface(scene, vertex, wo, rng, counters);
    }
    return interpolate(vertex_radiance, hit.u, hit.v);
}

/// The secondary ray leaving `hit` along `direction`, traced if the recursion allows it.
Rgb trace_branch(const SceneRuntime& scene, const SurfaceHit& hit, const Vec3& direction,
                 float branch_weight, Pcg32& rng, RenderCounters& counters,
                 const PhongShading* phong, int depth) {
    const WhittedSettings& settings = scene.desc().render.whitted;
    if (depth >= settings.max_depth || !(branch_weight >= settings.min_weight) ||
        branch_weight <= 0.0f)
        return Rgb(0.0f);
    const Ray ray{offset_ray_origin(hit, direction), direction, 0.0f, kInfinity};
    return trace_whitted_ray(scene, ray, rng, counters, phong, depth + 1, branch_weight);
}

Rgb shade_mirror(const SceneRuntime& scene, const MirrorMaterial& mirror, const Ray& ray,
                 const SurfaceHit& hit, Pcg32& rng, RenderCounters& counters,
                 const PhongShading* phong, int depth, float weight) {
    const Vec3 wo = -ray.direction;
    const Vec3 wr = glm::normalize(reflect(wo, hit.shading_normal));
    return mirror.kr * trace_branch(scene, hit, wr, weight * max_component(mirror.kr), rng,
                                    counters, phong, depth);
}

Rgb shade_dielectric(const SceneRuntime& scene, const DielectricMaterial& glass, const Ray& ray,
                     const SurfaceHit& hit, Pcg32& rng, RenderCounters& counters,
                     const PhongShading* phong, int depth, float weight) {
    const Vec3 wo = -ray.direction;
    // The shape's normal points outside, where the relative index is 1; flip it to wo's side.
    const float cos_o = glm::dot(hit.shading_normal, wo);
    const bool outside = cos_o >= 0.0f;
    const Vec3 n = outside ? hit.shading_normal : -hit.shading_normal;
    const float eta = outside ? glass.ior : 1.0f / glass.ior;  // η_refracted / η_viewer
    const float reflectance = fresnel_dielectric(cos_o, glass.ior);
    Rgb radiance(0.0f);
    if (reflectance > 0.0f) {
        const Vec3 wr = glm::normalize(reflect(wo, n));
        radiance += reflectance *
                    trace_branch(scene, hit, wr, weight * reflectance, rng, counters, phong, depth);
    }
    if (reflectance < 1.0f) {
        if (const std::optional<Vec3> wt = refract(wo, n, eta)) {
            const Rgb transmittance = (1.0f - reflectance) * glass.tint;
            radiance += transmittance / (eta * eta) *
                        trace_branch(scene, hit, *wt, weight * max_component(transmittance), rng,
                                     counters, phong, depth);
        }
    }
    return radiance;
}

}  // namespace

Rgb emitted_radiance(const Material& material, const SurfaceHit& hit, const Vec3& wo) {
    if (glm::dot(hit.geometric_normal, wo) <= 0.0f)
        return Rgb(0.0f);
    return emission(material);
}

Rgb shade_hit(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit, Pcg32& rng,
              RenderCounters& counters, const PhongShading* phong, int depth, float weight) {
    const Material& material = scene.desc().materials[hit.material];
    const Rgb emitted = emitted_radiance(material, hit, -ray.direction);
    if (const auto* mirror = std::get_if<MirrorMaterial>(&material))
        return emitted +
               shade_mirror(scene, *mirror, ray, hit, rng, counters, phong, depth, weight);
    if (const auto* glass = std::get_if<DielectricMaterial>(&material))
        return emitted +
               shade_dielectric(scene, *glass, ray, hit, rng, counters, phong, depth, weight);
    if (phong != nullptr)
        return emitted + phong->phong_radiance(scene, ray, hit, rng, counters);
    if (hit.shading == Shading::Gouraud)
        return emitted + shade_gouraud(scene, ray, hit, rng, counters);
    return emitted + shade_surface(scene, hit, -ray.direction, rng, counters);
}

Rgb trace_whitted_ray(const SceneRuntime& scene, const Ray& ray, Pcg32& rng,
                      RenderCounters& counters, const PhongShading* phong, int depth,
                      float weight) {
    Rgb surface(0.0f);
    float t_end = ray.t_max;
    bool hit_surface = false;
    if (const SurfaceScene* surfaces = scene.surfaces()) {
        if (const auto hit = surfaces->intersect(ray)) {
            t_end = hit->t;
            hit_surface = true;
            surface = shade_hit(scene, ray, *hit, rng, counters, phong, depth, weight);
        }
    }
    // A ray that leaves the scene sees the sky with the sun's disc (or the background).
    if (!hit_surface)
        surface = escaped_radiance(scene, ray, true, rng);
    if (scene.plan().visible_lights) {
        // A mirror or glass shows the area lights in front of the next surface.
        if (const auto light = intersect_emitters(
                scene.desc().lights, Ray{ray.origin, ray.direction, ray.t_min, t_end})) {
            t_end = light->t;
            surface = light->radiance;
        }
    }
    if (scene.plan().volume) {
        Ray segment = ray;
        segment.t_max = t_end;
        const VolumeResult v = trace_volume_segment(scene, segment, rng, counters);
        surface = v.radiance + v.transmittance * surface;
    }
    // The air in front of what the ray reached (the sky already holds the air of open rays).
    return through_air(scene, ray, t_end, surface, rng);
}

}  // namespace kasumi
