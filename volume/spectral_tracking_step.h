#pragma once
/// One tentative collision of spectral tracking (Kutz, Habel, Li & Novák 2017, "Spectral and
/// Decomposition Tracking for Rendering Heterogeneous Volumes", ACM TOG 36(4), §3, absorption
/// folded into the weights), shared by the free-flight samplers that walk a Poisson process of
/// rate mu: scattering (sigma_s) or a null collision (sigma_n = mu - sigma_t) is chosen with
/// probabilities proportional to their throughput-weighted channel means.
#include "core/color.h"
#include "core/rng.h"

namespace kasumi {

/// The mean of the three channels.
inline float channel_mean(const Rgb& c) {
    return (c.r + c.g + c.b) * (1.0f / 3.0f);
}

enum class TrackingStep {
    Scatter,  ///< a real scattering collision: the flight ends here
    Null,     ///< a null collision: the flight goes on
    End,      ///< nothing can be chosen (weight set to 0): the flight ends
};

/// Chooses at a collision of rate mu with coefficients sigma_s and sigma_n (1/m), given the
/// path `throughput` and the flight's `weight` so far, by one uniform from `rng` (none drawn when
/// nothing can be chosen), and multiplies
/// `weight` by the choice's factor: (p_s + p_n) / (mu p_s) on scattering (the caller's F carries
/// sigma_s), sigma_n (p_s + p_n) / (mu p_n) on a null collision. Unbiased for every channel.
inline TrackingStep spectral_tracking_step(const Rgb& throughput, const Rgb& sigma_s,
                                           const Rgb& sigma_n, float mu, Pcg32& rng, Rgb& weight) {
    const Rgb w = throughput * weight;
    const float p_s = channel_mean(w * sigma_s), p_n = channel_mean(w * sigma_n);
    if (!(p_s + p_n > 0.0f)) {
        weight = Rgb(0.0f);
        return TrackingStep::End;
    }
    if (rng.next_float() * (p_s + p_n) < p_s) {
        weight *= (p_s + p_n) / (mu * p_s);
        return TrackingStep::Scatter;
    }
    weight *= sigma_n * ((p_s + p_n) / (mu * p_n));
    return TrackingStep::Null;
}

}  // namespace kasumi
