#include "volume/transmittance.h"

#include "volume/march_walk.h"

#include <cmath>

namespace kasumi {

namespace {

/// Below this largest-channel weight, ratio trackers play Russian roulette (unbiased).
constexpr float kRouletteWeight = 0.05f;
/// Beyond this optical depth in every channel the march reports 0 (exp(-60) ~ 1e-26).
constexpr double kOpaqueDepth = 60.0;

float mean(const Rgb& c) {
    return (c.r + c.g + c.b) * (1.0f / 3.0f);
}

/// Exponential step with rate mu; u in [0, 1) so 1 - u > 0 and the log is finite.
float exponential_step(float mu, Pcg32& rng) {
    return -std::log1p(-rng.next_float()) / mu;
}

/// Calls at(t) at each tentative collision of a Poisson process of rate mu over [s.t0, s.t1),
/// in order, while it returns true. Returns false if `at` stopped the walk. By memorylessness,
/// restarting the process at each segment's start is exact.
template <class At>
bool walk_collisions(const MajorantSegment& s, float mu, Pcg32& rng, At&& at) {
    for (float t = s.t0;;) {
        t += exponential_step(mu, rng);
        if (!(t < s.t1))
            return true;
        if (!at(t))
            return false;
    }
}

Rgb march(const MediumSet& media, const Ray& ray, float step_m,
          const std::vector<MajorantSegment>& segments, Pcg32& rng, VolumeCounters& counters) {
    const glm::dvec3 tau = march_walk(
        media, ray, step_m, rng.next_float(), segments, true, counters,
        [](float, const Vec3&, const PointCoefficients&, uint32_t, const glm::dvec3& depth) {
            return !(depth.x > kOpaqueDepth && depth.y > kOpaqueDepth && depth.z > kOpaqueDepth);
        });
    return Rgb(glm::exp(-tau));
}

/// Delta tracking of one channel: 1 if the walk crosses without a real collision, else 0.
float delta_channel(const RayMediaQuery& media, int c, const std::vector<MajorantSegment>& segments,
                    Pcg32& rng, VolumeCounters& counters) {
    for (const MajorantSegment& s : segments) {
        const float mu = s.sigma_max[c];
        if (!(mu > 0.0f))
            continue;
        const bool crossed = walk_collisions(s, mu, rng, [&](float t) {
            const float sigma = media.coefficients(t, s.media_mask).sigma_t[c];
            ++counters.density_lookups;
            return !(rng.next_float() * mu < sigma);  // a real collision ends the walk
        });
        if (!crossed)
            return 0.0f;
    }
    return 1.0f;
}

Rgb delta(const MediumSet& media, const Ray& ray, const std::vector<MajorantSegment>& segments,
          Pcg32& rng, VolumeCounters& counters) {
    const RayMediaQuery query(media, ray);
    const float r = delta_channel(query, 0, segments, rng, counters);
    if (media.grey_extinction())
        return Rgb(r);
    return Rgb(r, delta_channel(query, 1, segments, rng, counters),
               delta_channel(query, 2, segments, rng, counters));
}

/// Ratio tracking (Novák et al. 2014, "Residual Ratio Tracking for Estimating Attenuation in
/// Participating Media", ACM TOG 33(6), Alg. 2) of sigma_t - control over each segment, with
/// the scalar majorant max_c(sigma_max - control); control = 0 gives plain ratio tracking,
/// control = minorant the residual form (the control's exp(-integral) is exact).
Rgb ratio(const MediumSet& media, const Ray& ray, const std::vector<MajorantSegment>& segments,
          bool residual, Pcg32& rng, VolumeCounters& counters) {
    const RayMediaQuery query(media, ray);
    Rgb weight(1.0f);
    glm::dvec3 control_depth(0.0);
    for (const MajorantSegment& s : segments) {
        const Rgb control = residual ? s.sigma_min : Rgb(0.0f);
        if (residual) {
            for (int c = 0; c < 3; ++c)
                if (control[c] > 0.0f)
                    control_depth[c] += static_cast<double>(control[c]) * (s.t1 - s.t0);
        }
        // The control's transmittance so far (exact); it scales the roulette threshold.
        const Rgb t_control(glm::exp(-control_depth));
        if (max_component(weight * t_control) == 0.0f)
            return Rgb(0.0f);
        const float mu = max_component(s.sigma_max - control);
        if (!(mu > 0.0f))
            continue;
        const bool alive = walk_collisions(s, mu, rng, [&](float t) {
            const Rgb sigma = query.coefficients(t, s.media_mask).sigma_t;
            ++counters.density_lookups;
            // sigma - control <= mu up to rounding; the clamp only guards rounding.
            weight *= glm::max(Rgb(1.0f) - (sigma - control) / mu, Rgb(0.0f));
            // Russian roulette once the estimate is small: unbiased, bounds the walk length.
            const float w = max_component(weight * t_control);
            if (w < kRouletteWeight) {
                const float survive = w / kRouletteWeight;
                if (!(rng.next_float() < survive))
                    return false;
                weight /= survive;
            }
            return true;
        });
        if (!alive)
            return Rgb(0.0f);
    }
    return weight * Rgb(glm::exp(-control_depth));
}

}  // namespace

const char* estimator_name(Estimator estimator) {
    switch (estimator) {
        case Estimator::March:
            return "march";
        case Estimator::Delta:
            return "delta";
        case Estimator::Ratio:
            return "ratio";
        case Estimator::ResidualRatio:
            return "residual-ratio";
    }
    return "?";
}

std::optional<Estimator> estimator_from_name(const std::string& name) {
    for (Estimator e :
         {Estimator::March, Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio}) {
        if (name == estimator_name(e))
            return e;
    }
    return std::nullopt;
}

float march_step_m(const MediumSet& media, const VolumeSettings& settings) {
    const float voxel = media.smallest_voxel_m();
    if (settings.step_voxels > 0.0f && voxel < kInfinity)
        return settings.step_voxels * voxel;
    return settings.step_m;
}

Rgb estimate_transmittance(const MediumSet& media, const Ray& ray, Estimator estimator,
                           float step_m, Pcg32& rng, VolumeCounters& counters) {
    ++counters.transmittance_estimates;
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
    if (segments.empty())
        return Rgb(1.0f);
    switch (estimator) {
        case Estimator::March:
            return march(media, ray, step_m, segments, rng, counters);
        case Estimator::Delta:
            return delta(media, ray, segments, rng, counters);
        case Estimator::Ratio:
            return ratio(media, ray, segments, false, rng, counters);
        case Estimator::ResidualRatio:
            return ratio(media, ray, segments, true, rng, counters);
    }
    return Rgb(1.0f);
}

FreeFlight sample_free_flight(const MediumSet& media, const Ray& ray, const Rgb& throughput,
                              Pcg32& rng, VolumeCounters& counters) {
    ++counters.free_flights;
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
    const RayMediaQuery query(media, ray);
    const bool emits = media.emits();
    FreeFlight flight;
    for (const MajorantSegment& s : segments) {
        const float mu = max_component(s.sigma_max);
        if (!(mu > 0.0f))
            continue;
        const bool passed = walk_collisions(s, mu, rng, [&](float t) {
            const PointCoefficients k = query.coefficients(t, s.media_mask);
            ++counters.density_lookups;
            if (emits)
                flight.emitted +=
                    throughput * flight.weight * media.emission(ray.at(t), s.media_mask) / mu;
            const Rgb sigma_n = glm::max(Rgb(mu) - k.sigma_t, Rgb(0.0f));
            const Rgb w = throughput * flight.weight;
            const float p_s = mean(w * k.sigma_s), p_n = mean(w * sigma_n);
            if (!(p_s + p_n > 0.0f)) {
                flight.weight = Rgb(0.0f);
                return false;
            }
            // Choose scattering with probability p_s / (p_s + p_n); dividing by it keeps the
            // estimate unbiased for every channel.
            if (rng.next_float() * (p_s + p_n) < p_s) {
                flight.scattered = true;
                flight.t = t;
                flight.position = ray.at(t);
                flight.media_mask = s.media_mask;
                flight.weight *= (p_s + p_n) / (mu * p_s);
                return false;
            }
            flight.weight *= sigma_n * ((p_s + p_n) / (mu * p_n));
            return true;
        });
        if (!passed)
            return flight;
    }
    return flight;
}

}  // namespace kasumi
