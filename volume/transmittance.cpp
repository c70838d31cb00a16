#include "volume/transmittance.h"

#include "volume/majorant_walk.h"
#include "volume/march_walk.h"
#include "volume/poisson_collisions.h"
#include "volume/spectral_tracking_step.h"
#include "volume/unbiased_march.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace kasumi {

namespace {

/// Below this largest-channel weight, ratio trackers play Russian roulette (unbiased).
constexpr float kRouletteWeight = 0.05f;
/// Beyond this optical depth in every channel the march reports 0 (exp(-60) ~ 1e-26).
constexpr double kOpaqueDepth = 60.0;
/// exp(-110) ~ 1.7e-48 is 0 in float (the smallest subnormal is 1.4e-45).
constexpr double kUnderflowDepth = 110.0;

float mean(const Rgb& c) {
    return (c.r + c.g + c.b) * (1.0f / 3.0f);
}

Rgb march(const MediumSet& media, const Ray& ray, float step_m,
          const std::vector<MajorantSegment>& segments, Pcg32& rng, VolumeCounters& counters) {
    const float h = bounded_march_step(step_m, march_extent(segments), counters);
    const glm::dvec3 tau = march_walk(
        media, ray, h, rng.next_float(), segments, true, counters,
        [](float, const Vec3&, const PointCoefficients&, uint32_t, const glm::dvec3& depth) {
            return !(depth.x > kOpaqueDepth && depth.y > kOpaqueDepth && depth.z > kOpaqueDepth);
        });
    return Rgb(glm::exp(-tau));
}

/// Delta tracking of one channel: 1 if the walk crosses without a real collision, else 0.
float delta_channel(const MediumSet& media, const RayMediaQuery& query, int c, Pcg32& rng,
                    VolumeCounters& counters) {
    Collisions collisions(rng);
    const bool crossed =
        walk_majorants(media, query, [&](const MajorantSegment& s, const BrickRef* brick) {
            const float mu = s.sigma_max[c];
            if (!(mu > 0.0f))
                return true;
            return collisions.walk(s.t0, s.t1, mu, [&](float t) {
                const float sigma = coefficients_at(media, query, s, brick, t).sigma_t[c];
                ++counters.density_lookups;
                return !(rng.next_float() * mu < sigma);  // a real collision ends the walk
            });
        });
    return crossed ? 1.0f : 0.0f;
}

Rgb delta(const MediumSet& media, const Ray& ray, Pcg32& rng, VolumeCounters& counters) {
    const RayMediaQuery query(media, ray);
    const float r = delta_channel(media, query, 0, rng, counters);
    if (media.grey_extinction())
        return Rgb(r);
    return Rgb(r, delta_channel(media, query, 1, rng, counters),
               delta_channel(media, query, 2, rng, counters));
}

/// Ratio tracking (Novák et al. 2014, "Residual Ratio Tracking for Estimating Attenuation in
/// Participating Media", ACM TOG 33(6), Alg. 2) of sigma_t - control over each segment, with
/// the scalar majorant max_c(sigma_max - control); control = 0 gives plain ratio tracking,
/// control = minorant the residual form (the control's exp(-integral) is exact).
Rgb ratio(const MediumSet& media, const Ray& ray, bool residual, Pcg32& rng,
          VolumeCounters& counters) {
    const RayMediaQuery query(media, ray);
    // Grey extinction: the three control depths are the same numbers, so one exp serves all.
    const bool grey = media.grey_extinction();
    const auto control_transmittance = [grey](const glm::dvec3& depth) {
        return grey ? Rgb(static_cast<float>(std::exp(-depth.x))) : Rgb(glm::exp(-depth));
    };
    Rgb weight(1.0f);
    glm::dvec3 control_depth(0.0);
    Collisions collisions(rng);
    // A segment's collisions, out of line: most segments have none (Collisions::passes).
    const auto collide = [&](const MajorantSegment& s, const BrickRef* brick, const Rgb& control,
                             float mu) __attribute__((noinline)) {
        // The control's transmittance so far (exact) scales the roulette threshold; taken
        // once per segment, at its first collision.
        Rgb t_control(-1.0f);
        return collisions.walk(s.t0, s.t1, mu, [&](float t) {
            const Rgb sigma = coefficients_at(media, query, s, brick, t).sigma_t;
            ++counters.density_lookups;
            // sigma - control <= mu up to rounding; the clamp only guards rounding.
            weight *= glm::max(Rgb(1.0f) - (sigma - control) / mu, Rgb(0.0f));
            if (t_control.r < 0.0f)
                t_control = control_transmittance(control_depth);
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
    };
    const bool alive =
        walk_majorants(media, query, [&](const MajorantSegment& s, const BrickRef* brick) {
            const Rgb control = residual ? s.sigma_min : Rgb(0.0f);
            if (residual) {
                bool gone = true;
                for (int c = 0; c < 3; ++c) {
                    if (control[c] > 0.0f)
                        control_depth[c] += static_cast<double>(control[c]) * (s.t1 - s.t0);
                    gone = gone && (weight[c] == 0.0f || control_depth[c] > kUnderflowDepth);
                }
                // The result, weight exp(-control depth) in float, is already 0.
                if (gone)
                    return false;
            }
            const float mu = max_component(s.sigma_max - control);
            if (!(mu > 0.0f) || collisions.passes(s.t0, s.t1, mu))
                return true;
            return collide(s, brick, control, mu);
        });
    if (!alive)
        return Rgb(0.0f);
    return weight * control_transmittance(control_depth);
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
        case Estimator::UnbiasedMarch:
            return "unbiased-march";
        case Estimator::DebiasedMarch:
            return "debiased-march";
    }
    return "?";
}

std::optional<Estimator> estimator_from_name(const std::string& name) {
    for (Estimator e :
         {Estimator::March, Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio,
          Estimator::UnbiasedMarch, Estimator::DebiasedMarch}) {
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
    switch (estimator) {
        case Estimator::March: {
            // The march's limit h -> 0 where every medium has a closed form (homogeneous: the
            // trapezoid is already exact; height fog: volume/height_fog.h).
            if (media.closed_form() && !media.all_homogeneous())
                return media.transmittance(ray);
            thread_local std::vector<MajorantSegment> segments;
            media.majorants(ray, segments);
            if (segments.empty())
                return Rgb(1.0f);
            return march(media, ray, step_m, segments, rng, counters);
        }
        case Estimator::Delta:
            return delta(media, ray, rng, counters);
        case Estimator::Ratio:
            return ratio(media, ray, false, rng, counters);
        case Estimator::ResidualRatio:
            return ratio(media, ray, true, rng, counters);
        case Estimator::UnbiasedMarch:
        case Estimator::DebiasedMarch:
            // An endless varying stretch has no march: residual ratio tracking covers it.
            if (const auto t = unbiased_march_transmittance(media, ray, rng, counters))
                return *t;
            return ratio(media, ray, true, rng, counters);
    }
    return Rgb(1.0f);
}

TrackedWalk track_collisions(const MediumSet& media, const Ray& ray, const Rgb* throughput,
                             Pcg32& rng, VolumeCounters& counters,
                             std::vector<TrackedCollision>& out) {
    ++counters.free_flights;
    out.clear();
    const RayMediaQuery query(media, ray);
    const bool grey = media.grey_extinction();
    const bool emits = media.emits();
    TrackedWalk walk;
    bool flight_open = throughput != nullptr;
    Rgb weight(1.0f);               // product of the ratio factors so far
    glm::dvec3 control_depth(0.0);  // integral of the minorant before the current segment
    Collisions collisions(rng);
    const bool alive =
        walk_majorants(media, query, [&](const MajorantSegment& s, const BrickRef* brick) {
            const Rgb control = s.sigma_min;
            const float mu = max_component(s.sigma_max);
            const glm::dvec3 depth_before = control_depth;
            for (int c = 0; c < 3; ++c)
                control_depth[c] += static_cast<double>(control[c]) * (s.t1 - s.t0);
            if (!(mu > 0.0f))
                return true;
            const float inv_mu = 1.0f / mu;
            return collisions.walk(s.t0, s.t1, mu, [&](float t) {
                const PointCoefficients k = coefficients_at(media, query, s, brick, t);
                ++counters.density_lookups;
                const glm::dvec3 depth =
                    depth_before + glm::dvec3(control) * static_cast<double>(t - s.t0);
                const Rgb t_control =
                    grey ? Rgb(std::exp(-static_cast<float>(depth.x))) : Rgb(glm::exp(-depth));
                if (!is_black(k.sigma_s) || emits)
                    out.push_back({t, ray.at(t), s.media_mask, k, weight * t_control * inv_mu});
                if (flight_open) {
                    // Spectral tracking's choice at this collision (as in sample_free_flight).
                    const Rgb sigma_n = glm::max(Rgb(mu) - k.sigma_t, Rgb(0.0f));
                    const Rgb w = *throughput * walk.flight_weight;
                    const float p_s = mean(w * k.sigma_s), p_n = mean(w * sigma_n);
                    if (!(p_s + p_n > 0.0f)) {
                        walk.flight_weight = Rgb(0.0f);
                        flight_open = false;
                    } else if (rng.next_float() * (p_s + p_n) < p_s) {
                        walk.scatter = static_cast<int>(out.size()) - 1;
                        walk.flight_weight *= (p_s + p_n) / (mu * p_s);
                        flight_open = false;
                    } else {
                        walk.flight_weight *= sigma_n * ((p_s + p_n) / (mu * p_n));
                    }
                }
                // sigma - control <= mu up to rounding; the clamp only guards rounding.
                weight *= glm::max(Rgb(1.0f) - (k.sigma_t - control) * inv_mu, Rgb(0.0f));
                const float w = max_component(weight * t_control);
                if (w < kRouletteWeight) {
                    const float survive = w / kRouletteWeight;
                    if (!(rng.next_float() < survive)) {
                        walk.stopped_at = t;
                        return false;
                    }
                    weight /= survive;
                }
                return true;
            });
        });
    walk.flight_open = flight_open && !alive;
    if (alive) {
        walk.transmittance = grey ? weight * Rgb(std::exp(-static_cast<float>(control_depth.x)))
                                  : weight * Rgb(glm::exp(-control_depth));
    }
    return walk;
}

FreeFlight sample_free_flight(const MediumSet& media, const Ray& ray, const Rgb& throughput,
                              Pcg32& rng, VolumeCounters& counters) {
    ++counters.free_flights;
    const RayMediaQuery query(media, ray);
    const bool emits = media.emits();
    FreeFlight flight;
    walk_tentative_collisions(
        media, query, rng, counters,
        [&](float t, const MajorantSegment& s, const PointCoefficients& k, float mu) {
            if (emits)
                flight.emitted +=
                    throughput * flight.weight * media.emission(ray.at(t), s.media_mask) / mu;
            const Rgb sigma_n = glm::max(Rgb(mu) - k.sigma_t, Rgb(0.0f));
            const TrackingStep step =
                spectral_tracking_step(throughput, k.sigma_s, sigma_n, mu, rng, flight.weight);
            if (step != TrackingStep::Scatter)
                return step == TrackingStep::Null;
            flight.scattered = true;
            flight.t = t;
            flight.position = ray.at(t);
            flight.media_mask = s.media_mask;
            flight.k = k;
            return false;
        });
    return flight;
}

}  // namespace kasumi
