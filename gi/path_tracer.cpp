#include "gi/path_tracer.h"

#include "core/error.h"
#include "lights/light_hit.h"
#include "render/integrator.h"
#include "render/sky_environment.h"
#include "render/whitted.h"
#include "surface/fresnel.h"
#include "surface/phong_brdf.h"
#include "volume/transmittance.h"

#include <sstream>

namespace kasumi {

namespace {

/// Power heuristic with β = 2 (Veach & Guibas 1995, eq. 9) for a one-sample-each combination.
float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0.0f ? a / (a + b) : 0.0f;
}

/// Transmittance of the media over [0, distance] along (origin, direction); 1 without media.
Rgb media_transmittance(const SceneRuntime& scene, const Vec3& origin, const Vec3& direction,
                        float distance, Pcg32& rng) {
    if (!scene.plan().volume)
        return Rgb(1.0f);
    VolumeCounters vc;
    const VolumeSettings& volume = scene.desc().render.volume;
    return estimate_transmittance(scene.media(), Ray{origin, direction, 0.0f, distance},
                                  volume.estimator, march_step_m(scene.media(), volume), rng, vc);
}

}  // namespace

void require_energy_conserving(const SceneDesc& scene) {
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const auto* phong = std::get_if<PhongMaterial>(&scene.materials[i]);
        if (phong == nullptr)
            continue;
        const Rgb sum = phong->kd + phong->ks;
        if (max_component(sum) > 1.0f) {
            std::ostringstream msg;
            msg << scene.file << ": /materials/" << scene.material_names[i] << ": kd + ks = ("
                << sum.r << ", " << sum.g << ", " << sum.b
                << ") exceeds 1: render.gi = " << gi_mode_name(scene.render.gi)
                << " needs energy-conserving Phong materials";
            throw_input_error(msg.str());
        }
    }
}

PathTracer::PathTracer(const SceneRuntime& scene) : m_emitters(scene.desc()) {
    require_energy_conserving(scene.desc());
}

std::string PathTracer::summary() const {
    std::ostringstream out;
    out << (m_emitters.empty() ? "no emissive triangles"
                               : "emissive triangles sampled by power, total L·A " +
                                     std::to_string(m_emitters.total_weight()) + " cd");
    return out.str();
}

Rgb PathTracer::direct_light(const SceneRuntime& scene, const SurfaceHit& hit,
                             const PhongMaterial& m, const Vec3& ns, const Vec3& wo, Pcg32& rng,
                             RenderCounters& counters) const {
    const SceneDesc& desc = scene.desc();
    const Vec3 ng =
        glm::dot(hit.geometric_normal, wo) < 0.0f ? -hit.geometric_normal : hit.geometric_normal;
    Rgb radiance(0.0f);
    for (const Light& light : desc.lights) {
        const IncidentLight in = sample_incident(light, hit.position, rng);
        if (is_black(in.irradiance))
            continue;
        const float cos_theta = glm::dot(ns, in.wi);
        if (cos_theta <= 0.0f || glm::dot(ng, in.wi) <= 0.0f)
            continue;
        const Rgb f = eval(m, ns, wo, in.wi);
        if (is_black(f))
            continue;
        const bool to_infinity = in.distance >= kInfinity;
        const Vec3 origin = offset_ray_origin(hit, in.wi);
        if (scene.occlusion() != nullptr && light.shadows != ShadowMode::None) {
            ++counters.surface_shadow_rays;
            const bool blocked = to_infinity
                                     ? scene.occlusion()->occluded_direction(origin, in.wi)
                                     : scene.occlusion()->occluded(origin, in.light_position);
            if (blocked)
                continue;
        }
        const Rgb t_media =
            media_transmittance(scene, origin, in.wi, to_infinity ? kInfinity : in.distance, rng);
        const float pdf_light = sample_pdf(light, hit.position, in.wi);
        const float weight =
            pdf_light > 0.0f ? power_heuristic(pdf_light, pdf(m, ns, wo, in.wi)) : 1.0f;
        radiance += f * in.irradiance * (cos_theta * weight) * t_media;
    }
    if (!m_emitters.empty()) {
        const float u_pick = rng.next_float();
        const Vec2 u = rng.next_vec2();
        if (const auto s = m_emitters.sample(u_pick, u)) {
            const Vec3 d = s->position - hit.position;
            const float distance = glm::length(d);
            const Vec3 wi = d / distance;
            const float cos_l = -glm::dot(s->normal, wi);
            const float cos_theta = glm::dot(ns, wi);
            if (distance > 0.0f && cos_l > 0.0f && cos_theta > 0.0f && glm::dot(ng, wi) > 0.0f) {
                const Rgb f = eval(m, ns, wo, wi);
                const Vec3 origin = offset_ray_origin(hit, wi);
                ++counters.surface_shadow_rays;
                // Stop short of the emitter so the sampled point does not block itself.
                const float t_max = glm::length(s->position - origin) * (1.0f - 1e-4f);
                if (!is_black(f) && !scene.surfaces()->occluded(Ray{origin, wi, 0.0f, t_max})) {
                    const float pdf_solid = s->pdf_area * distance * distance / cos_l;
                    const float weight = power_heuristic(pdf_solid, pdf(m, ns, wo, wi));
                    radiance += f * s->radiance * (cos_theta * weight / pdf_solid) *
                                media_transmittance(scene, origin, wi, t_max, rng);
                }
            }
        }
    }
    return radiance;
}

