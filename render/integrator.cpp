#include "render/integrator.h"

#include "lights/light_samples.h"
#include "render/gi.h"
#include "render/photon_gi.h"
#include "render/sky_environment.h"
#include "render/sky_shafts.h"
#include "render/whitted.h"
#include "surface/emitter_hit.h"

#include "volume/transmittance.h"
#include "volume/volume_path.h"

namespace kasumi {

namespace {

/// Normalised modified Phong BRDF (Lafortune & Willems 1994), per steradian.
Rgb phong_brdf(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    Rgb f = m.kd * kInvPi;
    if (max_component(m.ks) > 0.0f) {
        const Vec3 mirror = 2.0f * glm::dot(n, wi) * n - wi;
        const float cos_alpha = std::max(0.0f, glm::dot(mirror, wo));
        f += specular_reflectance(m, glm::dot(n, wi)) *
             ((m.n + 2.0f) * kInv2Pi * std::pow(cos_alpha, m.n));
    }
    return f;
}

/// What scattered paths meet beyond the media: the directly lit surfaces, or the sky (without
/// the sun's disc: next-event estimation takes the sun) or the constant background.
class RenderPathEnvironment final : public PathEnvironment {
  public:
    RenderPathEnvironment(const SceneRuntime& scene, RenderCounters& counters)
        : m_scene(scene), m_counters(counters) {}
    float surface_distance(const Ray& ray) const override {
        if (m_scene.surfaces() == nullptr)
            return kInfinity;
        const auto hit = m_scene.surfaces()->intersect(ray);
        return hit ? hit->t : kInfinity;
    }
    Rgb radiance(const Ray& ray, Pcg32& rng) const override {
        if (m_scene.surfaces() != nullptr) {
            Ray unbounded = ray;
            unbounded.t_max = kInfinity;
            if (const auto hit = m_scene.surfaces()->intersect(unbounded)) {
                if (m_scene.gi() != nullptr)
                    return gi_surface_radiance(m_scene, unbounded, *hit, rng, m_counters);
                return emitted_radiance(m_scene.desc().materials[hit->material], *hit,
                                        -ray.direction) +
                       shade_surface(m_scene, *hit, -ray.direction, rng, m_counters);
            }
        }
        return escaped_radiance(m_scene, ray, /*sun_disc=*/false, rng);
    }

