#include "render/photon_render.h"

#include "core/sampling.h"
#include "render/integrator.h"
#include "render/photon_estimate.h"
#include "surface/fresnel.h"
#include "volume/march_walk.h"
#include "volume/transmittance.h"
#include "volume/volume_path.h"

namespace kasumi {

namespace {

/// Below this camera transmittance the volume-map march stops (as the single-scattering march).
constexpr float kTailTransmittance = 1e-6f;
/// Specular bounces a final-gather ray follows through mirrors and glass to a Phong surface.
constexpr int kGatherSpecularDepth = 8;

/// Normalised modified Phong BRDF per steradian (Lafortune & Willems 1994), as shade_surface.
Rgb phong_brdf(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    Rgb f = m.kd * kInvPi;
    if (max_component(m.ks) > 0.0f) {
        const Vec3 mirror = 2.0f * glm::dot(n, wi) * n - wi;
        const float cos_alpha = std::max(0.0f, glm::dot(mirror, wo));
        f += specular_reflectance(m, std::max(0.0f, glm::dot(n, wi))) *
             ((m.n + 2.0f) * kInv2Pi * std::pow(cos_alpha, m.n));
    }
    return f;
}

/// Geometric and shading normals turned to the side wo leaves from.
void face_normals(const SurfaceHit& hit, const Vec3& wo, Vec3& ng, Vec3& ns) {
    ng = hit.geometric_normal;
    ns = hit.shading_normal;
    if (glm::dot(ng, wo) < 0.0f) {
        ng = -ng;
        ns = -ns;
    }
}

PhotonQueryScratch& scratch() {
    thread_local PhotonQueryScratch s;
    return s;
}

Rgb map_radiance(const PhotonRenderContext& c, const PhotonMap& map, const PhongMaterial& m,
                 const SurfaceHit& hit, const Vec3& wo) {
    Vec3 ng, ns;
    face_normals(hit, wo, ng, ns);
    return surface_estimate(map, hit.position, ng, c.settings.k, c.settings.max_radius_m,
                            c.settings.filter, scratch(),
                            [&](const Vec3& wi) { return phong_brdf(m, ns, wo, wi); });
}

/// Transmittance of the media over a ray segment (exact for homogeneous media).
Rgb segment_transmittance(const SceneRuntime& scene, const Ray& segment, Pcg32& rng) {
    if (!scene.plan().volume)
        return Rgb(1.0f);
    VolumeCounters vc;
    return estimate_transmittance(scene.media(), segment, scene.desc().render.volume.estimator,
                                  march_step_m(scene.media(), scene.desc().render.volume), rng, vc);
}

/// Radiance a final-gather ray brings back: the global map at the first Phong surface it meets
/// (through up to kGatherSpecularDepth mirror and glass events, chosen by Fresnel), attenuated
/// by the media on the way, or the background.
Rgb gather_ray(const PhotonRenderContext& c, Ray ray, Pcg32& rng) {
    const SceneRuntime& scene = c.scene;
    Rgb weight(1.0f);
    for (int depth = 0; depth <= kGatherSpecularDepth; ++depth) {
        const auto hit = scene.surfaces()->intersect(ray);
        Ray segment = ray;
        segment.t_max = hit ? hit->t : kInfinity;
        weight *= segment_transmittance(scene, segment, rng);
        if (is_black(weight))
            return Rgb(0.0f);
        if (!hit)
            return weight * scene.desc().background;
        const Vec3 wo = -ray.direction;
        const Material& material = scene.desc().materials[hit->material];
        if (const auto* phong = std::get_if<PhongMaterial>(&material))
            return weight * map_radiance(c, c.maps.global, *phong, *hit, wo);
        Vec3 next;
        if (const auto* mirror = std::get_if<MirrorMaterial>(&material)) {
            weight *= mirror->kr;
            next = glm::normalize(reflect(wo, hit->shading_normal));
        } else {
            const auto& glass = std::get<DielectricMaterial>(material);
            const float cos_o = glm::dot(hit->shading_normal, wo);
            const Vec3 n = cos_o >= 0.0f ? hit->shading_normal : -hit->shading_normal;
            const float eta = cos_o >= 0.0f ? glass.ior : 1.0f / glass.ior;
            const float reflectance = fresnel_dielectric(cos_o, glass.ior);
            const std::optional<Vec3> wt = reflectance < 1.0f ? refract(wo, n, eta) : std::nullopt;
            // One branch chosen with probability F: the estimate stays unbiased. Radiance
            // crossing the interface scales by 1/η².
            if (!wt || rng.next_float() < reflectance) {
                next = glm::normalize(reflect(wo, n));
            } else {
                next = *wt;
                weight *= glass.tint / (eta * eta);
            }
        }
        ray = Ray{offset_ray_origin(*hit, next), next, 0.0f, kInfinity};
    }
    return Rgb(0.0f);
}

/// Indirect light at a Phong hit by final gathering (Jensen 2001, §9.3.4): N cosine-weighted
/// rays, each weighted by π f_r (f_r cos θ / pdf with pdf cos θ / π).
Rgb final_gather(const PhotonRenderContext& c, const PhongMaterial& m, const SurfaceHit& hit,
                 const Vec3& wo, Pcg32& rng) {
    const int n = c.settings.final_gather_samples;
    Vec3 ng, ns;
    face_normals(hit, wo, ng, ns);
    if (glm::dot(ns, wo) <= 0.0f)
        ns = ng;
    const Frame frame(ns);
    Rgb sum(0.0f);
    // Stratified over a √N × √N grid where N is a square, else plain random.
    const int side = static_cast<int>(std::lround(std::sqrt(static_cast<float>(n))));
    const bool stratified = side * side == n;
    for (int j = 0; j < n; ++j) {
        Vec2 u = rng.next_vec2();
        if (stratified)
            u = (Vec2(static_cast<float>(j % side), static_cast<float>(j / side)) + u) /
                static_cast<float>(side);
        const Vec3 wi = frame.to_world(sample_cosine_hemisphere(u));
        if (!(glm::dot(wi, ng) > 0.0f))
            continue;
        const Rgb l = gather_ray(c, Ray{offset_ray_origin(hit, wi), wi, 0.0f, kInfinity}, rng);
        sum += kPi * phong_brdf(m, ns, wo, wi) * l;
    }
    return sum / static_cast<float>(n);
}

Rgb shade_phong(const PhotonRenderContext& c, const PhongMaterial& m, const SurfaceHit& hit,
                const Vec3& wo, Pcg32& rng, RenderCounters& counters) {
    Rgb radiance = shade_surface(c.scene, hit, wo, rng, counters);
    radiance += map_radiance(c, c.maps.caustic, m, hit, wo);
    if (c.settings.final_gather_samples > 0)
        radiance += final_gather(c, m, hit, wo, rng);
    return radiance;
}

Rgb shade(const PhotonRenderContext& c, const Ray& ray, const SurfaceHit& hit, Pcg32& rng,
          RenderCounters& counters, int depth, float weight) {
    const Vec3 wo = -ray.direction;
    const Material& material = c.scene.desc().materials[hit.material];
    if (const auto* phong = std::get_if<PhongMaterial>(&material))
        return shade_phong(c, *phong, hit, wo, rng, counters);
    const WhittedSettings& whitted = c.scene.desc().render.whitted;
    auto branch = [&](const Vec3& d, float w) {
        if (depth >= whitted.max_depth || !(w >= whitted.min_weight) || w <= 0.0f)
            return Rgb(0.0f);
        return photon_ray_radiance(c, Ray{offset_ray_origin(hit, d), d, 0.0f, kInfinity}, rng,
                                   counters, depth + 1, w);
    };
    if (const auto* mirror = std::get_if<MirrorMaterial>(&material)) {
        const Vec3 wr = glm::normalize(reflect(wo, hit.shading_normal));
        return mirror->kr * branch(wr, weight * max_component(mirror->kr));
    }
    const auto& glass = std::get<DielectricMaterial>(material);
    const float cos_o = glm::dot(hit.shading_normal, wo);
    const bool outside = cos_o >= 0.0f;
    const Vec3 n = outside ? hit.shading_normal : -hit.shading_normal;
    const float eta = outside ? glass.ior : 1.0f / glass.ior;
    const float reflectance = fresnel_dielectric(cos_o, glass.ior);
    Rgb radiance(0.0f);
    if (reflectance > 0.0f)
        radiance += reflectance * branch(glm::normalize(reflect(wo, n)), weight * reflectance);
    if (reflectance < 1.0f) {
        if (const std::optional<Vec3> wt = refract(wo, n, eta)) {
            const Rgb t = (1.0f - reflectance) * glass.tint;
            radiance += t / (eta * eta) * branch(*wt, weight * max_component(t));
        }
    }
    return radiance;
}

/// The volume stage of the photon renderer over one segment: single scattering by shadow rays
/// (the scene's estimator, integrator forced to single) plus the volume map.
VolumeResult photon_volume(const PhotonRenderContext& c, const Ray& segment, Pcg32& rng,
                           RenderCounters& counters) {
    const SceneRuntime& scene = c.scene;
    ++counters.volume_rays;
    VolumeSettings single = scene.desc().render.volume;
    single.integrator = VolumeIntegrator::Single;
    VolumeCounters vc;
    VolumeResult v = integrate_media(scene.media(), scene.desc().lights, scene.occlusion(), nullptr,
                                     segment, single, scene.plan().in_scattering, rng, vc);
    counters.volume_steps += vc.steps;
    counters.volume_shadow_rays += vc.shadow_rays;
    if (scene.plan().in_scattering && !c.maps.volume.empty())
        v.radiance += volume_map_radiance(c, segment, rng);
    return v;
}

}  // namespace

Rgb global_map_radiance(const PhotonRenderContext& context, const SurfaceHit& hit, const Vec3& wo) {
    const auto* phong = std::get_if<PhongMaterial>(&context.scene.desc().materials[hit.material]);
    if (phong == nullptr)
        return Rgb(0.0f);
    return map_radiance(context, context.maps.global, *phong, hit, wo);
}

Rgb volume_map_radiance(const PhotonRenderContext& c, const Ray& segment, Pcg32& rng) {
    const MediumSet& media = c.scene.media();
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(segment, segments);
    const float h = c.scene.desc().render.volume.step_m;
    const Vec3 wo = -segment.direction;
    Rgb radiance(0.0f);
    VolumeCounters vc;
    march_walk(media, segment, h, rng.next_float(), segments, false, vc,
               [&](float, const Vec3& x, const PointCoefficients& k, uint32_t mask,
                   const glm::dvec3& depth) {
                   const Rgb t_camera(glm::exp(-depth));
                   if (max_component(t_camera) < kTailTransmittance)
                       return false;
                   if (is_black(k.sigma_s))
                       return true;
                   // Photons carry the flux they scatter (σ_s folded in): the estimate needs
                   // the phase function alone, the mixture's σ_s-weighted one over σ_s.
                   const Rgb inv_sigma_s(k.sigma_s.r > 0.0f ? 1.0f / k.sigma_s.r : 0.0f,
                                         k.sigma_s.g > 0.0f ? 1.0f / k.sigma_s.g : 0.0f,
                                         k.sigma_s.b > 0.0f ? 1.0f / k.sigma_s.b : 0.0f);
                   const Rgb in_scattered = volume_estimate(
                       c.maps.volume, x, c.settings.k, c.settings.max_radius_m, PhotonFilter::Box,
                       scratch(), [&](const Vec3& wi) {
                           return media.scattering(x, mask, scattering_cosine(wo, wi)) *
                                  inv_sigma_s;
                       });
                   radiance += h * t_camera * in_scattered;
                   return true;
               });
    return radiance;
}

Rgb photon_ray_radiance(const PhotonRenderContext& c, const Ray& ray, Pcg32& rng,
                        RenderCounters& counters, int depth, float weight) {
    Rgb surface = c.scene.desc().background;
    float t_end = ray.t_max;
    if (const SurfaceScene* surfaces = c.scene.surfaces()) {
        if (const auto hit = surfaces->intersect(ray)) {
            t_end = hit->t;
            surface = shade(c, ray, *hit, rng, counters, depth, weight);
        }
    }
    if (!c.scene.plan().volume)
        return surface;
    Ray segment = ray;
    segment.t_max = t_end;
    const VolumeResult v = photon_volume(c, segment, rng, counters);
    return v.radiance + v.transmittance * surface;
}

PixelSample trace_photon_camera_ray(const PhotonRenderContext& c, const Ray& ray, Pcg32& rng,
                                    RenderCounters& counters) {
    ++counters.camera_rays;
    PixelSample sample;
    float t_end = ray.t_max;
    if (const SurfaceScene* surfaces = c.scene.surfaces()) {
        if (const auto hit = surfaces->intersect(ray)) {
            ++counters.surface_hits;
            sample.hit = true;
            t_end = hit->t;
            sample.depth = hit->t * glm::dot(ray.direction, c.scene.camera().forward());
            sample.albedo = albedo(c.scene.desc().materials[hit->material]);
            sample.surface = shade(c, ray, *hit, rng, counters, 0, 1.0f);
        }
    }
    if (!sample.hit)
        sample.surface = c.scene.desc().background;
    if (c.scene.plan().volume) {
        Ray segment = ray;
        segment.t_max = t_end;
        const VolumeResult v = photon_volume(c, segment, rng, counters);
        sample.volume = v.radiance;
        sample.transmittance = v.transmittance;
    }
    sample.radiance = sample.volume + sample.transmittance * sample.surface;
    return sample;
}

}  // namespace kasumi
