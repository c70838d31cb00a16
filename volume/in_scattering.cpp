#include "volume/in_scattering.h"

#include "volume/equiangular.h"
#include "volume/gauss_interpolant.h"
#include "volume/march_walk.h"
#include "volume/shadow_intervals.h"

#include <array>
#include <cmath>

namespace kasumi {

namespace {

constexpr float kTailTransmittance = 1e-6f;

/// Unshadowed light from one light scattered toward wo at x, per unit length:
/// sigma_s p(mu) E T_light, with the incident light a shadow ray must test.
struct LightContribution {
    Rgb value{0.0f};
    IncidentLight incident;
    bool casts_shadows = true;
};

/// Extended lights contribute through one sample of a point on them (an unbiased estimate).
LightContribution unshadowed(const MediumSet& media, const MediumInterval& interval,
                             const Light& light, const Vec3& x, const Vec3& wo, Pcg32& rng) {
    LightContribution c;
    c.incident = sample_incident(light, x, rng);
    // Media test map and shadow-volume lights with shadow rays too (docs/lights.md).
    c.casts_shadows = light.shadows != ShadowMode::None;
    if (is_black(c.incident.irradiance))
        return c;
    const Rgb scatter = media.scattering(interval, scattering_cosine(wo, c.incident.wi));
    if (is_black(scatter))
        return c;
    const bool to_infinity = c.incident.distance >= kInfinity;
    const Ray shadow{x, c.incident.wi, 0.0f, to_infinity ? kInfinity : c.incident.distance};
    c.value = scatter * c.incident.irradiance * media.transmittance(shadow);
    return c;
}

bool blocked(const OcclusionQuery* occlusion, const Vec3& x, const LightContribution& c,
             VolumeCounters& counters) {
    if (occlusion == nullptr || !c.casts_shadows)
        return false;
    const IncidentLight& in = c.incident;
    ++counters.shadow_rays;
    return in.distance >= kInfinity ? occlusion->occluded_direction(x, in.wi)
                                    : occlusion->occluded(x, in.light_position);
}

/// Light scattered toward wo at x per unit length, sum over lights of sigma_s p E T_light V:
/// exactly with a shadow ray per light, or by picking one light with probability proportional
/// to its unshadowed luminance (unbiased; only the visibility is then estimated).
Rgb source(const MediumSet& media, const MediumInterval& interval,
           const std::vector<const Light*>& lights, const OcclusionQuery* occlusion, const Vec3& x,
           const Vec3& wo, LightSampling sampling, float u, Pcg32& rng, VolumeCounters& counters) {
    constexpr size_t kMaxStackLights = 16;
    if (sampling == LightSampling::All || lights.size() == 1 || lights.size() > kMaxStackLights) {
        Rgb total(0.0f);
        for (const Light* light : lights) {
            const LightContribution c = unshadowed(media, interval, *light, x, wo, rng);
            if (is_black(c.value) || blocked(occlusion, x, c, counters))
                continue;
            total += c.value;
        }
        return total;
    }
    LightContribution contributions[kMaxStackLights];
    float weights[kMaxStackLights];
    float total_weight = 0.0f;
    for (size_t i = 0; i < lights.size(); ++i) {
        contributions[i] = unshadowed(media, interval, *lights[i], x, wo, rng);
        weights[i] = std::max(luminance(contributions[i].value), 0.0f);
        total_weight += weights[i];
    }
    if (!(total_weight > 0.0f))
        return Rgb(0.0f);
    // Pick light i with probability weights[i] / total_weight by walking the CDF with u.
    // Rounding can leave target past the last bin: fall back to the last light with weight.
    float target = u * total_weight;
    size_t chosen = 0;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (weights[i] == 0.0f)
            continue;
        chosen = i;
        if (target < weights[i])
            break;
        target -= weights[i];
    }
    const LightContribution& c = contributions[chosen];
    if (blocked(occlusion, x, c, counters))
        return Rgb(0.0f);
    return c.value * (total_weight / weights[chosen]);
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
        if (interval.sigma_s[c] > 0.0f)
            t = std::max(t, transmittance[c]);
    }
    return t;
}

/// F(theta) of point_light_scattering without visibility, at the point x a shadow ray starts
/// from.
struct AirlightSample {
    Rgb f{0.0f};
    Vec3 x{0.0f};
};

