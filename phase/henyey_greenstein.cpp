#include "phase/henyey_greenstein.h"

namespace kasumi {

double hg_denominator(double g, double mu) {
    // A float dot product of unit vectors can pass ±1 by an ulp (6e-8), which for |g| = 0.9999
    // (denominator ~1e-8 at the pole) would make it negative and p NaN.
    mu = std::clamp(mu, -1.0, 1.0);
    return g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu)
                    : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu);
}

double eval_precise(const HenyeyGreenstein& p, double mu) {
    const double g = p.g;
    const double denom = hg_denominator(g, mu);
    return (1.0 - g) * (1.0 + g) / (4.0 * kPiD * denom * std::sqrt(denom));
}

float eval(const HenyeyGreenstein& p, float mu) {
    return static_cast<float>(eval_precise(p, mu));
}

float pdf(const HenyeyGreenstein& p, float mu) {
    return eval(p, mu);
}

double sample_hg_cosine(double g, double u) {
    u = std::clamp(u, 0.0, 1.0);
    // Near g = 0 the inversion divides by g; its limit is the uniform cosine, and the first
    // neglected term is O(g) relative, below float precision for |g| < 1e-7.
    if (std::abs(g) < 1e-7)
        return 2.0 * u - 1.0;
    // s = sqrt(1 + g² - 2 g mu) at the sampled mu, then mu = (1 + g² - s²) / (2g). Double
    // precision keeps 1 - mu accurate to ~1e-8 relative for g = ±0.9999, where float would
    // lose every digit of the forward peak.
    const double s = (1.0 - g) * (1.0 + g) / (1.0 - g + 2.0 * g * u);
    const double mu = (1.0 + g * g - s * s) / (2.0 * g);
    return std::clamp(mu, -1.0, 1.0);
}

PhaseSample sample(const HenyeyGreenstein& p, const Vec3& wo, Vec2 u) {
    const double mu = sample_hg_cosine(p.g, u.x);
    return phase_sample_about(wo, mu, kTwoPi * u.y, eval_precise(p, mu));
}

float mean_cosine(const HenyeyGreenstein& p) {
    return p.g;
}

}  // namespace kasumi
