#include "phase/size_distribution.h"

#include "core/math.h"

#include <cmath>

namespace kasumi {

namespace {

struct LogDensity {
    double operator()(const LogNormalSizes& d, double r) const {
        const double t = (std::log(r) - std::log(d.median_radius_um)) / d.sigma;
        return -0.5 * t * t - std::log(r * d.sigma * std::sqrt(2.0 * kPiD));
    }
    double operator()(const ModifiedGammaSizes& d, double r) const {
        // Normalisation: ∫ r^alpha exp(-b r^gamma) dr = Γ((alpha+1)/gamma) / (gamma
        // b^((alpha+1)/gamma)).
        const double b = d.alpha / (d.gamma * std::pow(d.mode_radius_um, d.gamma));
        const double k = (d.alpha + 1.0) / d.gamma;
        const double log_norm = std::lgamma(k) - std::log(d.gamma) - k * std::log(b);
        return d.alpha * std::log(r) - b * std::pow(r, d.gamma) - log_norm;
    }
};

double reference_radius(const SizeDistribution& d) {
    return std::visit(
        [](const auto& s) -> double {
            using T = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<T, LogNormalSizes>)
                return s.median_radius_um;
            else
                return s.mode_radius_um;
        },
        d);
}

/// log(n(r) r³) on a log grid spanning 1e-4 .. 1e4 reference radii.
template <typename F>
void scan(const SizeDistribution& d, F&& visit_point) {
    const double r_ref = reference_radius(d);
    const int n = 4001;
    for (int i = 0; i < n; ++i) {
        const double r = r_ref * std::pow(10.0, -4.0 + 8.0 * i / (n - 1));
        const double value =
            std::visit([r](const auto& s) { return LogDensity{}(s, r); }, d) + 3.0 * std::log(r);
        visit_point(r, value);
    }
}

}  // namespace

double number_density(const SizeDistribution& d, double radius_um) {
    if (!(radius_um > 0.0))
        return 0.0;
    return std::exp(
        std::visit([radius_um](const auto& s) { return LogDensity{}(s, radius_um); }, d));
}

double dominant_radius_um(const SizeDistribution& d) {
    double best = -INFINITY, best_r = reference_radius(d);
    scan(d, [&](double r, double v) {
        if (v > best) {
            best = v;
            best_r = r;
        }
    });
    return best_r;
}

void scattering_radius_range(const SizeDistribution& d, double& r_min_um, double& r_max_um) {
    double best = -INFINITY;
    scan(d, [&](double, double v) { best = std::max(best, v); });
    // exp(-28) ≈ 7e-13 of the peak weight per unit ln r.
    const double threshold = best - 28.0;
    r_min_um = INFINITY;
    r_max_um = 0.0;
    scan(d, [&](double r, double v) {
        if (v >= threshold) {
            r_min_um = std::min(r_min_um, r);
            r_max_um = std::max(r_max_um, r);
        }
    });
}

}  // namespace kasumi