/// One point light's share of point_light_scattering over one equiangular segment, with an
/// N-node interpolant; returns the integral over theta (the caller applies t_start).
template <int N>
Rgb point_light_segment(const MediumSet& media, const MediumInterval& interval,
                        const PointLight& light, bool casts_shadows,
                        const OcclusionQuery* occlusion, const Ray& ray,
                        const EquiangularSegment& segment, float t0, int samples,
                        int shadow_intervals, Pcg32& rng, VolumeCounters& counters) {
    const Vec3 wo = -ray.direction;
    // I / r² times dt/dtheta = d / cos² theta is I / d: r = d / cos theta.
    const Rgb intensity_over_d = light.intensity / segment.d;
    auto point_at = [&](float theta, Vec3& x) {
        const float t = segment.delta + segment.d * std::tan(theta);
        x = ray.at(t);
        return t;
    };
    auto integrand = [&](float theta) {
        AirlightSample s;
        const float t = point_at(theta, s.x);
        if (!std::isfinite(t))
            return s;
        const Vec3 to_light = light.position - s.x;
        const float r2 = glm::dot(to_light, to_light);
        if (!(r2 > 1e-12f))  // as point_source_incident: no light from 1 µm away
            return s;
        const float r = std::sqrt(r2);
        const Vec3 wi = to_light / r;
        const Rgb scatter = media.scattering(interval, scattering_cosine(wo, wi));
        if (is_black(scatter))
            return s;
        // Camera transmittance from t0 and the light's through every medium, one exp.
        const Rgb tau = media.optical_depth(Ray{s.x, wi, 0.0f, r}) + interval.sigma_t * (t - t0);
        const Rgb transmittance =
            tau.r == tau.g && tau.g == tau.b ? Rgb(std::exp(-tau.r)) : exp_neg(tau);
        s.f = scatter * intensity_over_d * transmittance;
        return s;
    };
    auto visible = [&](const Vec3& x) {
        if (occlusion == nullptr || !casts_shadows)
            return true;
        ++counters.shadow_rays;
        return !occlusion->occluded(x, light.position);
    };

    std::array<Rgb, N> at_nodes;
    for (int k = 0; k < N; ++k) {
        at_nodes[k] =
            integrand(GaussLegendreInterpolantN<N>::node(k, segment.theta_a, segment.theta_b)).f;
    }
    counters.steps += N;
    GaussLegendreInterpolantN<N> control;
    control.set(segment.theta_a, segment.theta_b, at_nodes);
    const float span = segment.theta_b - segment.theta_a;

    if (shadow_intervals > 0 && occlusion != nullptr && casts_shadows) {
        return lit_interval_integral(control, segment.theta_a, segment.theta_b, shadow_intervals,
                                     [&](float theta) {
                                         Vec3 x;
                                         point_at(theta, x);
                                         return visible(x);
                                     });
    }
    const float u = rng.next_float();
    Rgb residual(0.0f);
    for (int j = 0; j < samples; ++j) {
        const float theta =
            segment.theta_a + span * ((static_cast<float>(j) + u) / static_cast<float>(samples));
        ++counters.steps;
        const AirlightSample s = integrand(theta);
        residual -= control(theta);
        if (!is_black(s.f) && visible(s.x))
            residual += s.f;
    }
    return control.integral() + span * residual / static_cast<float>(samples);
}

