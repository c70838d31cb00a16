#include "volume/debiased_march_single.h"

#include "volume/debiased_exp.h"
#include "volume/light_cache.h"
#include "volume/march_lights.h"
#include "volume/march_walk.h"
#include "volume/scattered_direct.h"
#include "volume/transmittance.h"
#include "volume/unbiased_march.h"

#include <array>
#include <cmath>
#include <optional>

namespace kasumi {

namespace {

/// The camera depth (T = 1e-4) at which the tail roulette first plays, and the depth between
/// later rounds (ln 10: the pivot's transmittance falls tenfold between rounds).
constexpr double kTailDepth = 9.210340371976184;
constexpr double kTailRound = 2.302585092994046;
/// Survival probability of each tail round (the survivor's weight is its inverse).
constexpr float kTailSurvival = 0.1f;

double min_component(const DVec3& v) {
    return std::min(v.x, std::min(v.y, v.z));
}

}  // namespace

std::optional<VolumeResult> debiased_march_single(const MediumSet& media,
                                                  const std::vector<Light>& lights,
                                                  const OcclusionQuery* occlusion, const Ray& ray,
                                                  const VolumeSettings& settings, Pcg32& rng,
                                                  VolumeCounters& counters) {
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
    VolumeResult result;
    if (segments.empty())
        return result;
    // An endless segment has no march (march_walk stops at it): such rays (unbounded fog) take
    // the trackers instead.
    if (!(segments.back().t1 < kInfinity))
        return std::nullopt;
    thread_local ResidualMarch camera;
    if (!camera.build(segments))
        return std::nullopt;
    const float h =
        bounded_march_step(march_step_m(media, settings), march_extent(segments), counters);
    const Vec3 wo = -ray.direction;
    thread_local std::vector<MarchLight> march_lights;
    collect_march_lights(media, lights, ray, true, rng, march_lights);
    // The camera corrections: N_cam running residual marches (usually none).
    const SeriesRoulette camera_law;
    const int camera_order = camera_law.sample(rng.next_float());
    std::array<ResidualMarch::Prefix, kMaxSeriesOrder> prefixes;
    std::array<DVec3, kMaxSeriesOrder> tau_hat;
    const int corrections = camera.exact() ? 0 : camera_order;
    // The correction marches at least as dense as the primary one (its step over the varying
    // stretches): their noise, not the trapezoid's error, is what the roulette's 1/P(N >= 1)
    // amplifies. (Kettunen et al.'s fitted count alone measured 1.5% more noise.)
    const int camera_nodes = std::max(
        unbiased_march_nodes(camera.residual_bound()),
        static_cast<int>(std::min(std::ceil(camera.varying_length() / h), kMaxMarchSteps)));
    for (int j = 0; j < corrections; ++j)
        prefixes[j] = camera.start_prefix(camera_nodes, rng.next_float());
    const RayMediaQuery query(media, ray);
    const bool grey = media.grey_extinction();
    const auto camera_transmittance = [&](float t, const DVec3& pivot) {
        if (corrections == 0)
            return grey ? Rgb(static_cast<float>(std::exp(-pivot.x))) : Rgb(glm::exp(-pivot));
        for (int j = 0; j < corrections; ++j)
            tau_hat[j] = camera.prefix(media, query, prefixes[j], t, counters);
        return Rgb(debiased_exp_about(pivot, tau_hat.data(), corrections, camera_law));
    };
    float weight = 1.0f;  // 1 / the tail roulette's survival so far
    double cut = kTailDepth;
    bool ended = false;
    const DVec3 tau = march_walk(
        media, ray, h, rng.next_float(), segments, false, counters,
        [&](float t, const Vec3& x, const PointCoefficients& k, uint32_t mask, const DVec3& depth) {
            if (min_component(depth) > cut) {
                if (!(rng.next_float() < kTailSurvival)) {
                    ended = true;
                    return false;
                }
                weight /= kTailSurvival;
                cut += kTailRound;
            }
            const bool emits = media.emits();
            if (is_black(k.sigma_s) && !emits)
                return true;
            const Rgb t_camera = weight * camera_transmittance(t, depth);
            if (emits)
                result.radiance += (h * t_camera) * media.emission(x, mask);
            if (is_black(k.sigma_s))
                return true;
            ++counters.steps;
            const Rgb direct = march_node_light(
                media, lights, march_lights, occlusion, x, k, mask, wo, settings, h, rng, counters,
                [&](const MarchLight& m, const Rgb& f) {
                    const Light& light = lights[m.index];
                    float integral = 0.0f;
                    if (m.cache == nullptr || is_black(f) ||
                        !m.cache->density_integral(m.line, t, integral))
                        return light_term(media, light, occlusion, x, m.incident, f, std::nullopt,
                                          settings, h, rng, counters);
                    if (light.shadows != ShadowMode::None &&
                        light_blocked(occlusion, x, m.incident, counters))
                        return Rgb(0.0f);
                    const DVec3 pivot =
                        static_cast<double>(integral) * DVec3(m.cache->sigma_t_per_density());
                    const Ray shadow{x, m.incident.wi, 0.0f, kInfinity};
                    // A set with a light cache is one bounded grid: its shadow rays always march.
                    const std::optional<Rgb> t_light =
                        unbiased_march_about(media, shadow, pivot, rng, counters);
                    return f * m.incident.irradiance *
                           (t_light ? *t_light
                                    : estimate_transmittance(media, shadow, settings.estimator, h,
                                                             rng, counters));
                });
            result.radiance += (h * t_camera) * direct;
            return true;
        });
    if (ended) {
        result.transmittance = Rgb(0.0f);
    } else {
        result.transmittance = weight * camera_transmittance(ray.t_max, tau);
    }
    return result;
}

}  // namespace kasumi
