#include "volume/debiased_march_single.h"

#include "volume/debiased_exp.h"
#include "volume/light_cache.h"
#include "volume/march_grid_walk.h"
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

/// The series-order roulettes (debiased_exp_about; Kettunen et al.'s is {0.1, 2}). Measured on
/// the vdb_render bench cloud (docs/volumes.md, 3 voxels, 128² callgrind cost x 512² RMSE²):
/// corrections in 4 rays of 10 for the camera and in half the shadow rays, each shadow
/// correction mostly one march (c = 1), give variance x cost 0.050 against 0.163 for
/// {0.1, 2} / {0.1, 2} (both with stratified shadow orders): the corrections' variance goes as
/// 1/P(N >= 1), their cost as P(N >= 1), and at 0.1 the variance dominated.
constexpr SeriesRoulette kCameraRoulette{0.4, 2.0};
constexpr SeriesRoulette kShadowRoulette{0.5, 1.0};

/// The step between consecutive shadow rays' order uniforms along one camera ray (the golden
/// ratio's fractional part: a rank-1 lattice, so the corrected nodes are spread evenly).
constexpr float kOrderStep = 0.618034f;

/// The order uniform of the next node: v + kOrderStep mod 1 (uniform when v is).
float next_order_uniform(float v) {
    v += kOrderStep;
    return v >= 1.0f ? v - 1.0f : v;
}

double min_component(const DVec3& v) {
    return std::min(v.x, std::min(v.y, v.z));
}

/// The camera corrections of one ray: N_cam running residual marches (usually none), built only
/// when N_cam > 0 (the segment list and the marches' set-up cost nothing on the other rays).
struct CameraCorrections {
    SeriesRoulette law = kCameraRoulette;
    int count = 0;
    std::array<ResidualMarch::Prefix, kMaxSeriesOrder> prefixes;
    std::array<DVec3, kMaxSeriesOrder> tau_hat;

    /// Starts `order` marches over the ray's segments (none when every segment is constant:
    /// the trapezoid pivot is exact there); h the primary march's step.
    void start(const ResidualMarch& camera, int order, float h, Pcg32& rng) {
        count = camera.exact() ? 0 : order;
        // The correction marches at least as dense as the primary one (its step over the
        // varying stretches): their noise, not the trapezoid's error, is what the roulette's
        // 1/P(N >= 1) amplifies. (Kettunen et al.'s fitted count alone measured 1.5% more noise.)
        const int nodes = std::max(
            unbiased_march_nodes(camera.residual_bound()),
            static_cast<int>(std::min(std::ceil(camera.varying_length() / h), kMaxMarchSteps)));
        for (int j = 0; j < count; ++j)
            prefixes[j] = camera.start_prefix(nodes, rng.next_float());
    }
    /// T^_cam over [t_min, t) about the pivot depth (debiased_exp_about).
    Rgb transmittance(const ResidualMarch& camera, const MediumSet& media,
                      const RayMediaQuery& query, float t, const DVec3& pivot, bool grey,
                      VolumeCounters& counters) {
        if (count == 0)
            return grey ? Rgb(static_cast<float>(std::exp(-pivot.x))) : Rgb(glm::exp(-pivot));
        for (int j = 0; j < count; ++j)
            tau_hat[j] = camera.prefix(media, query, prefixes[j], t, counters);
        return Rgb(debiased_exp_about(pivot, tau_hat.data(), count, law));
    }
};

/// A directional light's term at node x with its cache's depth as the pivot: f E T^_l, T^_l by
/// unbiased_march_about with kShadowRoulette's order drawn from order_u (light_term where x is
/// off the cache's lattice).
Rgb cached_light_term(const MediumSet& media, const Light& light, const MarchLight& m,
                      const OcclusionQuery* occlusion, const Vec3& x, float t, const Rgb& f,
                      const VolumeSettings& settings, float h, float order_u, Pcg32& rng,
                      VolumeCounters& counters) {
    float integral = 0.0f;
    if (m.cache == nullptr || is_black(f) || !m.cache->density_integral(m.line, t, integral))
        return light_term(media, light, occlusion, x, m.incident, f, std::nullopt, settings, h, rng,
                          counters);
    if (light.shadows != ShadowMode::None && light_blocked(occlusion, x, m.incident, counters))
        return Rgb(0.0f);
    const DVec3 pivot = static_cast<double>(integral) * DVec3(m.cache->sigma_t_per_density());
    const Ray shadow{x, m.incident.wi, 0.0f, kInfinity};
    // A set with a light cache is one bounded grid: its shadow rays always march.
    const std::optional<Rgb> t_light =
        unbiased_march_about(media, shadow, pivot, kShadowRoulette, order_u, rng, counters);
    return f * m.incident.irradiance *
           (t_light ? *t_light
                    : estimate_transmittance(media, shadow, settings.estimator, h, rng, counters));
}