/// Point lights' single scattering over [t0, t1] of a stretch by stratified equiangular
/// sampling with a control variate: `budget` shadow-ray samples shared among the lights in
/// proportion to their unattenuated inverse-square integrals (at least one each).
///
/// In the equiangular angle theta (t = delta + d tan theta, dt/dtheta = d / cos² theta) the
/// integrand F(theta) = T(t) sigma_s p E T_light dt/dtheta, T(t) = t_start exp(-sigma_t (t - t0))
/// the camera transmittance, is smooth without its visibility V: the inverse square cancels.
/// Its polynomial interpolant P at 8 Gauss-Legendre nodes (no shadow rays) has the exact
/// integral G (gauss_interpolant.h), and the estimate
///   G + (theta_b - theta_a) / N sum_j [F(theta_j) V(theta_j) - P(theta_j)]
/// over N stratified uniform angles is unbiased for ∫ F V dtheta whatever P is. Where the
/// stretch is all lit, F - P is only the interpolation error and the estimate almost exact
/// (tests/volume/airlight_control_test.cpp: spread below 1e-3 of the mean); the shadow rays
/// then only estimate the light the shadows take away. The control is the unshadowed airlight
/// of Sun et al. 2005 ("A Practical Analytic Single Scattering Model for Real Time Rendering"),
/// integrated numerically so that any phase function and lights outside the fog are exact.
/// Where every sample is shadowed the estimate can be slightly negative (unbiased).
/// With settings.shadow_intervals > 0 the shadow-ray samples are replaced by the lit
/// intervals (lit_interval_integral): deterministic and biased, bounds in shadow_intervals.h.
Rgb point_light_scattering(const MediumSet& media, const MediumInterval& interval,
                           const std::vector<const Light*>& point_lights,
                           const OcclusionQuery* occlusion, const Ray& ray, float t0, float t1,
                           const Rgb& t_start, int budget, const VolumeSettings& settings,
                           Pcg32& rng, VolumeCounters& counters) {
    constexpr size_t kMaxLights = 64;
    const size_t n = std::min(point_lights.size(), kMaxLights);
    EquiangularSegment segments[kMaxLights];
    float weights[kMaxLights];
    float total = 0.0f;
    for (size_t i = 0; i < n; ++i) {
        const auto& light = std::get<PointLight>(point_lights[i]->emitter);
        segments[i] = make_equiangular(ray.origin, ray.direction, light.position, t0, t1);
        weights[i] = luminance(light.intensity) * segments[i].inverse_square_integral();
        total += weights[i];
    }
    Rgb radiance(0.0f);
    if (!(total > 0.0f))
        return radiance;
    for (size_t i = 0; i < n; ++i) {
        if (!(weights[i] > 0.0f))
            continue;
        const EquiangularSegment& segment = segments[i];
        const PointLight& light = std::get<PointLight>(point_lights[i]->emitter);
        const bool casts_shadows = point_lights[i]->shadows != ShadowMode::None;
        const int samples = std::max(1, static_cast<int>(std::lround(budget * weights[i] / total)));
        const Rgb integral = point_light_segment<GaussLegendreInterpolant::kNodes>(
            media, interval, light, casts_shadows, occlusion, ray, segment, t0, samples,
            settings.shadow_intervals, rng, counters);
        radiance += t_start * integral;
    }
    return radiance;
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
    // Point lights are sampled equiangularly; the march gathers the other lights.
    thread_local std::vector<const Light*> marched, point_lights;
    marched.clear();
    point_lights.clear();
    for (const Light& light : lights) {
        (std::holds_alternative<PointLight>(light.emitter) ? point_lights : marched)
            .push_back(&light);
    }
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
            if (!(march_length > 0.0f) || !(march_length < kInfinity))
                march_length = 0.0f;
            // At most kMaxMarchSteps per stretch (counted when the step had to be lengthened);
            // in double, as march_length / step_m can exceed every int (step_m = 1e-30).
            double steps_wanted = std::ceil(static_cast<double>(march_length) / settings.step_m);
            if (steps_wanted > kMaxMarchSteps) {
                steps_wanted = kMaxMarchSteps;
                ++counters.bounded_marches;
            }
            const auto n_steps = static_cast<int>(steps_wanted);
            // n_steps is 0 when nothing is left to see through.
            const float dt = march_length / static_cast<float>(std::max(n_steps, 1));
            // Distances within a step are drawn from exp(-sigma_bar s) truncated to [0, dt].
            // Only the marched (non-point) lights use them.
            if (!marched.empty() && n_steps > 0) {
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
                const Rgb t_step = exp_neg(interval.sigma_t * dt);
                for (int i = 0; i < n_steps; ++i) {
                    const float t = interval.t0 + static_cast<float>(i) * dt + s;
                    const Rgb src =
                        source(media, interval, marched, occlusion, ray.at(t), wo,
                               settings.light_sampling, rng.next_float(), rng, counters);
                    ++counters.steps;
                    result.radiance += t_step_start * t_within * src / pdf;
                    t_step_start *= t_step;
                }
            }
            if (!point_lights.empty() && n_steps > 0) {
                result.radiance += point_light_scattering(
                    media, interval, point_lights, occlusion, ray, interval.t0,
                    interval.t0 + march_length, transmittance, n_steps, settings, rng, counters);
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
