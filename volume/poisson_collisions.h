#pragma once
/// The tentative collisions of the trackers' Poisson process (rate: a majorant), shared by the
/// transmittance estimators and the free-flight samplers.
#include "core/math.h"
#include "core/rng.h"
#include "volume/in_scattering.h"
#include "volume/majorant_walk.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace kasumi {

/// std::nextafter(t, +inf) without the libm call for the usual t > 0 (an integer step of the
/// bit pattern is the adjacent float of the same sign; Ray Tracing Gems, ch. 6); it was 2% of a
/// multiple-scattering render's CPU time.
inline float next_float_up(float t) {
    if (t == 0.0f)  // +-0: a walk starting at the ray origin
        return std::numeric_limits<float>::denorm_min();
    if (!(t > 0.0f && t < kInfinity))
        return std::nextafter(t, kInfinity);
    uint32_t bits;
    std::memcpy(&bits, &t, sizeof bits);
    ++bits;
    std::memcpy(&t, &bits, sizeof t);
    return t;
}

/// The unit exponential variate of a uniform u in [0, 1) that is a multiple of 2^-24 (as
/// Pcg32::next_float draws): 1 - u is exact and > 0.
inline float unit_exponential_of(float u) {
    return -std::log(1.0f - u);
}

/// A unit exponential variate drawn from `rng`.
inline float unit_exponential(Pcg32& rng) {
    return unit_exponential_of(rng.next_float());
}

/// The tentative collisions of a Poisson process whose rate is piecewise constant (each majorant
/// segment's mu in turn), sampled in optical depth: each collision draws one unit exponential
/// E and the segments consume it, the collision lying where the integral of mu reaches E.
/// Exact for any sequence of segments, and a segment's end costs no random number (restarting
/// the process at every segment, also exact by memorylessness, drew one variate per segment
/// only to throw it away at the segment's end).
class Collisions {
  public:
    explicit Collisions(Pcg32& rng) : m_rng(rng) {}

    /// Calls at(t) at each collision in [t0, t1) of rate mu > 0, in order, while it returns
    /// true. Returns false if `at` stopped the walk; the process then ends (walk is not called
    /// again).
    /// Inlined into each caller: it runs once per majorant segment, and a call there cost a
    /// spill of the caller's walk state around it.
    template <class At>
    __attribute__((always_inline)) bool walk(float t0, float t1, float mu, At&& at) {
        if (m_left < 0.0f)
            m_left = unit_exponential(m_rng);  // drawn on the first segment that has a rate
        for (float t = t0;;) {
            const float depth = std::max(t1 - t, 0.0f) * mu;
            if (!(m_left < depth)) {
                m_left -= depth;
                return true;
            }
            // A gap below t's float resolution (mu ulp(t) >> 1) would leave t where it is, and
            // where sigma(t) = 0 the walk would never end: advance t by at least one ulp.
            t = std::max(t + m_left / mu, next_float_up(t));
            // The next collision's variate is drawn here, before `at` draws its own numbers,
            // but its logarithm is taken only if the walk goes on: a walk that `at` stops
            // (a scattering event, a roulette) never needs it.
            const float u = m_rng.next_float();
            if (!at(t))
                return false;
            m_left = unit_exponential_of(u);
        }
    }

    /// walk's first step on its own: true, the segment's depth consumed, when [t0, t1) at rate
    /// mu holds no collision (then walk(t0, t1, mu, at) would have called nothing and done the
    /// same); false, nothing changed but the first variate's draw, when it holds one (then call
    /// walk). Lets a caller keep the collision loop out of line and the common empty segment
    /// in line.
    bool passes(float t0, float t1, float mu) {
        if (m_left < 0.0f)
            m_left = unit_exponential(m_rng);
        const float depth = std::max(t1 - t0, 0.0f) * mu;
        if (m_left < depth)
            return false;
        m_left -= depth;
        return true;
    }

  private:
    Pcg32& m_rng;
    float m_left = -1.0f;  ///< optical depth (rate-1 units) left to the next collision
};

/// Calls at(t, segment, k, mu) at each tentative collision of the Poisson process whose rate is
/// each segment's scalar majorant mu = max_c sigma_max along query.ray() (the free-flight samplers'
/// walk), k the coefficients there (each lookup counted), while at returns true. Returns false
/// if at stopped the walk, true if the walk left the ray's end.
template <class At>
bool walk_tentative_collisions(const MediumSet& media, const RayMediaQuery& query, Pcg32& rng,
                               VolumeCounters& counters, At&& at) {
    Collisions collisions(rng);
    // The segments with collisions, out of line (most segments have none).
    const auto collide = [&](const MajorantSegment& s, const BrickRef* brick, float mu)
        __attribute__((noinline)) {
        return collisions.walk(s.t0, s.t1, mu, [&](float t) {
            const PointCoefficients k = coefficients_at(media, query, s, brick, t);
            ++counters.density_lookups;
            return at(t, s, k, mu);
        });
    };
    return walk_majorants(media, query, [&](const MajorantSegment& s, const BrickRef* brick) {
        const float mu = max_component(s.sigma_max);
        if (!(mu > 0.0f) || collisions.passes(s.t0, s.t1, mu))
            return true;
        return collide(s, brick, mu);
    });
}

}  // namespace kasumi
