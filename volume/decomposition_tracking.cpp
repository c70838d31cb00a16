#include "volume/decomposition_tracking.h"

#include "volume/majorant_walk.h"
#include "volume/poisson_collisions.h"
#include "volume/spectral_tracking_step.h"

#include <algorithm>

namespace kasumi {

ControlExtinction control_extinction(const MediumSet& media, const MajorantSegment& s) {
    // Grey: one control rate for every channel, so the control's collisions need no channel
    // choice; the smallest channel's minorant is below every channel's sigma_t. Tested first:
    // most segments of a cloud have a zero minorant and cost nothing more here.
    const float sigma_c =
        std::min({s.sigma_min.r, s.sigma_min.g, s.sigma_min.b, max_component(s.sigma_max)});
    const uint32_t mask = s.media_mask;
    if (!(sigma_c > 0.0f) || mask == 0 || (mask & (mask - 1)) != 0)
        return {};
    const MediumSet::FastMedium& m = media.fast(static_cast<uint32_t>(__builtin_ctz(mask)));
    if (m.other)
        return {};
    Rgb albedo(0.0f);
    for (int c = 0; c < 3; ++c)
        albedo[c] = m.sigma_t[c] > 0.0f ? m.sigma_s[c] / m.sigma_t[c] : 0.0f;
    return {sigma_c, {Rgb(sigma_c), albedo * sigma_c}};
}

FreeFlight sample_free_flight_decomposition(const MediumSet& media, const Ray& ray,
                                            const Rgb& throughput, Pcg32& rng,
                                            VolumeCounters& counters) {
    if (media.emits())
        return sample_free_flight(media, ray, throughput, rng, counters);
    ++counters.free_flights;
    const RayMediaQuery query(media, ray);
    FreeFlight flight;
    Collisions residual(rng);
    // Optical depth (rate-1 units) left to the control part's next collision: the control
    // process is Poisson with a piecewise-constant rate, so one unit exponential is consumed
    // across segments (as Collisions does for the residual).
    float control_left = -1.0f;
    const auto scatter = [&](float t, const MajorantSegment& s, const PointCoefficients& k) {
        flight.scattered = true;
        flight.t = t;
        flight.position = ray.at(t);
        flight.media_mask = s.media_mask;
        flight.k = k;
    };
    walk_majorants(media, query, [&](const MajorantSegment& s, const BrickRef* brick) {
        const float mu = max_component(s.sigma_max);
        if (!(mu > 0.0f))
            return true;
        const ControlExtinction control = control_extinction(media, s);
        const float sigma_c = control.sigma_c;
        const float mu_r = mu - sigma_c;
        float t_c = kInfinity;
        if (sigma_c > 0.0f) {
            if (control_left < 0.0f)
                control_left = unit_exponential(rng);
            t_c = s.t0 + control_left / sigma_c;
        }
        const float t_end = std::min(t_c, s.t1);
        if (mu_r > 0.0f && t_end > s.t0) {
            const bool passed = residual.walk(s.t0, t_end, mu_r, [&](float t) {
                const PointCoefficients k = coefficients_at(media, query, s, brick, t);
                ++counters.density_lookups;
                // The residual medium: sigma - control (>= 0 up to rounding, which the max
                // guards); its null part mu - sigma_t is the full medium's.
                const PointCoefficients k_r =
                    sigma_c > 0.0f
                        ? PointCoefficients{glm::max(k.sigma_t - control.k.sigma_t, Rgb(0.0f)),
                                            glm::max(k.sigma_s - control.k.sigma_s, Rgb(0.0f))}
                        : k;
                const Rgb sigma_n = glm::max(Rgb(mu) - k.sigma_t, Rgb(0.0f));
                const TrackingStep step = spectral_tracking_step(throughput, k_r.sigma_s, sigma_n,
                                                                 mu_r, rng, flight.weight);
                if (step == TrackingStep::Scatter)
                    scatter(t, s, k_r);
                return step == TrackingStep::Null;
            });
            if (!passed)
                return false;
        }
        if (t_c < s.t1) {
            // A collision of the control part: real everywhere (its null part is 0), so the
            // flight scatters there with weight 1 / sigma_c; the control's albedo is in k.
            if (!(channel_mean(throughput * flight.weight * control.k.sigma_s) > 0.0f)) {
                flight.weight = Rgb(0.0f);  // absorbed in every channel the path carries
                return false;
            }
            scatter(t_c, s, control.k);
            flight.weight *= 1.0f / sigma_c;
            return false;
        }
        if (sigma_c > 0.0f)
            control_left = std::max(control_left - sigma_c * (s.t1 - s.t0), 0.0f);
        return true;
    });
    return flight;
}

}  // namespace kasumi
