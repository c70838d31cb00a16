#include "phase/phase_quadrature.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace kasumi {

namespace {

double simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm,
               double fb, double whole, double tolerance, double relative, int depth) {
    const double m = 0.5 * (a + b);
    const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const double delta = left + right - whole;
    // Relative as well as absolute: tails far below the peak need not be resolved to the
    // absolute tolerance asked of the whole integral.
    if (depth <= 0 || std::abs(delta) <= 15.0 * std::max(tolerance, relative * std::abs(whole)))
        return left + right + delta / 15.0;
    return simpson(f, a, m, fa, flm, fm, left, 0.5 * tolerance, relative, depth - 1) +
           simpson(f, m, b, fm, frm, fb, right, 0.5 * tolerance, relative, depth - 1);
}

}  // namespace

double integrate_mu(const std::function<double(double)>& f, double a, double b, double tolerance,
                    double relative, const std::vector<double>& breaks) {
    // Break points at 1 - |mu| = 2·10^{-k/2}: each panel then sees at most a factor ~3 change
    // in the distance to the pole, where HG-like peaks vary.
    std::vector<double> edges = {a, b};
    for (int k = 0; k <= 20; ++k) {
        const double d = 2.0 * std::pow(10.0, -0.5 * k);
        for (const double e : {-1.0 + d, 1.0 - d})
            if (e > a && e < b)
                edges.push_back(e);
    }
    for (int i = 1; i < 16; ++i) {
        const double e = -1.0 + 2.0 * i / 16.0;
        if (e > a && e < b)
            edges.push_back(e);
    }
    for (const double e : breaks)
        if (e > a && e < b)
            edges.push_back(e);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    const double panel_tolerance = tolerance / static_cast<double>(edges.size());
    double sum = 0.0;
    for (size_t i = 1; i < edges.size(); ++i) {
        const double lo = edges[i - 1], hi = edges[i];
        const double flo = f(lo), fhi = f(hi), fmid = f(0.5 * (lo + hi));
        const double whole = (hi - lo) / 6.0 * (flo + 4.0 * fmid + fhi);
        sum += simpson(f, lo, hi, flo, fmid, fhi, whole, panel_tolerance, relative, 30);
    }
    return sum;
}

double upper_incomplete_gamma_q(double a, double x) {
    if (x <= 0.0)
        return 1.0;
    if (!std::isfinite(x))
        return 0.0;
    const double log_prefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1.0) {
        // P(a, x) = e^{-x} x^a / Γ(a) Σ x^n / (a (a+1) ... (a+n)).
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::abs(term) < std::abs(sum) * 1e-16)
                break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
    }
    // Q(a, x) by Lentz's continued fraction (Press et al., Numerical Recipes, §6.2).
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < tiny)
            d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny)
            c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < 1e-16)
            break;
    }
    return std::exp(log_prefix) * h;
}

}  // namespace kasumi