Rgb PathTracer::lights_hit(const SceneRuntime& scene, const Ray& ray, float t_end, bool specular,
                           float bsdf_pdf, Pcg32& rng) const {
    Rgb radiance(0.0f);
    for (const Light& light : scene.desc().lights) {
        const auto seen = intersect(light, ray);
        if (!seen || !(seen->t < t_end) || is_black(seen->radiance))
            continue;
        const float t = seen->t;
        const float weight =
            specular ? 1.0f
                     : power_heuristic(bsdf_pdf, sample_pdf(light, ray.origin, ray.direction));
        radiance +=
            seen->radiance * weight * media_transmittance(scene, ray.origin, ray.direction, t, rng);
    }
    return radiance;
}

Rgb PathTracer::surface_radiance(const SceneRuntime& scene, const Ray& camera_ray,
                                 const SurfaceHit& first, Pcg32& rng,
                                 RenderCounters& counters) const {
    const SceneDesc& desc = scene.desc();
    const PathSettings& settings = desc.render.path;
    Rgb radiance(0.0f), beta(1.0f);
    Ray ray = camera_ray;
    SurfaceHit hit = first;
    bool specular = true;  // the last bounce was a delta distribution (or the camera)
    float bsdf_pdf = 0.0f;
    for (int bounce = 0;; ++bounce) {
        const Material& material = desc.materials[hit.material];
        const Vec3 wo = -ray.direction;
        const Rgb emitted = emitted_radiance(material, hit, wo);
        if (!is_black(emitted)) {
            float weight = 1.0f;
            if (!specular && m_emitters.is_sampled(hit.shape)) {
                const float cos_l = std::abs(glm::dot(hit.geometric_normal, wo));
                const float pdf_light =
                    cos_l > 0.0f ? m_emitters.pdf_area(emission(material)) * hit.t * hit.t / cos_l
                                 : 0.0f;
                weight = power_heuristic(bsdf_pdf, pdf_light);
            }
            radiance += beta * emitted * weight;
        }
        if (bounce >= settings.max_depth)
            break;

        Vec3 direction;
        if (const auto* mirror = std::get_if<MirrorMaterial>(&material)) {
            direction = glm::normalize(reflect(wo, hit.shading_normal));
            beta *= mirror->kr;
            specular = true;
        } else if (const auto* glass = std::get_if<DielectricMaterial>(&material)) {
            // Reflect with probability F, else refract: the weights F / F and
            // (1 - F) tint / η² / (1 - F) leave beta times 1 or tint / η² (as render/whitted.h).
            const float cos_o = glm::dot(hit.shading_normal, wo);
            const bool outside = cos_o >= 0.0f;
            const Vec3 n = outside ? hit.shading_normal : -hit.shading_normal;
            const float eta = outside ? glass->ior : 1.0f / glass->ior;
            const float reflectance = fresnel_dielectric(cos_o, glass->ior);
            const std::optional<Vec3> refracted = refract(wo, n, eta);
            if (!refracted || rng.next_float() < reflectance) {
                direction = glm::normalize(reflect(wo, n));
            } else {
                direction = *refracted;
                beta *= glass->tint / (eta * eta);
            }
            specular = true;
        } else {
            const auto& phong = std::get<PhongMaterial>(material);
            Vec3 ns = hit.shading_normal;
            if (glm::dot(hit.geometric_normal, wo) < 0.0f)
                ns = -ns;
            if (glm::dot(ns, wo) <= 0.0f)
                break;
            radiance += beta * direct_light(scene, hit, phong, ns, wo, rng, counters);
            const float u_lobe = rng.next_float();
            const auto s = sample(phong, ns, wo, u_lobe, rng.next_vec2());
            if (!s)
                break;
            const Vec3 ng = glm::dot(hit.geometric_normal, wo) < 0.0f ? -hit.geometric_normal
                                                                      : hit.geometric_normal;
            if (glm::dot(ng, s->wi) <= 0.0f)
                break;
            beta *= s->f * (glm::dot(ns, s->wi) / s->pdf);
            direction = s->wi;
            bsdf_pdf = s->pdf;
            specular = false;
        }
        if (is_black(beta))
            break;
        if (bounce + 1 >= settings.rr_depth) {
            // Russian roulette: continue with probability q, dividing by q keeps it unbiased.
            const float q = std::min(0.95f, max_component(beta));
            if (!(rng.next_float() < q))
                break;
            beta /= q;
        }

        ray = Ray{offset_ray_origin(hit, direction), direction, 0.0f, kInfinity};
        const std::optional<SurfaceHit> next = scene.surfaces()->intersect(ray);
        const float t_end = next ? next->t : kInfinity;
        if (scene.sky() != nullptr && next) {
            // The air in front of the next surface (open rays: the sky below holds it).
            Rgb l_air(0.0f), t_air(1.0f);
            scene.sky()->aerial_perspective(ray, t_end, rng, l_air, t_air);
            radiance += beta * l_air;
            beta *= t_air;
        }
        radiance += beta * lights_hit(scene, ray, t_end, specular, bsdf_pdf, rng);
        if (scene.plan().volume) {
            Ray segment = ray;
            segment.t_max = t_end;
            const VolumeResult v = trace_volume_segment(scene, segment, rng, counters);
            radiance += beta * v.radiance;
            beta *= v.transmittance;
        }
        if (!next) {
            // The environment: the sky (or the background). After a Phong bounce the sun's
            // disc is left out, since next-event estimation already sampled the sun as a
            // directional light (counting it here too would double it); after a mirror or
            // glass bounce no light was sampled, so the disc is seen.
            radiance += beta * escaped_radiance(scene, ray, specular, rng);
            break;
        }
        hit = *next;
    }
    return radiance;
}

}  // namespace kasumi
