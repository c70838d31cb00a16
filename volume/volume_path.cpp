#include "volume/volume_path.h"

#include "volume/light_cache.h"
#include "volume/march_walk.h"
#include "volume/transmittance.h"

#include <optional>

namespace kasumi {

/// scattered_direct for one light (`step`: the march step, metres).
Rgb scattered_direct_one(const MediumSet& media, const Light& light, size_t light_index,
                         const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                         const Vec3& wo, const VolumeSettings& settings, float step, Pcg32& rng,
                         VolumeCounters& counters);

namespace {

/// The marched single scattering stops once every channel's camera transmittance is below this:
/// the light left out is at most this fraction of what the rest of the ray could add.
constexpr float kTailTransmittance = 1e-4f;
/// Paths play Russian roulette from this many scattering events on.
constexpr int kRouletteDepth = 3;

bool blocked(const OcclusionQuery* occlusion, const Vec3& x, const IncidentLight& in,
             VolumeCounters& counters) {
    if (occlusion == nullptr)
        return false;
    ++counters.shadow_rays;
    return in.distance >= kInfinity ? occlusion->occluded_direction(x, in.wi)
                                    : occlusion->occluded(x, in.light_position);
}

/// exp(-depth) per channel; one exp when every medium's extinction is grey (equal channels).
Rgb camera_transmittance(const glm::dvec3& depth, bool grey) {
    if (grey)
        return Rgb(std::exp(-static_cast<float>(depth.x)));
    return Rgb(glm::exp(-depth));
}

/// What one light contributes at x once its incident light `in` and the phase-weighted
/// scattering `f` are known: f E T V, with V from `occlusion` and T from the light cache (when
/// `cache` is given and covers x: `cached`) or the transmittance estimator.
Rgb light_term(const MediumSet& media, const Light& light, const OcclusionQuery* occlusion,
               const Vec3& x, const IncidentLight& in, const Rgb& f,
               const std::optional<Rgb>& cached, const VolumeSettings& settings, float step,
               Pcg32& rng, VolumeCounters& counters) {
    if (is_black(f) || (light.shadows != ShadowMode::None && blocked(occlusion, x, in, counters)))
        return Rgb(0.0f);
    if (cached)
        return f * in.irradiance * *cached;
    const Ray shadow{x, in.wi, 0.0f, in.distance >= kInfinity ? kInfinity : in.distance};
    return f * in.irradiance *
           estimate_transmittance(media, shadow, settings.estimator, step, rng, counters);
}

/// Per-ray constants of one light for the marched single scattering: a directional light's
/// incident light and scattering cosine are the same at every node, and its cached
/// transmittance is read along the ray's lattice line (no transform per node).
struct MarchLight {
    size_t index = 0;
    bool directional = false;
    IncidentLight incident;
    float mu = 0.0f;
    const LightTransmittanceCache* cache = nullptr;
    LightTransmittanceCache::Line line;
};

VolumeResult march_single(const MediumSet& media, const std::vector<Light>& lights,
                          const OcclusionQuery* occlusion, const Ray& ray,
                          const VolumeSettings& settings, Pcg32& rng, VolumeCounters& counters) {
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
    VolumeResult result;
    if (segments.empty())
        return result;
    const float h = march_step_m(media, settings);
    const Vec3 wo = -ray.direction;
    const bool grey = media.grey_extinction();
    thread_local std::vector<MarchLight> march_lights;
    march_lights.clear();
    for (size_t i = 0; i < lights.size(); ++i) {
        MarchLight m;
        m.index = i;
        if (std::holds_alternative<DirectionalLight>(lights[i].emitter)) {
            // A delta light at infinity: the same incident light everywhere (no random number).
            m.directional = true;
            m.incident = sample_incident(lights[i], ray.origin, rng);
            if (is_black(m.incident.irradiance))
                continue;
            m.mu = scattering_cosine(wo, m.incident.wi);
            if (settings.light_cache) {
                m.cache = media.light_cache(i, lights[i]);
                if (m.cache != nullptr)
                    m.line = m.cache->line(ray.origin, ray.direction);
            }
        }
        march_lights.push_back(m);
    }
    // Each node stands for a step h: with the offset uniform per ray, sum h f(t_i) is an
    // unbiased estimate of the integral of f for a given T; T itself is the trapezoid's.
    const glm::dvec3 tau = march_walk(
        media, ray, h, rng.next_float(), segments, false, counters,
        [&](float t, const Vec3& x, const PointCoefficients& k, uint32_t mask,
            const glm::dvec3& depth) {
            const Rgb t_camera = camera_transmittance(depth, grey);
            if (max_component(t_camera) < kTailTransmittance)
                return false;
            if (media.emits())
                result.radiance += (h * t_camera) * media.emission(x, mask);
            if (is_black(k.sigma_s))
                return true;
            ++counters.steps;
            Rgb direct(0.0f);
            for (const MarchLight& m : march_lights) {
                const Light& light = lights[m.index];
                if (!m.directional) {
                    direct += scattered_direct_one(media, light, m.index, occlusion, x, mask, wo,
                                                   settings, h, rng, counters);
                    continue;
                }
                // One medium in the mask: its sigma_s is k's (no second lookup).
                if ((mask & (mask - 1)) != 0)
                    ++counters.density_lookups;
                const Rgb f = media.scattering(k, x, mask, m.mu);
                const std::optional<Rgb> cached =
                    m.cache != nullptr ? m.cache->transmittance(m.line, t) : std::nullopt;
                direct += light_term(media, light, occlusion, x, m.incident, f, cached, settings, h,
                                     rng, counters);
            }
            result.radiance += (h * t_camera) * direct;
            return true;
        });
    result.transmittance = camera_transmittance(tau, grey);
    return result;
}

Rgb path_radiance(const MediumSet& media, const std::vector<Light>& lights,
                  const OcclusionQuery* occlusion, const PathEnvironment* environment,
                  const Ray& camera_segment, const VolumeSettings& settings, Pcg32& rng,
                  VolumeCounters& counters, Rgb* first_escape) {
    Rgb radiance(0.0f), throughput(1.0f);
    Ray ray = camera_segment;
    for (int depth = 0;;) {
        const FreeFlight flight = sample_free_flight(media, ray, throughput, rng, counters);
        radiance += flight.emitted;
        throughput *= flight.weight;
        if (depth == 0 && first_escape != nullptr)
            *first_escape = flight.scattered ? Rgb(0.0f) : flight.weight;
        if (!flight.scattered) {
            // The camera segment's own escape is composited by the caller (T * L_surface).
            if (depth > 0 && environment != nullptr && !is_black(throughput))
                radiance += throughput * environment->radiance(ray, rng);
            break;
        }
        ++counters.scattering_events;
        const Vec3 wo = -ray.direction;
        radiance += throughput * scattered_direct(media, lights, occlusion, flight.position,
                                                  flight.media_mask, wo, settings, rng, counters);
        if (settings.integrator == VolumeIntegrator::Single || ++depth >= settings.max_depth)
            break;
        const float u_pick = rng.next_float();
        const MixtureSample next = media.sample_scattering(flight.position, flight.media_mask, wo,
                                                           u_pick, rng.next_vec2());
        if (!(next.pdf > 0.0f))
            break;
        throughput *= next.scattering / next.pdf;
        if (depth >= kRouletteDepth) {
            const float survive = std::min(1.0f, max_component(throughput));
            if (!(rng.next_float() < survive))
                break;
            throughput /= survive;
        }
        ray = Ray{flight.position, next.wi, 0.0f, kInfinity};
        if (environment != nullptr)
            ray.t_max = environment->surface_distance(ray);
    }
    return radiance;
}

}  // namespace

Rgb scattered_direct_one(const MediumSet& media, const Light& light, size_t light_index,
                         const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                         const Vec3& wo, const VolumeSettings& settings, float step, Pcg32& rng,
                         VolumeCounters& counters) {
    // One sample per light: exact for delta lights, unbiased for extended ones (irradiance at
    // normal incidence over the pdf; no cosine inside a medium).
    const IncidentLight in = sample_incident(light, x, rng);
    if (is_black(in.irradiance))
        return Rgb(0.0f);
    const Rgb f = media.scattering(x, media_mask, scattering_cosine(wo, in.wi));
    ++counters.density_lookups;
    std::optional<Rgb> cached;
    if (settings.light_cache && !is_black(f)) {
        if (const LightTransmittanceCache* cache = media.light_cache(light_index, light))
            cached = cache->transmittance(x);
    }
    return light_term(media, light, occlusion, x, in, f, cached, settings, step, rng, counters);
}

Rgb scattered_direct(const MediumSet& media, const std::vector<Light>& lights,
                     const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                     const Vec3& wo, const VolumeSettings& settings, Pcg32& rng,
                     VolumeCounters& counters) {
    const float step = march_step_m(media, settings);
    Rgb total(0.0f);
    for (size_t light_index = 0; light_index < lights.size(); ++light_index)
        total += scattered_direct_one(media, lights[light_index], light_index, occlusion, x,
                                      media_mask, wo, settings, step, rng, counters);
    return total;
}

VolumeResult integrate_media(const MediumSet& media, const std::vector<Light>& lights,
                             const OcclusionQuery* occlusion, const PathEnvironment* environment,
                             const Ray& ray, const VolumeSettings& settings, bool in_scatter,
                             Pcg32& rng, VolumeCounters& counters, bool nothing_behind) {
    // Emitting media add light along the ray even when nothing scatters.
    in_scatter = in_scatter || media.emits();
    const bool marched_single =
        settings.estimator == Estimator::March && settings.integrator == VolumeIntegrator::Single;
    if (in_scatter && marched_single) {
        if (media.all_homogeneous())
            return integrate_volume(media, lights, occlusion, ray, settings, true, rng, counters);
        return march_single(media, lights, occlusion, ray, settings, rng, counters);
    }
    VolumeResult result;
    if (in_scatter && nothing_behind) {
        // T only feeds the transmittance AOV here: the first free flight's escape weight is an
        // unbiased estimate of it, so no separate walk through the media is needed.
        result.radiance = path_radiance(media, lights, occlusion, environment, ray, settings, rng,
                                        counters, &result.transmittance);
        return result;
    }
    result.transmittance = estimate_transmittance(media, ray, settings.estimator,
                                                  march_step_m(media, settings), rng, counters);
    if (in_scatter) {
        result.radiance = path_radiance(media, lights, occlusion, environment, ray, settings, rng,
                                        counters, nullptr);
    }
    return result;
}

}  // namespace kasumi
