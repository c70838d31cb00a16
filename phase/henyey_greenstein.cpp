#include "phase/henyey_greenstein.h"

#include "core/sampling.h"

namespace kasumi {

float eval(const HenyeyGreenstein& p, float mu) {
    // 1 + g² - 2 g mu written as (1 - g)² + 2 g (1 - mu): the textbook form cancels
    // catastrophically near g = 1, mu = 1 (for g = 0.9999 in float it is pure rounding noise).
    const double g = p.g;
    const double denom = (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - static_cast<double>(mu));
    return static_cast<float>((1.0 - g) * (1.0 + g) / (4.0 * kPiD * denom * std::sqrt(denom)));
}

float pdf(const HenyeyGreenstein& p, float mu) {
    return eval(p, mu);
}

float sample_hg_cosine(float g_in, float u_in) {
    const double g = g_in, u = std::clamp(static_cast<double>(u_in), 0.0, 1.0);
    // Near g = 0 the inversion divides by g; its limit is the uniform cosine, and the first
    // neglected term is O(g) relative, below float precision for |g| < 1e-7.
    if (std::abs(g) < 1e-7)
        return static_cast<float>(2.0 * u - 1.0);
    // s = sqrt(1 + g² - 2 g mu) at the sampled mu, then mu = (1 + g² - s²) / (2g). Double
    // precision keeps 1 - mu accurate to ~1e-8 relative for g = ±0.9999, where float would
    // lose every digit of the forward peak.
    const double s = (1.0 - g) * (1.0 + g) / (1.0 - g + 2.0 * g * u);
    const double mu = (1.0 + g * g - s * s) / (2.0 * g);
    return static_cast<float>(std::clamp(mu, -1.0, 1.0));
}

PhaseSample sample(const HenyeyGreenstein& p, const Vec3& wo, Vec2 u) {
    const float mu = sample_hg_cosine(p.g, u.x);
    // Light arriving along -wi leaves along wo, so mu = dot(-wi, wo): draw -wi about wo.
    const Vec3 propagation = direction_about(wo, mu, kTwoPi * u.y);
    const float value = eval(p, mu);
    return PhaseSample{-propagation, value, value};
}

float mean_cosine(const HenyeyGreenstein& p) {
    return p.g;
}

}  // namespace kasumi
