#include "render/integrator.h"

namespace kasumi {

namespace {

/// Normalised modified Phong BRDF (Lafortune & Willems 1994), per steradian.
Rgb phong_brdf(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    Rgb f = m.kd * kInvPi;
    if (max_component(m.ks) > 0.0f) {
        const Vec3 mirror = 2.0f * glm::dot(n, wi) * n - wi;
        const float cos_alpha = std::max(0.0f, glm::dot(mirror, wo));
        f += m.ks * ((m.n + 2.0f) * kInv2Pi * std::pow(cos_alpha, m.n));
    }
    return f;
}

}  // namespace

Rgb shade_surface(const SceneRuntime& scene, const SurfaceHit& hit, const Vec3& wo,
                  RenderCounters& counters) {
    const SceneDesc& desc = scene.desc();
    const PhongMaterial& material = std::get<PhongMaterial>(desc.materials[hit.material]);
    // Shade the side the viewer sees: quads and open meshes are two-sided.
    Vec3 ng = hit.geometric_normal, ns = hit.shading_normal;
    if (glm::dot(ng, wo) < 0.0f) {
        ng = -ng;
        ns = -ns;
    }
    Rgb radiance(0.0f);
    if (scene.plan().ambient)
        radiance += material.ka * desc.ambient;
    if (!scene.plan().direct_light)
        return radiance;
    for (const Light& light : desc.lights) {
        const IncidentLight in = incident_light(light, hit.position);
        if (is_black(in.irradiance))
            continue;
        const float cos_theta = glm::dot(ns, in.wi);
        if (cos_theta <= 0.0f || glm::dot(ng, in.wi) <= 0.0f)
            continue;
        const bool to_infinity = in.distance >= kInfinity;
        const Vec3 origin = offset_ray_origin(hit, in.wi);
        Rgb t_media(1.0f);
        if (scene.plan().volume) {
            t_media = scene.media().transmittance(
                Ray{origin, in.wi, 0.0f, to_infinity ? kInfinity : in.distance});
            if (is_black(t_media))
                continue;
        }
        if (scene.occlusion() != nullptr) {
            ++counters.surface_shadow_rays;
            const bool blocked = to_infinity
                                     ? scene.occlusion()->occluded_direction(origin, in.wi)
                                     : scene.occlusion()->occluded(origin, in.light_position);
            if (blocked)
                continue;
        }
        radiance += phong_brdf(material, ns, wo, in.wi) * in.irradiance * cos_theta * t_media;
    }
    return radiance;
}

PixelSample trace_camera_ray(const SceneRuntime& scene, const Ray& ray, Pcg32& rng,
                             RenderCounters& counters) {
    ++counters.camera_rays;
    PixelSample sample;
    const Vec3 wo = -ray.direction;
    float t_end = ray.t_max;
    if (const SurfaceScene* surfaces = scene.surfaces()) {
        if (const auto hit = surfaces->intersect(ray)) {
            ++counters.surface_hits;
            sample.hit = true;
            t_end = hit->t;
            sample.depth = hit->t * glm::dot(ray.direction, scene.camera().forward());
            sample.albedo = albedo(scene.desc().materials[hit->material]);
            sample.surface = shade_surface(scene, *hit, wo, counters);
        }
    }
    if (!sample.hit)
        sample.surface = scene.desc().background;

    if (scene.plan().volume) {
        ++counters.volume_rays;
        VolumeCounters vc;
        Ray segment = ray;
        segment.t_max = t_end;
        const VolumeResult v =
            integrate_volume(scene.media(), scene.desc().lights, scene.occlusion(), segment,
                             scene.desc().render.volume, scene.plan().in_scattering, rng, vc);
        counters.volume_steps += vc.steps;
        counters.volume_shadow_rays += vc.shadow_rays;
        sample.volume = v.radiance;
        sample.transmittance = v.transmittance;
    }
    sample.radiance = sample.volume + sample.transmittance * sample.surface;
    return sample;
}

}  // namespace kasumi
