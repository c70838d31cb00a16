#include "volume/unbiased_march.h"

#include "volume/debiased_exp.h"
#include "volume/majorant_walk.h"

#include <cmath>
#include <vector>

namespace kasumi {

namespace {

/// exp(-110) ~ 1.7e-48 is 0 in float (the smallest subnormal is 1.4e-45).
constexpr double kUnderflowDepth = 110.0;

/// A segment whose coefficients vary: the march samples its residual sigma_t - sigma_min.
struct ResidualStretch {
    MajorantSegment s;
    BrickRef brick;
    bool has_brick = false;
    float mu = 0.0f;      ///< residual bound max_c (sigma_max - sigma_min), 1/m
    double depth0 = 0.0;  ///< residual bound depth before the stretch, dimensionless
};

/// One march's estimate of the residual depth: nodes at residual bound depth (u + k) Delta.
DVec3 march_residual(const MediumSet& media, const RayMediaQuery& query,
                     const std::vector<ResidualStretch>& stretches, int nodes, double delta,
                     float u, VolumeCounters& counters) {
    DVec3 tau(0.0);
    size_t i = 0;
    for (int k = 0; k < nodes; ++k) {
        const double depth = (static_cast<double>(u) + k) * delta;
        while (i + 1 < stretches.size() && !(depth < stretches[i + 1].depth0))
            ++i;
        const ResidualStretch& r = stretches[i];
        const double t = r.s.t0 + (depth - r.depth0) / r.mu;
        const float t_node = std::min(std::max(static_cast<float>(t), r.s.t0), r.s.t1);
        const Rgb sigma =
            coefficients_at(media, query, r.s, r.has_brick ? &r.brick : nullptr, t_node).sigma_t;
        ++counters.density_lookups;
        tau += (delta / r.mu) * DVec3(sigma - r.s.sigma_min);
    }
    return tau;
}

}  // namespace

int unbiased_march_nodes(double tau_bar) {
    const double total =
        std::ceil(std::cbrt((0.015 + tau_bar) * (0.65 + tau_bar) * (60.3 + tau_bar)));
    const double per_march = std::floor(total / (expected_series_order() + 1.0) + 0.5);
    if (!(per_march < kMaxMarchNodes))
        return kMaxMarchNodes;  // also NaN and inf
    return std::max(1, static_cast<int>(per_march));
}

std::optional<Rgb> unbiased_march_transmittance(const MediumSet& media, const Ray& ray, Pcg32& rng,
                                                VolumeCounters& counters) {
    if (media.closed_form())
        return media.transmittance(ray);
    thread_local std::vector<ResidualStretch> stretches;
    stretches.clear();
    DVec3 tau_min(0.0);
    double tau_bar = 0.0;
    bool bounded = true;
    walk_majorants(media, ray, [&](const MajorantSegment& s, const BrickRef* brick) {
        const double length = static_cast<double>(s.t1) - s.t0;
        for (int c = 0; c < 3; ++c)
            if (s.sigma_min[c] > 0.0f)  // an endless stretch of sigma_min = 0 adds 0, not NaN
                tau_min[c] += static_cast<double>(s.sigma_min[c]) * length;
        const float mu = max_component(s.sigma_max - s.sigma_min);
        if (!(mu > 0.0f) || !(length > 0.0))
            return true;
        if (!(length < HUGE_VAL)) {
            bounded = false;
            return false;
        }
        stretches.push_back({s, brick ? *brick : BrickRef{}, brick != nullptr, mu, tau_bar});
        tau_bar += static_cast<double>(mu) * length;
        return true;
    });
    if (!bounded)
        return std::nullopt;
    if (!(tau_min.x < kUnderflowDepth) && !(tau_min.y < kUnderflowDepth) &&
        !(tau_min.z < kUnderflowDepth))
        return Rgb(0.0f);
    if (stretches.empty())
        return Rgb(glm::exp(-tau_min));
    const int nodes = unbiased_march_nodes(tau_bar);
    const double delta = tau_bar / nodes;
    const int order = sample_series_order(rng.next_float());
    const RayMediaQuery query(media, ray);
    thread_local std::vector<DVec3> tau_hat;
    tau_hat.clear();
    for (int j = 0; j <= order; ++j)
        tau_hat.push_back(tau_min + march_residual(media, query, stretches, nodes, delta,
                                                   rng.next_float(), counters));
    return Rgb(debiased_exp(tau_hat));
}

}  // namespace kasumi
