#include "phase/rayleigh.h"

namespace kasumi {

namespace {

double rayleigh_gamma(float rho) {
    return static_cast<double>(rho) / (2.0 - static_cast<double>(rho));
}

}  // namespace

double rayleigh_phase(double rho, double mu) {
    const double gamma = rho / (2.0 - rho);
    return 3.0 / (16.0 * kPiD * (1.0 + 2.0 * gamma)) *
           ((1.0 + 3.0 * gamma) + (1.0 - gamma) * mu * mu);
}

double eval_precise(const Rayleigh& p, double mu) {
    return rayleigh_phase(static_cast<double>(p.rho), mu);
}

float eval(const Rayleigh& p, float mu) {
    return static_cast<float>(eval_precise(p, mu));
}

float pdf(const Rayleigh& p, float mu) {
    return eval(p, mu);
}

double sample_quadratic_cosine(double a, double u) {
    // CDF: (mu + a mu³/3 + 1 + a/3) / (2 + 2a/3) = u, i.e. the depressed cubic
    // mu³ + P mu + Q = 0 with P = 3/a > 0, which has exactly one real root. The hyperbolic form
    // of that root, -2 sqrt(P/3) sinh(asinh(3Q/(2P) sqrt(3/P)) / 3), avoids the cancellation of
    // Cardano's two cube roots when a is small.
    if (a < 1e-9)
        return std::clamp(2.0 * u - 1.0, -1.0, 1.0);
    const double P = 3.0 / a;
    const double Q = -(3.0 / a) * ((2.0 + 2.0 * a / 3.0) * u - 1.0 - a / 3.0);
    const double r = std::sqrt(P / 3.0);
    const double mu = -2.0 * r * std::sinh(std::asinh(1.5 * Q / (P * r)) / 3.0);
    return std::clamp(mu, -1.0, 1.0);
}

PhaseSample sample(const Rayleigh& p, const Vec3& wo, Vec2 u) {
    const double gamma = rayleigh_gamma(p.rho);
    const double a = (1.0 - gamma) / (1.0 + 3.0 * gamma);
    const double mu = sample_quadratic_cosine(a, u.x);
    return phase_sample_about(wo, mu, kTwoPi * u.y, eval_precise(p, mu));
}

float mean_cosine(const Rayleigh&) {
    return 0.0f;
}

}  // namespace kasumi