  private:
    const SceneRuntime& m_scene;
    RenderCounters& m_counters;
};

}  // namespace

Rgb shade_surface(const SceneRuntime& scene, const SurfaceHit& hit, const Vec3& wo, Pcg32& rng,
                  RenderCounters& counters, const KnownVisibility* known) {
    const SceneDesc& desc = scene.desc();
    // Mirrors and dielectrics reflect lights only along discrete directions: render/whitted.cpp
    // traces them; here they are black.
    const auto* phong = std::get_if<PhongMaterial>(&desc.materials[hit.material]);
    if (phong == nullptr)
        return Rgb(0.0f);
    const PhongMaterial& material = *phong;
    // Shade the side the viewer sees: quads and open meshes are two-sided.
    Vec3 ng = hit.geometric_normal, ns = hit.shading_normal;
    if (glm::dot(ng, wo) < 0.0f) {
        ng = -ng;
        ns = -ns;
    }
    Rgb radiance(0.0f);
    if (scene.plan().ambient)
        radiance += material.ka * desc.ambient;
    if (scene.sky() != nullptr)
        radiance += material.kd * kInvPi * scene.sky()->irradiance(ns);
    if (!scene.plan().direct_light)
        return radiance;
    for (const Light& light : desc.lights) {
        // Delta lights take one exact sample; extended lights `samples` points on the light, one
        // shadow ray each, combined by the ratio estimator of shadow_sample_weight.
        const int samples = is_delta(light) ? 1 : light.samples;
        const bool traced = scene.occlusion() != nullptr && light.shadows == ShadowMode::Ray;
        const KnownVisibility visible = known != nullptr && traced
                                            ? known[&light - desc.lights.data()]
                                            : KnownVisibility::Unknown;
        Rgb reflected(0.0f);
        float unshadowed = 0.0f;
        // Extended lights: stratified samples (Owen-scrambled Sobol, seeded from rng) and, with
        // `shadow_probes`, the adaptive rule for ray-traced or unshadowed lights
        // (lights/light_samples.h). Delta lights consume no random numbers.
        const bool delta = is_delta(light);
        const StratifiedLightSamples u_light =
            delta ? StratifiedLightSamples(0u, 0u) : StratifiedLightSamples(rng);
        ProbeRule probes(samples,
                         traced || light.shadows == ShadowMode::None ? light.shadow_probes : 0);
        for (int k = 0; k < samples; ++k) {
            const IncidentLight in = delta ? incident_light(light, hit.position)
                                           : sample_incident(light, hit.position, u_light[k]);
            LightSampleOutcome outcome = LightSampleOutcome::Ignored;
            [&] {
                if (is_black(in.irradiance))
                    return;
                const float cos_theta = glm::dot(ns, in.wi);
                if (cos_theta <= 0.0f)
                    return;
                unshadowed += luminance(in.irradiance) * cos_theta;
                outcome = LightSampleOutcome::Blocked;
                if (glm::dot(ng, in.wi) <= 0.0f)
                    return;
                if (visible == KnownVisibility::Shadowed) {
                    ++counters.shadow_rays_avoided;
                    return;
                }
                const bool to_infinity = in.distance >= kInfinity;
                const Vec3 origin = offset_ray_origin(hit, in.wi);
                Rgb t_media(1.0f);
                if (scene.plan().volume) {
                    VolumeCounters vc;
                    const VolumeSettings& volume = desc.render.volume;
                    t_media = estimate_transmittance(
                        scene.media(),
                        Ray{origin, in.wi, 0.0f, to_infinity ? kInfinity : in.distance},
                        volume.estimator, march_step_m(scene.media(), volume), rng, vc);
                    counters.density_lookups += vc.density_lookups;
                    counters.transmittance_rays += vc.transmittance_estimates;
                    if (is_black(t_media))
                        return;
                }
                if (visible == KnownVisibility::Lit) {
                    ++counters.shadow_rays_avoided;
                } else if (traced) {
                    ++counters.surface_shadow_rays;
                    const bool blocked =
                        to_infinity ? scene.occlusion()->occluded_direction(origin, in.wi)
                                    : scene.occlusion()->occluded(origin, in.light_position);
                    if (blocked)
                        return;
                }
                float visibility = 1.0f;
                if (light.shadows == ShadowMode::Map || light.shadows == ShadowMode::ShadowVolume) {
                    visibility =
                        scene.staged_visibility(static_cast<size_t>(&light - desc.lights.data()),
                                                hit.position, ng, origin, in.light_position, wo);
                    if (!(visibility > 0.0f))
                        return;
                }
                outcome = LightSampleOutcome::Lit;
                reflected += phong_brdf(material, ns, wo, in.wi) * in.irradiance * cos_theta *
                             t_media * visibility;
            }();
            if (probes.record(k, outcome))
                break;
        }
        radiance += shadow_sample_weight(light, hit.position, ns, unshadowed) * reflected;
    }
    return radiance;
}

VolumeResult trace_volume_segment(const SceneRuntime& scene, const Ray& segment, Pcg32& rng,
                                  RenderCounters& counters) {
    ++counters.volume_rays;
    VolumeCounters vc;
    const RenderPathEnvironment environment(scene, counters);
    VolumeResult v =
        integrate_media(scene.media(), scene.desc().lights, scene.occlusion(), &environment,
                        segment, scene.desc().render.volume, scene.plan().in_scattering, rng, vc,
                        !(segment.t_max < kInfinity) && is_black(scene.desc().background) &&
                            scene.sky() == nullptr);
    counters.volume_steps += vc.steps;
    counters.volume_shadow_rays += vc.shadow_rays;
    counters.density_lookups += vc.density_lookups;
    counters.transmittance_rays += vc.transmittance_estimates;
    counters.free_flights += vc.free_flights;
    counters.scattering_events += vc.scattering_events;
    // Photon mapping adds the light scattered more than once from its volume map.
    if (const auto* photons = dynamic_cast<const PhotonGi*>(scene.gi()))
        v.radiance += photons->volume_radiance(scene, segment, rng);
    return v;
}

PixelSample trace_camera_ray(const SceneRuntime& scene, const Ray& ray, Pcg32& rng,
                             RenderCounters& counters) {
    ++counters.camera_rays;
    PixelSample sample;
    float t_end = ray.t_max;
    if (const SurfaceScene* surfaces = scene.surfaces()) {
        if (const auto hit = surfaces->intersect(ray)) {
            ++counters.surface_hits;
            sample.hit = true;
            t_end = hit->t;
            sample.depth = hit->t * glm::dot(ray.direction, scene.camera().forward());
            sample.albedo = albedo(scene.desc().materials[hit->material]);
            sample.surface = gi_surface_radiance(scene, ray, *hit, rng, counters);
        }
    }
    if (!sample.hit)
        sample.surface = scene.desc().background;
    if (scene.plan().visible_lights) {
        // Area lights in front of the first surface are seen with their luminance.
        if (const auto light = intersect_emitters(
                scene.desc().lights, Ray{ray.origin, ray.direction, ray.t_min, t_end})) {
            sample.hit = true;
            t_end = light->t;
            sample.depth = light->t * glm::dot(ray.direction, scene.camera().forward());
            sample.albedo = Rgb(0.0f);
            sample.surface = light->radiance;
        }
    }

    if (scene.plan().volume) {
        Ray segment = ray;
        segment.t_max = t_end;
        const VolumeResult v = trace_volume_segment(scene, segment, rng, counters);
        sample.volume = v.radiance;
        sample.transmittance = v.transmittance;
    }
    sample.radiance = sample.volume + sample.transmittance * sample.surface;
    if (scene.sky() != nullptr) {
        scene.sky()->apply(ray, t_end, rng, sample);
        apply_sky_shafts(scene, ray, t_end, rng, sample, counters);
    }
    return sample;
}

}  // namespace kasumi
