#include "phase/draine.h"

#include "phase/henyey_greenstein.h"
#include "phase/rayleigh.h"

#include <array>

namespace kasumi {

namespace {

/// Below this |g| the g = 0 form (density ∝ 1 + alpha mu²) is used for sampling; the
/// neglected first-order term changes the density by at most ~3|g| relative.
constexpr double kTinyG = 1e-7;

/// ∫_{w0}^{w} x(v)² dv with x(v) = (a0 - v⁻²) / (2g), a0 = 1 + g², for g in (0, 1).
///
/// Why this variable: with w = (1 + g² - 2 g mu)^{-1/2} the HG part of the CDF is linear in w
/// (dmu (1 + g² - 2 g mu)^{-3/2} = dw / g), so the whole Draine CDF is
/// G(w) = (1/g) ∫_{w0}^{w} (1 + alpha x(v)²) dv with a bounded, slowly varying integrand, and
/// Newton's method converges in a few steps even for g = 0.9999.
double integral_x_squared(double g, double w0, double w) {
    const double a0 = 1.0 + g * g;
    if (g >= 0.05) {
        // Antiderivative (a0² v + 2 a0 / v - 1 / (3 v³)) / (4 g²); the difference loses about
        // eps / g² relative, harmless for g >= 0.05.
        const auto prim = [&](double v) {
            return a0 * a0 * v + 2.0 * a0 / v - 1.0 / (3.0 * v * v * v);
        };
        return (prim(w) - prim(w0)) / (4.0 * g * g);
    }
    // For small g the antiderivative cancels catastrophically; the interval [w0, w] is within
    // [1/(1+g), 1/(1-g)], where x(v)² is a smooth low-degree function: 8-point Gauss-Legendre is
    // accurate far beyond float precision.
    static constexpr std::array<double, 4> kNodes = {0.1834346424956498, 0.5255324099163290,
                                                     0.7966664774136267, 0.9602898564975363};
    static constexpr std::array<double, 4> kWeights = {0.3626837833783620, 0.3137066458778873,
                                                       0.2223810344533745, 0.1012285362903763};
    const double half = 0.5 * (w - w0), mid = 0.5 * (w + w0);
    double sum = 0.0;
    for (size_t i = 0; i < kNodes.size(); ++i) {
        for (const double sign : {-1.0, 1.0}) {
            const double v = mid + sign * half * kNodes[i];
            const double x = (a0 - 1.0 / (v * v)) / (2.0 * g);
            sum += kWeights[i] * x * x;
        }
    }
    return sum * half;
}

/// g * CDF numerator: ∫_{w0}^{w} (1 + alpha x²) dv.
double scaled_cdf(double g, double alpha, double w0, double w) {
    return (w - w0) + alpha * integral_x_squared(g, w0, w);
}

}  // namespace

double draine_value(double g, double alpha, double mu) {
    const double s = hg_denominator(g, mu);
    const double hg = (1.0 - g * g) / (4.0 * kPiD * s * std::sqrt(s));
    return hg * (1.0 + alpha * mu * mu) / (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0);
}

double sample_draine_cosine(double g, double alpha, double u) {
    if (std::abs(g) < kTinyG)
        return sample_quadratic_cosine(alpha, u);
    // p(mu; -g) = p(-mu; g): sample the forward-peaked case with 1 - u and mirror, which keeps
    // the map from u to mu increasing (the inverse CDF of p(mu; g)).
    const double sign = g < 0.0 ? -1.0 : 1.0;
    if (g < 0.0)
        u = 1.0 - u;
    g = std::abs(g);
    const double a0 = 1.0 + g * g;
    const double w0 = 1.0 / (1.0 + g), w1 = 1.0 / (1.0 - g);
    const double target = std::clamp(u, 0.0, 1.0) * scaled_cdf(g, alpha, w0, w1);
    double lo = w0, hi = w1;
    // Start at the HG sample (linear in w), then safeguarded Newton on the monotone CDF.
    double w = w0 + std::clamp(u, 0.0, 1.0) * (w1 - w0);
    for (int iteration = 0; iteration < 60; ++iteration) {
        const double f = scaled_cdf(g, alpha, w0, w) - target;
        if (f > 0.0)
            hi = w;
        else
            lo = w;
        const double x = (a0 - 1.0 / (w * w)) / (2.0 * g);
        double next = w - f / (1.0 + alpha * x * x);
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        const bool converged = std::abs(next - w) <= 1e-14 * w1;
        w = next;
        if (converged)
            break;
    }
    const double mu = (a0 - 1.0 / (w * w)) / (2.0 * g);
    return sign * std::clamp(mu, -1.0, 1.0);
}

double eval_precise(const Draine& p, double mu) {
    return draine_value(p.g, p.alpha, mu);
}

float eval(const Draine& p, float mu) {
    return static_cast<float>(eval_precise(p, mu));
}

float pdf(const Draine& p, float mu) {
    return eval(p, mu);
}

PhaseSample sample(const Draine& p, const Vec3& wo, Vec2 u) {
    const double mu = sample_draine_cosine(p.g, p.alpha, u.x);
    return phase_sample_about(wo, mu, kTwoPi * u.y, eval_precise(p, mu));
}

float mean_cosine(const Draine& p) {
    const double g = p.g, alpha = p.alpha;
    return static_cast<float>(g * (1.0 + alpha * (3.0 + 2.0 * g * g) / 5.0) /
                              (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0));
}

}  // namespace kasumi
