#include "volume/in_scattering.h"

#include <cmath>

namespace kasumi {

namespace {

constexpr float kTailTransmittance = 1e-6f;

/// Light scattered toward -ray.direction at x, per unit length: sum over lights of
/// sigma_s p(mu) E T_light V.
Rgb source(const MediumSet& media, const MediumInterval& interval, const std::vector<Light>& lights,
           const OcclusionQuery* occlusion, const Vec3& x, const Vec3& wo,
           VolumeCounters& counters) {
    Rgb total(0.0f);
    for (const Light& light : lights) {
        const IncidentLight in = incident_light(light, x);
        if (is_black(in.irradiance))
            continue;
        const Rgb scatter = media.scattering(interval, scattering_cosine(wo, in.wi));
        if (is_black(scatter))
            continue;
        const bool to_infinity = in.distance >= kInfinity;
        Ray shadow{x, in.wi, 0.0f, to_infinity ? kInfinity : in.distance};
        const Rgb t_light = media.transmittance(shadow);
        if (is_black(t_light))
            continue;
        if (occlusion != nullptr) {
            ++counters.shadow_rays;
            const bool blocked = to_infinity ? occlusion->occluded_direction(x, in.wi)
                                             : occlusion->occluded(x, in.light_position);
            if (blocked)
                continue;
        }
        total += scatter * in.irradiance * t_light;
    }
    return total;
}

/// Smallest extinction among channels that scatter (those channels carry in-scattered light).
float min_scattering_extinction(const MediumInterval& interval) {
    float sigma = kInfinity;
    for (int c = 0; c < 3; ++c) {
        if (interval.sigma_s[c] > 0.0f)
            sigma = std::min(sigma, interval.sigma_t[c]);
    }
    return sigma;
}

/// Largest transmittance among scattering channels: the light they can still carry.
float max_scattering_transmittance(const MediumInterval& interval, const Rgb& transmittance) {
    float t = 0.0f;
    for (int c = 0; c < 3; ++c) {
        if (interval.sigma_s[c] > 0.0f) t = std::max(t, transmittance[c]);
    }
    return t;
}

}  // namespace

VolumeResult integrate_volume(const MediumSet& media, const std::vector<Light>& lights,
                              const OcclusionQuery* occlusion, const Ray& ray,
                              const VolumeSettings& settings, bool in_scatter, Pcg32& rng,
                              VolumeCounters& counters) {
    VolumeResult result;
    thread_local std::vector<MediumInterval> intervals;
    media.intervals(ray, intervals);
    const Vec3 wo = -ray.direction;
    const float u = rng.next_float();
    Rgb transmittance(1.0f);  // from the ray origin to the start of the current stretch
    for (const MediumInterval& interval : intervals) {
        const float length = interval.t1 - interval.t0;
        if (in_scatter && interval.scattering_mask != 0) {
            // Marching stops once the transmittance of every scattering channel, from the ray
            // origin, is below kTailTransmittance (an endless stretch seen toward the sky, or a
            // long optically thick one): the light left out is at most that fraction of the
            // single-scattered radiance a homogeneous continuation would add.
            const float sigma_min = min_scattering_extinction(interval);
            const float t_start = max_scattering_transmittance(interval, transmittance);
            float march_length = length;
            if (sigma_min > 0.0f && t_start > 0.0f) {
                march_length = std::min(length, std::log(t_start / kTailTransmittance) / sigma_min);
            }
            if (!(march_length > 0.0f) || !(march_length < kInfinity)) march_length = 0.0f;
            const auto n_steps = static_cast<int>(std::ceil(march_length / settings.step_m));
            // n_steps is 0 when nothing is left to see through.
            const float dt = march_length / static_cast<float>(std::max(n_steps, 1));
            // Distances within a step are drawn from exp(-sigma_bar s) truncated to [0, dt].
            const float sigma_bar =
                (interval.sigma_t.r + interval.sigma_t.g + interval.sigma_t.b) / 3.0f;
            const float mass = sigma_bar > 0.0f ? -std::expm1(-sigma_bar * dt) : 0.0f;
            float s, pdf;
            if (sigma_bar * dt > 1e-6f) {
                s = -std::log1p(-u * mass) / sigma_bar;
                pdf = sigma_bar * std::exp(-sigma_bar * s) / mass;
            } else {
                s = u * dt;
                pdf = 1.0f / dt;
            }
            Rgb t_step_start = transmittance;
            const Rgb t_within = exp_neg(interval.sigma_t * s);
            for (int i = 0; i < n_steps; ++i) {
                const float t = interval.t0 + static_cast<float>(i) * dt + s;
                const Rgb src = source(media, interval, lights, occlusion, ray.at(t), wo, counters);
                ++counters.steps;
                result.radiance += t_step_start * t_within * src / pdf;
                t_step_start *= exp_neg(interval.sigma_t * dt);
            }
        }
        for (int c = 0; c < 3; ++c) {
            if (interval.sigma_t[c] > 0.0f)
                transmittance[c] *= std::exp(-interval.sigma_t[c] * length);
        }
    }
    result.transmittance = transmittance;
    return result;
}

}  // namespace kasumi