/// debiased_march_single for the common cloud: one grid medium, grey extinction, no emission,
/// every light directional with a light cache. The same estimator (nodes, pivots, corrections,
/// tail roulette) with the camera march walked along the grid's bricks (march_grid_nodes: the
/// nodes and trapezoid depth of march_walk, as the biased march's fast path), f per unit
/// density once per ray and light, and the segment list made only for a ray that draws camera
/// corrections. Returns false, having drawn no random number, when the case does not apply.
bool debiased_march_single_grid(const MediumSet& media, const std::vector<Light>& lights,
                                const OcclusionQuery* occlusion, const Ray& ray,
                                const VolumeSettings& settings, Pcg32& rng,
                                VolumeCounters& counters, VolumeResult& result) {
    const MediumSet::FastMedium* g = media.single_grid();
    if (g == nullptr || !media.grey_extinction() || media.emits() || lights.empty() ||
        lights.size() > MediumSet::kMaxCachedLights)
        return false;
    for (size_t i = 0; i < lights.size(); ++i)
        if (!std::holds_alternative<DirectionalLight>(lights[i].emitter) ||
            media.light_cache(i, lights[i]) == nullptr)
            return false;
    result = VolumeResult{};
    const auto span = g->bounds_world.clip(ray);
    const float sigma_t = g->sigma_t.r;  // per unit density, equal channels (grey)
    if (!span || g->grid->empty() || !(sigma_t > 0.0f))
        return true;
    thread_local std::vector<MarchLight> march_lights;
    collect_march_lights(media, lights, ray, true, rng, march_lights);
    // Per light: f per unit density (sigma_s p(mu)) and the order uniform of its next shadow
    // ray (stratified along the ray, next_order_uniform).
    std::array<Rgb, MediumSet::kMaxCachedLights> f_unit;
    std::array<float, MediumSet::kMaxCachedLights> order_u;
    for (size_t i = 0; i < march_lights.size(); ++i) {
        f_unit[i] = g->sigma_s * media.phase_value(0, march_lights[i].mu);
        order_u[i] = rng.next_float();
    }
    const float h = bounded_march_step(march_step_m(media, settings),
                                       static_cast<double>(span->second - span->first), counters);
    thread_local ResidualMarch camera;
    thread_local CameraCorrections corrections;
    const int order = corrections.law.sample(rng.next_float());
    corrections.count = 0;
    if (order > 0) {
        thread_local std::vector<MajorantSegment> segments;
        media.majorants(ray, segments);
        if (camera.build(segments))  // a grid's segments are bounded
            corrections.start(camera, order, h, rng);
    }
    const RayMediaQuery query(media, ray);
    const Vec3 o(g->world_to_index * Vec4(ray.origin, 1.0f));
    const Vec3 d(g->world_to_index * Vec4(ray.direction, 0.0f));
    float weight = 1.0f;  // 1 / the tail roulette's survival so far
    double cut = kTailDepth;
    uint64_t steps = 0;
    const GridMarch march = march_grid_nodes(
        *g->grid, o, d, span->first, span->second, ray.t_min, h, [&] { return rng.next_float(); },
        [&](float t, float rho, double depth, const BrickSpan&, const BrickRef&) {
            const double tau = static_cast<double>(sigma_t) * depth;
            if (tau > cut) {
                if (!(rng.next_float() < kTailSurvival))
                    return false;
                weight /= kTailSurvival;
                cut += kTailRound;
            }
            if (!(rho > 0.0f))
                return true;
            ++steps;
            const Vec3 x = ray.at(t);
            Rgb direct(0.0f);
            for (size_t i = 0; i < march_lights.size(); ++i) {
                direct += cached_light_term(media, lights[march_lights[i].index], march_lights[i],
                                            occlusion, x, t, rho * f_unit[i], settings, h,
                                            order_u[i], rng, counters);
                order_u[i] = next_order_uniform(order_u[i]);
            }
            const Rgb t_camera = weight * corrections.transmittance(camera, media, query, t,
                                                                    DVec3(tau), true, counters);
            result.radiance += (h * t_camera) * direct;
            return true;
        },
        [](const BrickSpan&, const BrickRef&) {});
    counters.density_lookups += march.lookups;
    counters.steps += steps;
    // A ray the tail roulette ended returns 0 (its weighted estimate at the end).
    result.transmittance = Rgb(0.0f);
    if (!march.stopped)
        result.transmittance =
            weight * corrections.transmittance(camera, media, query, ray.t_max,
                                               DVec3(static_cast<double>(sigma_t) * march.depth),
                                               true, counters);
    return true;
}

}  // namespace

std::optional<VolumeResult> debiased_march_single(const MediumSet& media,
                                                  const std::vector<Light>& lights,
                                                  const OcclusionQuery* occlusion, const Ray& ray,
                                                  const VolumeSettings& settings, Pcg32& rng,
                                                  VolumeCounters& counters) {
    VolumeResult result;
    if (debiased_march_single_grid(media, lights, occlusion, ray, settings, rng, counters, result))
        return result;
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
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
    thread_local std::vector<float> order_u;  // per light, as in the grid path
    order_u.clear();
    for (size_t i = 0; i < march_lights.size(); ++i)
        order_u.push_back(rng.next_float());
    thread_local CameraCorrections corrections;
    corrections.start(camera, corrections.law.sample(rng.next_float()), h, rng);
    const RayMediaQuery query(media, ray);
    const bool grey = media.grey_extinction();
    const auto camera_transmittance = [&](float t, const DVec3& pivot) {
        return corrections.transmittance(camera, media, query, t, pivot, grey, counters);
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
                    const size_t i = static_cast<size_t>(&m - march_lights.data());
                    const float u = order_u[i];
                    order_u[i] = next_order_uniform(u);
                    return cached_light_term(media, lights[m.index], m, occlusion, x, t, f,
                                             settings, h, u, rng, counters);
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
