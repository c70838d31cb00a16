#include "gi/photon/photon_render.h"

#include "core/sampling.h"
#include "gi/photon/photon_estimate.h"
#include "gi/photon/photon_shadow.h"
#include "render/integrator.h"
#include "render/whitted.h"
#include "surface/fresnel.h"
#include "surface/phong_brdf.h"
#include "volume/march_walk.h"
#include "volume/transmittance.h"
#include "volume/volume_path.h"

namespace kasumi {

namespace {

/// Below this camera transmittance the volume-map march stops (as the single-scattering march).
constexpr float kTailTransmittance = 1e-6f;
/// Specular bounces a final-gather ray follows through mirrors and glass to a Phong surface.
constexpr int kGatherSpecularDepth = 8;

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
                            [&](const Vec3& wi) { return eval(m, ns, wo, wi); });
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
        // Emissive surfaces are lit directly only through gathering (their photons are in
        // the maps, but shadow rays go to lights alone).
        const Rgb emitted = weight * emitted_radiance(material, *hit, wo);
        if (const auto* phong = std::get_if<PhongMaterial>(&material))
            return emitted + weight * map_radiance(c, c.maps.global, *phong, *hit, wo);
        if (!is_black(emitted))
            return emitted;  // a specular emitter: its own light dominates; the rest is cut
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
        sum += kPi * eval(m, ns, wo, wi) * l;
    }
    return sum / static_cast<float>(n);
}

}  // namespace

Rgb photon_phong_radiance(const PhotonRenderContext& c, const SurfaceHit& hit, const Vec3& wo,
                          Pcg32& rng, RenderCounters& counters) {
    const auto* m = std::get_if<PhongMaterial>(&c.scene.desc().materials[hit.material]);
    if (m == nullptr)
        return Rgb(0.0f);
    // Shadow photons decide, per light, where a shadow ray is needed at all.
    const KnownVisibility* known = nullptr;
    if (!c.maps.shadow.empty()) {
        thread_local std::vector<KnownVisibility> visibility;
        const size_t lights = c.scene.desc().lights.size();
        visibility.resize(lights);
        Vec3 ng, ns;
        face_normals(hit, wo, ng, ns);
        classify_shadow_photons(c.maps.shadow, hit.position, ng, c.settings.shadow_k,
                                c.settings.max_radius_m, lights, scratch(), visibility.data());
        known = visibility.data();
    }
    Rgb radiance = shade_surface(c.scene, hit, wo, rng, counters, known);
    radiance += map_radiance(c, c.maps.caustic, *m, hit, wo);
    if (c.settings.final_gather_samples > 0)
        radiance += final_gather(c, *m, hit, wo, rng);
    else
        radiance += map_radiance(c, c.maps.global, *m, hit, wo);
    return radiance;
}

Rgb volume_map_radiance(const PhotonRenderContext& c, const Ray& segment, Pcg32& rng) {
    const MediumSet& media = c.scene.media();
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(segment, segments);
    VolumeCounters vc;
    const float h =
        bounded_march_step(c.scene.desc().render.volume.step_m, march_extent(segments), vc);
    const Vec3 wo = -segment.direction;
    Rgb radiance(0.0f);
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

}  // namespace kasumi
