#include "render/integrator.h"

#include "lights/light_samples.h"
#include "render/air_and_media.h"
#include "render/sky_environment.h"
#include "render/sky_shafts.h"
#include "render/whitted.h"
#include "surface/emitter_hit.h"
#include "surface/phong_brdf.h"
#include "surface/sphere_light_occluders.h"

#include "volume/transmittance.h"
#include "volume/volume_path.h"

namespace kasumi {

namespace {

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
                if (const GiMethod* gi = m_scene.gi())
                    return gi->surface_radiance(m_scene, unbounded, *hit, rng, m_counters);
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

namespace {

/// One light's samples at one shading point, summed for the ratio estimator of
/// shadow_sample_weight (docs/lights.md, "Shadows and the sampling API"):
/// L_r ≈ E(p, n) · reflected / unshadowed.
class LightSampleSums {
  public:
    LightSampleSums(const SceneRuntime& scene, const Light& light, const SurfaceHit& hit,
                    const PhongMaterial& material, const Vec3& ng, const Vec3& ns, const Vec3& wo,
                    KnownVisibility visible, Pcg32& rng, RenderCounters& counters)
        : m_scene(scene),
          m_light(light),
          m_hit(hit),
          m_material(material),
          m_ng(ng),
          m_ns(ns),
          m_wo(wo),
          m_visible(visible),
          m_rng(rng),
          m_counters(counters),
          m_traced(scene.occlusion() != nullptr && light.shadows == ShadowMode::Ray),
          // Every sample that casts a ray leaves on the +ng side (dot(ng, wi) > 0 is checked
          // first), so one offset origin serves them all (offset_ray_origin picks the side
          // from the sign of dot(ng, wi) alone).
          m_origin(offset_ray_origin(hit, ng)) {}

    Rgb reflected{0.0f};      ///< Σ_k f(wi_k) E_k cos θ_k T_k V_k
    float unshadowed = 0.0f;  ///< Σ_k luminance(E_k) cos θ_k over the samples above the horizon

    /// Adds one sample's terms to the sums; returns what became of it (for the probe rule).
    LightSampleOutcome add(const IncidentLight& in) {
        if (is_black(in.irradiance))
            return LightSampleOutcome::Ignored;
        const float cos_theta = glm::dot(m_ns, in.wi);
        if (cos_theta <= 0.0f)
            return LightSampleOutcome::Ignored;
        unshadowed += luminance(in.irradiance) * cos_theta;
        // Below the geometric horizon: the surface itself blocks the light.
        if (glm::dot(m_ng, in.wi) <= 0.0f)
            return LightSampleOutcome::Blocked;
        if (m_visible == KnownVisibility::Shadowed) {
            ++m_counters.shadow_rays_avoided;
            return LightSampleOutcome::Blocked;
        }
        const Rgb t_media = media_transmittance(in);
        if (is_black(t_media))
            return LightSampleOutcome::Blocked;
        if (m_visible == KnownVisibility::Lit)
            ++m_counters.shadow_rays_avoided;
        else if (m_traced && blocked(in))
            return LightSampleOutcome::Blocked;
        float visibility = 1.0f;
        if (shadows_by_stage(m_light.shadows)) {
            visibility = m_scene.staged_visibility(light_index(), m_hit, m_ng, m_origin,
                                                   in.light_position, m_wo);
            if (!(visibility > 0.0f))
                return LightSampleOutcome::Blocked;
        }
        reflected +=
            eval(m_material, m_ns, m_wo, in.wi) * in.irradiance * cos_theta * t_media * visibility;
        return LightSampleOutcome::Lit;
    }

    /// A shadow ray toward in.light_position (or along in.wi for lights at infinity) from the
    /// +ng side of the point: true when a surface blocks it.
    bool blocked(const IncidentLight& in) {
        ++m_counters.surface_shadow_rays;
        return in.distance >= kInfinity
                   ? m_scene.occlusion()->occluded_direction(m_origin, in.wi)
                   : m_scene.occlusion()->occluded(m_origin, in.light_position);
    }

