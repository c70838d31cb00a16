#include "volume/march_single.h"

#include "volume/equiangular.h"
#include "volume/light_cache.h"
#include "volume/march_grid_walk.h"
#include "volume/march_lights.h"
#include "volume/march_walk.h"
#include "volume/scattered_direct.h"
#include "volume/transmittance.h"

#include <cmath>
#include <new>
#include <optional>
#include <type_traits>

namespace kasumi {

namespace {

/// The marched single scattering stops once every channel's camera transmittance is below this:
/// the light left out is at most this fraction of what the rest of the ray could add.
constexpr float kTailTransmittance = 1e-4f;

/// exp(-depth) per channel; one exp when every medium's extinction is grey (equal channels).
Rgb camera_transmittance(const glm::dvec3& depth, bool grey) {
    if (grey)
        return Rgb(std::exp(-static_cast<float>(depth.x)));
    return Rgb(glm::exp(-depth));
}

/// A directional light's march record at RAY: its incident light (the same everywhere along the
/// ray: a delta light at infinity) and the scattering cosine toward WO. False when it sends no
/// light.
bool directional_march_light(const Light& light, size_t index, const Ray& ray, const Vec3& wo,
                             Pcg32& rng, MarchLight& m) {
    m.index = index;
    m.directional = true;
    m.incident = sample_incident(light, ray.origin, rng);
    if (is_black(m.incident.irradiance))
        return false;
    m.mu = scattering_cosine(wo, m.incident.wi);
    return true;
}

/// The camera optical depth at which the marched single scattering stops (kTailTransmittance).
const float kTailDepth = -std::log(kTailTransmittance);

/// march_single for the common cloud case: the set is one grid medium with grey extinction and
/// no emission, and every light is directional with a cached transmittance. Same estimator,
/// nodes and weights as march_walk (jittered grid, abutting bricks walked as one run with nodes
/// at the run's ends, trapezoid tau), but walked lazily along the grid's brick DDA (each lookup
/// reads the brick the walk names; nothing past the tail cut-off is walked, no segment list),
/// and with one exp per node and light: T_camera T_light = exp(-(tau + sigma_t D)), D the
/// cache's density integral toward the light. Returns false, having drawn no random number and
/// touched nothing, when the case does not apply.
bool march_single_grid(const MediumSet& media, const std::vector<Light>& lights,
                       const OcclusionQuery* occlusion, const Ray& ray,
                       const VolumeSettings& settings, Pcg32& rng, VolumeCounters& counters,
                       VolumeResult& result) {
    const MediumSet::FastMedium* g = media.single_grid();
    if (g == nullptr || !settings.light_cache || !media.grey_extinction() || media.emits() ||
        lights.empty() || lights.size() > MediumSet::kMaxCachedLights)
        return false;
    // A ray that misses the grid's box (about half the camera rays of the vdb_render bench)
    // sees nothing on either path (the general one finds no majorant segment and draws no
    // random number), so it is answered before the per-light checks.
    const auto span = g->bounds_world.clip(ray);
    if (!span) {
        result = VolumeResult{};
        return true;
    }
    const LightTransmittanceCache* caches[MediumSet::kMaxCachedLights];
    for (size_t i = 0; i < lights.size(); ++i) {
        if (!std::holds_alternative<DirectionalLight>(lights[i].emitter))
            return false;
        caches[i] = media.light_cache(i, lights[i]);
        if (caches[i] == nullptr)
            return false;
    }
    result = VolumeResult{};
    const float sigma_t = g->sigma_t.r;  // per unit density, equal channels (grey)
    if (g->grid->empty() || !(sigma_t > 0.0f))
        return true;
    // Per light and ray: f = sigma_s p(mu) per unit density, and f E (directional: the same at
    // every node; sample_incident draws no random number for a delta light).
    struct GridLight {
        const Light* light = nullptr;
        IncidentLight incident;
        Rgb f{0.0f};
        Rgb weight{0.0f};
        const LightTransmittanceCache* cache = nullptr;
        LightTransmittanceCache::Line line;
        bool blockable = false;
    };
    // Constructed only as lights are taken: a zeroed array of all eight cost more per ray than
    // the setup of the one light a cloud usually has (callgrind: 135 instructions per ray;
    // std::optional per element saved only a quarter of them).
    static_assert(std::is_trivially_destructible<GridLight>::value, "no destructor to run");
    union GridLights {
        GridLights() {}  // constructs no element
        GridLight at[MediumSet::kMaxCachedLights];
    } storage;
    GridLight* const grid_lights = storage.at;
    size_t n_lights = 0;
    const Vec3 wo = -ray.direction;
    for (size_t i = 0; i < lights.size(); ++i) {
        GridLight& m = *new (&grid_lights[n_lights]) GridLight;
        m.incident = sample_incident(lights[i], ray.origin, rng);
        if (is_black(m.incident.irradiance))
            continue;
        m.f = g->sigma_s * media.phase_value(0, scattering_cosine(wo, m.incident.wi));
        if (is_black(m.f))
            continue;  // the general path's light_term returns 0 before any shadow test
        m.light = &lights[i];
        m.weight = m.f * m.incident.irradiance;
        m.cache = caches[i];
        m.line = m.cache->line(ray.origin, ray.direction);
        m.blockable = occlusion != nullptr && lights[i].shadows != ShadowMode::None;
        ++n_lights;
    }
    // The same expressions as RayMediaQuery's, so both see the same index-space ray.
    const Vec3 o(g->world_to_index * Vec4(ray.origin, 1.0f));
    const Vec3 d(g->world_to_index * Vec4(ray.direction, 0.0f));
    const float h = bounded_march_step(march_step_m(media, settings),
                                       static_cast<double>(span->second - span->first), counters);
    uint64_t steps = 0;
    // The common cloud: one directional light, no surfaces to block it (sum of h rho T T_light
    // over the nodes, times the light's f E once).
    const GridLight* const single =
        n_lights == 1 && !grid_lights[0].blockable ? &grid_lights[0] : nullptr;
    float single_sum = 0.0f;
    // u drawn where the general path draws it: at the first brick (media ahead).
    const GridMarch march = march_grid_nodes(
        *g->grid, o, d, span->first, span->second, ray.t_min,
        h, [&]() __attribute__((always_inline)) { return rng.next_float(); },
        [&](float t, float rho, double depth, const BrickSpan&,
            const BrickRef&) __attribute__((always_inline)) {
            const float tau = sigma_t * static_cast<float>(depth);
            if (tau > kTailDepth)
                return false;
            if (!(rho > 0.0f) || n_lights == 0)
                return true;
            ++steps;
            if (single != nullptr) {
                // One light that nothing else can block, on its cache: no light loop, and its
                // weight applied once per ray (after the walk) instead of per node.
                float integral = 0.0f;
                if (single->cache->density_integral(single->line, t, integral)) {
                    single_sum += h * rho * std::exp(-(tau + sigma_t * integral));
                    return true;
                }
            }
            for (size_t i = 0; i < n_lights; ++i) {
                const GridLight& m = grid_lights[i];
                if (m.blockable && light_blocked(occlusion, ray.at(t), m.incident, counters))
                    continue;
                float integral = 0.0f;
                if (m.cache->density_integral(m.line, t, integral)) {
                    result.radiance += (h * rho * std::exp(-(tau + sigma_t * integral))) * m.weight;
                } else {
                    // Off the cached lattice: a shadow ray through the estimator, as
                    // light_term does (the occlusion test is done above).
                    result.radiance +=
                        (h * std::exp(-tau)) * light_term(media, *m.light, nullptr, ray.at(t),
                                                          m.incident, rho * m.f, std::nullopt,
                                                          settings, h, rng, counters);
                }
            }
            return true;
        },
        [](const BrickSpan&, const BrickRef&) {});
    if (single != nullptr)
        result.radiance += single_sum * single->weight;
    counters.density_lookups += march.lookups;
    counters.steps += steps;
    result.transmittance = Rgb(std::exp(-sigma_t * static_cast<float>(march.depth)));
    return true;
}

/// march_single for a set that is one height fog (volume/height_fog.h), whose optical depths
/// are closed forms that can be inverted. Along the ray, with c(t) the unit-density column from
/// the fog's entry t0 (metres; rho(t) = rho_0 - kappa c(t), kappa = d_y / H), the camera depth
/// is sigma c and the depth toward a directional light above the horizon (s_y > 0 the y of
/// its direction) is sigma H rho / s_y + const = const - sigma (d_y / s_y) c: the product of
/// both transmittances is e^{-sigma' c} up to a constant, sigma' = sigma (1 - d_y / s_y). So
/// the march samples c from the pdf q(c) = e^{-sigma' c} / Z on [0, c_end] (c_end: the
/// tail cut-off kTailTransmittance of the camera transmittance, or the ray's end;
/// Z = -expm1(-sigma' c_end) / sigma'), stratified: N nodes c_k = F^{-1}((k + u) / N), one u
/// per ray, t_k by inverting c(t) = rho_0 (1 - e^{-kappa (t - t0)}) / kappa. Since
/// dt = dc / rho, the single scattering int sigma_s rho T(t) L(t) dt is estimated by
///   (Z / N) sum_k sigma_s T(c_k) L(c_k) e^{sigma' c_k},
/// L = sum_lights p E T_light V with T and T_light exact (closed forms): unbiased for any N and
/// any sigma' (the pdf is only importance). sigma is the reference channel's (the least
/// extinguished channel that scatters), the light the brightest directional one with
/// s_y > kLowSun (sigma' = sigma without one), and sigma' is kept within +-8 sigma so the
/// weights stay finite. For a grey fog without a box's sides in the way and a lit ray, every
/// node then gives the same value: the variance left is the shadows' (V) and the other lights'.
/// N: the step h laid along the ray where its fog is densest and lengthened in proportion to
/// 1 / density elsewhere, N = ceil(l / h), l = c_end / rho_max = L g(|kappa| L) the ray's
/// length at its densest (L to c_end, g(x) = (1 - e^{-x}) / x): a level ray gets the homogeneous
/// march's node count, a steep one about H / |d_y| / h. Returns false, having drawn nothing,
/// when the set is not one height fog.
bool march_single_height_fog(const MediumSet& media, const std::vector<Light>& lights,
                             const OcclusionQuery* occlusion, const Ray& ray,
                             const VolumeSettings& settings, Pcg32& rng, VolumeCounters& counters,
                             VolumeResult& result) {
    if (media.media().size() != 1 || media.emits())
        return false;
    const auto* fog = std::get_if<HeightFogMedium>(&media.media()[0].model);
    if (fog == nullptr)
        return false;
    constexpr float kLowSun = 0.02f;   // the sun's s_y below which it does not shape the pdf
    constexpr double kMaxSlope = 8.0;  // |sigma'| <= kMaxSlope sigma
    result = VolumeResult{};
    double t0 = ray.t_min, t1 = ray.t_max;
    if (fog->bounds) {
        const auto span = fog->bounds->clip(ray);
        if (!span)
            return true;
        t0 = span->first;
        t1 = span->second;
    }
    if (!(t1 > t0))
        return true;
    const Rgb sigma_t = fog->sigma_t(), sigma_s = fog->sigma_s;
    const double oy = ray.origin.y, dy = ray.direction.y;
    const double column = height_fog_column(*fog, oy, dy, t0, t1);  // unit density, metres
    result.transmittance = exp_neg(height_fog_optical_depth(*fog, ray));
    // The reference channel: the smallest extinction among the channels that scatter.
    double sigma = HUGE_VAL;
    for (int c = 0; c < 3; ++c)
        if (sigma_s[c] > 0.0f)
            sigma = std::min(sigma, static_cast<double>(sigma_t[c]));
    if (!(sigma < HUGE_VAL) || lights.empty() || !(column > 0.0))
        return true;
    const Vec3 wo = -ray.direction;
    thread_local std::vector<MarchLight> march_lights;
    march_lights.clear();
    thread_local std::vector<size_t> point_lights;
    point_lights.clear();
    double sun_y = 0.0;
    float sun_luminance = 0.0f;
    for (size_t i = 0; i < lights.size(); ++i) {
        MarchLight m;
        m.index = i;
        if (std::holds_alternative<DirectionalLight>(lights[i].emitter)) {
            if (!directional_march_light(lights[i], i, ray, wo, rng, m))
                continue;
            const float y = luminance(m.incident.irradiance);
            if (m.incident.wi.y > kLowSun && y > sun_luminance) {
                sun_luminance = y;
                sun_y = m.incident.wi.y;
            }
        } else if (std::holds_alternative<PointLight>(lights[i].emitter)) {
            point_lights.push_back(i);  // equiangular samples of their own (below)
            continue;
        }
        march_lights.push_back(m);
    }
    const double c_end = std::min(column, static_cast<double>(kTailDepth) / sigma);
    const double slope = sun_y > 0.0 ? std::clamp(1.0 - dy / sun_y, -kMaxSlope, kMaxSlope) : 1.0;
    const double sigma_q = sigma * slope;  // sigma'
    // Z = int_0^c_end e^{-sigma' c} dc, c_end when sigma' c_end -> 0.
    const double z = c_end * one_minus_exp_over_signed(sigma_q * c_end);
    const double H = fog->scale_height_m;
    const double kappa = dy / H;  // d a / d t, per metre
    const double rho_0 = std::exp(-(oy + dy * t0 - fog->reference_height_m) / H);
    const double length = static_cast<double>(t1) - t0;
    // The distance from t0 at which the unit-density column reaches c (clamped to the span).
    const auto distance_at = [&](double c) {
        const double x = kappa * c / rho_0;
        double l = kappa == 0.0 ? c / rho_0 : (x < 1.0 ? -std::log1p(-x) / kappa : length);
        if (!(l < length))  // rounding, or an inverse past the span (rho_0 underflow)
            l = length;
        return std::max(l, 0.0);
    };
    const double l_end = distance_at(c_end);
    const double densest = l_end * one_minus_exp_over(std::abs(kappa) * l_end);
    const float h = march_step_m(media, settings);
    double wanted = std::ceil(densest / static_cast<double>(h));
    if (!(wanted >= 1.0))
        wanted = 1.0;
    if (wanted > kMaxMarchSteps) {
        wanted = kMaxMarchSteps;
        ++counters.bounded_marches;
    }
    const int n = static_cast<int>(wanted);
    const float u = rng.next_float();
    for (int k = 0; k < n && !march_lights.empty(); ++k) {
        // F^{-1}(v) = -log1p(-sigma' Z v) / sigma' (Z v when sigma' Z v -> 0).
        const double zv = z * (k + static_cast<double>(u)) / n;
        const double x_q = sigma_q * zv;
        const double c_k = x_q == 0.0 ? zv : -std::log1p(-x_q) / sigma_q;
        const double t = t0 + distance_at(c_k);
        const Vec3 x = ray.at(static_cast<float>(t));
        const double rho = fog->relative_density(x.y);
        if (!(rho > 0.0))
            continue;
        ++counters.steps;
        ++counters.density_lookups;
        PointCoefficients coefficients;
        coefficients.sigma_t = sigma_t * static_cast<float>(rho);
        coefficients.sigma_s = sigma_s * static_cast<float>(rho);
        Rgb direct(0.0f);
        for (const MarchLight& m : march_lights) {
            const Light& light = lights[m.index];
            if (!m.directional) {
                direct += scattered_direct_one(media, light, m.index, occlusion, x, 1u, wo,
                                               settings, h, rng, counters, &coefficients);
                continue;
            }
            const Rgb f = media.scattering(coefficients, x, 1u, m.mu);
            direct += light_term(media, light, occlusion, x, m.incident, f, std::nullopt, settings,
                                 h, rng, counters);
        }
        // direct holds sigma_s rho L: times T_c(c_k) / (rho q(c_k)) / N.
        // In double: the weight alone can exceed a float where rho is tiny (direct is small).
        for (int c = 0; c < 3; ++c)
            result.radiance[c] += static_cast<float>(
                static_cast<double>(direct[c]) * z / n *
                std::exp((sigma_q - static_cast<double>(sigma_t[c])) * c_k) / rho);
    }
    // Point lights: N stratified equiangular distances over the same stretch [t0, t0 + l_end]
    // (Kulla & Fajardo 2012, volume/equiangular.h: the pdf is the light's inverse square), each
    // weighted by the exact camera transmittance (closed-form column from t0) over its pdf; the
    // light's term (sigma_s rho p I / r^2 T_light V) as at any node. Unbiased for that stretch.
    for (const size_t i : point_lights) {
        const auto& point = std::get<PointLight>(lights[i].emitter);
        const float ta = static_cast<float>(t0), tb = static_cast<float>(t0 + l_end);
        if (!(tb > ta))
            continue;
        const EquiangularSegment segment =
            make_equiangular(ray.origin, ray.direction, point.position, ta, tb);
        const float v = rng.next_float();
        for (int k = 0; k < n; ++k) {
            const float t = segment.sample((static_cast<float>(k) + v) / static_cast<float>(n));
            const float pdf = segment.pdf(t);
            if (!(pdf > 0.0f) || !(t >= ta && t <= tb))
                continue;
            const Vec3 x = ray.at(t);
            const double rho = fog->relative_density(x.y);
            ++counters.steps;
            ++counters.density_lookups;
            PointCoefficients coefficients;
            coefficients.sigma_t = sigma_t * static_cast<float>(rho);
            coefficients.sigma_s = sigma_s * static_cast<float>(rho);
            const Rgb direct = scattered_direct_one(media, lights[i], i, occlusion, x, 1u, wo,
                                                    settings, h, rng, counters, &coefficients);
            const double c_t = height_fog_column(*fog, oy, dy, t0, static_cast<double>(t));
            for (int c = 0; c < 3; ++c)
                result.radiance[c] += static_cast<float>(
                    static_cast<double>(direct[c]) *
                    std::exp(-static_cast<double>(sigma_t[c]) * c_t) / (double(pdf) * n));
        }
    }
    return true;
}

}  // namespace

VolumeResult march_single(const MediumSet& media, const std::vector<Light>& lights,
                          const OcclusionQuery* occlusion, const Ray& ray,
                          const VolumeSettings& settings, Pcg32& rng, VolumeCounters& counters) {
    VolumeResult fast;
    if (march_single_grid(media, lights, occlusion, ray, settings, rng, counters, fast))
        return fast;
    if (march_single_height_fog(media, lights, occlusion, ray, settings, rng, counters, fast))
        return fast;
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
    VolumeResult result;
    if (segments.empty())
        return result;
    const float h =
        bounded_march_step(march_step_m(media, settings), march_extent(segments), counters);
    const Vec3 wo = -ray.direction;
    const bool grey = media.grey_extinction();
    thread_local std::vector<MarchLight> march_lights;
    collect_march_lights(media, lights, ray, settings.light_cache, rng, march_lights);
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
            const Rgb direct = march_node_light(
                media, lights, march_lights, occlusion, x, k, mask, wo, settings, h, rng, counters,
                [&](const MarchLight& m, const Rgb& f) {
                    const std::optional<Rgb> cached =
                        m.cache != nullptr ? m.cache->transmittance(m.line, t) : std::nullopt;
                    return light_term(media, lights[m.index], occlusion, x, m.incident, f, cached,
                                      settings, h, rng, counters);
                });
            result.radiance += (h * t_camera) * direct;
            return true;
        });
    result.transmittance = camera_transmittance(tau, grey);
    return result;
}

}  // namespace kasumi