  private:
    /// Transmittance of the media between the point and the light (1 without media).
    Rgb media_transmittance(const IncidentLight& in) {
        if (!m_scene.plan().volume)
            return Rgb(1.0f);
        VolumeCounters vc;
        const VolumeSettings& volume = m_scene.desc().render.volume;
        const Rgb t = estimate_transmittance(
            m_scene.media(),
            Ray{m_origin, in.wi, 0.0f, in.distance >= kInfinity ? kInfinity : in.distance},
            volume.estimator, march_step_m(m_scene.media(), volume), m_rng, vc);
        m_counters.density_lookups += vc.density_lookups;
        m_counters.transmittance_rays += vc.transmittance_estimates;
        return t;
    }
    size_t light_index() const {
        return static_cast<size_t>(&m_light - m_scene.desc().lights.data());
    }

    const SceneRuntime& m_scene;
    const Light& m_light;
    const SurfaceHit& m_hit;
    const PhongMaterial& m_material;
    const Vec3 m_ng, m_ns, m_wo;
    const KnownVisibility m_visible;
    Pcg32& m_rng;
    RenderCounters& m_counters;
    const bool m_traced;
    const Vec3 m_origin;
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
        const bool traced = scene.occlusion() != nullptr && light.shadows == ShadowMode::Ray;
        KnownVisibility visible = known != nullptr && traced ? known[&light - desc.lights.data()]
                                                             : KnownVisibility::Unknown;
        // Delta lights: one exact sample, weight 1.
        if (is_delta(light)) {
            LightSampleSums sums(scene, light, hit, material, ng, ns, wo, visible, rng, counters);
            sums.add(incident_light(light, hit.position));
            radiance += sums.reflected;
            continue;
        }
        // Extended lights: `samples` stratified samples (Owen-scrambled Sobol, seeded from
        // rng), one shadow ray each, and with `shadow_probes` the adaptive rule for ray-traced
        // or unshadowed lights (lights/light_samples.h).
        const StratifiedLightSamples u_light(rng);
        if (traced && visible == KnownVisibility::Unknown && light.exact_penumbra &&
            !(max_component(material.ks) > 0.0f) && !scene.plan().volume) {
            // Exact penumbra (surface/sphere_light_occluders.h): the closed-form visible part
            // of the light, E = L Ω_n, and a Lambertian surface without media reflects kd/π E
            // (clipped at the horizon of ns, which is the geometric one when they are equal).
            // Where the closed form does not apply, the samples below.
            const SphereLightOccluders& occluders = scene.surfaces()->sphere_light_occluders();
            std::optional<double> omega;
            Rgb light_luminance(0.0f);
            if (const auto* sphere = std::get_if<SphereLight>(&light.emitter)) {
                light_luminance = sphere->luminance;
                if (ng == ns || SphereLightCone(*sphere, hit.position).above_plane(ng))
                    omega = occluders.visible_projected_solid_angle(*sphere, hit.position, ns,
                                                                    hit.shape);
            } else if (const auto* polygon = std::get_if<PolygonLight>(&light.emitter)) {
                light_luminance = polygon->luminance;
                if (ng == ns)
                    omega = occluders.visible_projected_solid_angle(*polygon, hit.position, ns,
                                                                    hit.shape);
            }
            if (omega) {
                radiance += material.kd * kInvPi * light_luminance * static_cast<float>(*omega);
                continue;
            }
        }
        const PointLightSampler sampler(light, hit.position);
        if (traced && visible == KnownVisibility::Unknown && light.outline_probes > 0 &&
            sampler.sphere_cone() != nullptr) {
            // Outline probes (lights/light_samples.h, OutlineProbes; biased, bounded).
            LightSampleSums probes(scene, light, hit, material, ng, ns, wo, visible, rng, counters);
            const OutlineVerdict verdict = outline_verdict(
                *sampler.sphere_cone(), ng, ns, light.outline_probes, u_light.rotation(),
                [&](const IncidentLight& in) { return probes.blocked(in); });
            if (verdict == OutlineVerdict::Shadowed)
                continue;  // every sample would be blocked: no light
            if (verdict == OutlineVerdict::Lit) {
                // Entirely lit, Lambertian, no media: every sample is above both horizons, so
                // the ratio estimator returns f E(p, n) exactly; skip the samples.
                if (!(max_component(material.ks) > 0.0f) && !scene.plan().volume) {
                    radiance +=
                        material.kd * kInvPi * unshadowed_irradiance(light, hit.position, ns);
                    continue;
                }
                visible = KnownVisibility::Lit;  // specular or media: samples without rays
            }
        }
        LightSampleSums sums(scene, light, hit, material, ng, ns, wo, visible, rng, counters);
        ProbeRule probes(light.samples,
                         traced || light.shadows == ShadowMode::None ? light.shadow_probes : 0);
        for (int k = 0; k < light.samples; ++k)
            if (probes.record(k, sums.add(sampler.sample(u_light[k]))))
                break;
        radiance += shadow_sample_weight(light, hit.position, ns, sums.unshadowed) * sums.reflected;
    }
    return radiance;
}

VolumeResult trace_volume_segment(const SceneRuntime& scene, const Ray& segment, Pcg32& rng,
                                  RenderCounters& counters, const PathGuiding* guiding,
                                  const std::vector<Light>* lights) {
    ++counters.volume_rays;
    VolumeCounters vc;
    const RenderPathEnvironment environment(scene, counters);
    VolumeResult v = integrate_media(
        scene.media(), lights != nullptr ? *lights : scene.desc().lights, scene.occlusion(),
        &environment, segment, scene.desc().render.volume, scene.plan().in_scattering, rng, vc,
        !(segment.t_max < kInfinity) && is_black(scene.desc().background) && scene.sky() == nullptr,
        guiding);
    counters.volume_steps += vc.steps;
    counters.volume_shadow_rays += vc.shadow_rays;
    counters.density_lookups += vc.density_lookups;
    counters.transmittance_rays += vc.transmittance_estimates;
    counters.free_flights += vc.free_flights;
    counters.scattering_events += vc.scattering_events;
    counters.bounded_marches += vc.bounded_marches;
    // Photon mapping adds the light scattered more than once from its volume map.
    if (const GiMethod* gi = scene.gi())
        v.radiance += gi->volume_radiance(scene, segment, rng);
    return v;
}

PixelSample trace_camera_ray(const SceneRuntime& scene, const Ray& ray, Pcg32& rng,
                             RenderCounters& counters, const std::optional<SurfaceHit>* first_hit,
                             const PathGuiding* guiding) {
    ++counters.camera_rays;
    PixelSample sample;
    float t_end = ray.t_max;
    if (const SurfaceScene* surfaces = scene.surfaces()) {
        if (const auto hit = first_hit != nullptr ? *first_hit : surfaces->intersect(ray)) {
            ++counters.surface_hits;
            sample.hit = true;
            t_end = hit->t;
            sample.depth = hit->t * glm::dot(ray.direction, scene.camera().forward());
            sample.albedo = albedo(scene.desc().materials[hit->material]);
            // The one dispatch of the hit: the scene's GI method, or direct Phong + Whitted.
            const GiMethod* gi = scene.gi();
            sample.surface = gi != nullptr ? gi->surface_radiance(scene, ray, *hit, rng, counters)
                                           : shade_hit(scene, ray, *hit, rng, counters);
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

    // With an atmosphere the air and the media are composed as one medium (and the sky too).
    if (scene.plan().volume && scene.sky() != nullptr) {
        compose_air_and_media(scene, ray, t_end, rng, counters, guiding, sample);
        return sample;
    }
    if (scene.plan().volume) {
        Ray segment = ray;
        segment.t_max = t_end;
        const VolumeResult v = trace_volume_segment(scene, segment, rng, counters, guiding);
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
