#include "volume/unbiased_march.h"

#include "volume/debiased_exp.h"
#include "volume/majorant_walk.h"

#include <array>
#include <cmath>
#include <vector>

namespace kasumi {

namespace {

/// exp(-110) ~ 1.7e-48 is 0 in float (the smallest subnormal is 1.4e-45).
constexpr double kUnderflowDepth = 110.0;

}  // namespace

int unbiased_march_nodes(double tau_bar) {
    const double total =
        std::ceil(std::cbrt((0.015 + tau_bar) * (0.65 + tau_bar) * (60.3 + tau_bar)));
    const double per_march = std::floor(total / (expected_series_order() + 1.0) + 0.5);
    if (!(per_march < kMaxMarchNodes))
        return kMaxMarchNodes;  // also NaN and inf
    return std::max(1, static_cast<int>(per_march));
}

bool ResidualMarch::add(const MajorantSegment& s, const BrickRef* brick) {
    const double length = static_cast<double>(s.t1) - s.t0;
    if (length < HUGE_VAL)
        m_segments.push_back({s.t0, s.t1, s.sigma_min, m_tau_min});
    for (int c = 0; c < 3; ++c)
        if (s.sigma_min[c] > 0.0f)  // an endless stretch of sigma_min = 0 adds 0, not NaN
            m_tau_min[c] += static_cast<double>(s.sigma_min[c]) * length;
    const float mu = max_component(s.sigma_max - s.sigma_min);
    if (!(mu > 0.0f) || !(length > 0.0))
        return true;
    if (!(length < HUGE_VAL)) {
        m_bounded = false;
        return false;
    }
    m_stretches.push_back({s, brick ? *brick : BrickRef{}, brick != nullptr, mu, m_tau_bar});
    m_tau_bar += static_cast<double>(mu) * length;
    m_varying_length += length;
    return true;
}

void ResidualMarch::reset() {
    m_stretches.clear();
    m_segments.clear();
    m_tau_min = DVec3(0.0);
    m_tau_bar = 0.0;
    m_varying_length = 0.0;
    m_bounded = true;
}

bool ResidualMarch::build(const MediumSet& media, const Ray& ray) {
    reset();
    walk_majorants(media, ray,
                   [&](const MajorantSegment& s, const BrickRef* brick) { return add(s, brick); });
    return m_bounded;
}

bool ResidualMarch::build(const std::vector<MajorantSegment>& segments) {
    reset();
    for (const MajorantSegment& s : segments)
        if (!add(s, nullptr))
            break;
    return m_bounded;
}

DVec3 ResidualMarch::node(const MediumSet& media, const RayMediaQuery& query, double depth,
                          double delta, size_t& i, float* t_out) const {
    while (i + 1 < m_stretches.size() && !(depth < m_stretches[i + 1].depth0))
        ++i;
    const Stretch& r = m_stretches[i];
    const double t = r.s.t0 + (depth - r.depth0) / r.mu;
    const float t_node = std::min(std::max(static_cast<float>(t), r.s.t0), r.s.t1);
    if (t_out != nullptr)
        *t_out = t_node;
    const Rgb sigma =
        coefficients_at(media, query, r.s, r.has_brick ? &r.brick : nullptr, t_node).sigma_t;
    return (delta / r.mu) * DVec3(sigma - r.s.sigma_min);
}

DVec3 ResidualMarch::depth(const MediumSet& media, const RayMediaQuery& query, int nodes, float u,
                           VolumeCounters& counters) const {
    DVec3 tau(0.0);
    if (m_stretches.empty())
        return m_tau_min;
    const double delta = m_tau_bar / nodes;
    size_t i = 0;
    for (int k = 0; k < nodes; ++k) {
        tau += node(media, query, (static_cast<double>(u) + k) * delta, delta, i, nullptr);
        ++counters.density_lookups;
    }
    return m_tau_min + tau;
}

ResidualMarch::Prefix ResidualMarch::start_prefix(int nodes, float u) const {
    Prefix p;
    p.nodes = std::max(nodes, 1);
    p.delta = m_tau_bar / p.nodes;
    p.u = u;
    return p;
}

DVec3 ResidualMarch::prefix(const MediumSet& media, const RayMediaQuery& query, Prefix& p, float t,
                            VolumeCounters& counters) const {
    // Residual nodes before t: a node's t is monotone in its residual depth, so the running
    // sum stops at the first node at or past t (that node is looked up again next call: the
    // lookup is counted once per call, a node costs at most two).
    while (!m_stretches.empty() && p.next < p.nodes) {
        size_t i = p.stretch;
        float t_node = 0.0f;
        const double depth = (static_cast<double>(p.u) + p.next) * p.delta;
        while (i + 1 < m_stretches.size() && !(depth < m_stretches[i + 1].depth0))
            ++i;
        const Stretch& r = m_stretches[i];
        t_node = std::min(std::max(static_cast<float>(r.s.t0 + (depth - r.depth0) / r.mu), r.s.t0),
                          r.s.t1);
        if (!(t_node < t))
            break;
        p.residual += node(media, query, depth, p.delta, i, nullptr);
        ++counters.density_lookups;
        p.stretch = i;
        ++p.next;
    }
    // The minorant's exact depth up to t.
    while (p.segment + 1 < m_segments.size() && !(t < m_segments[p.segment + 1].t0))
        ++p.segment;
    DVec3 minorant(0.0);
    if (!m_segments.empty()) {
        const MinorantSegment& s = m_segments[p.segment];
        const double inside = std::min(std::max(static_cast<double>(t) - s.t0, 0.0),
                                       static_cast<double>(s.t1) - s.t0);
        minorant = s.depth0 + inside * DVec3(s.sigma_min);
    }
    return minorant + p.residual;
}

std::optional<Rgb> unbiased_march_transmittance(const MediumSet& media, const Ray& ray, Pcg32& rng,
                                                VolumeCounters& counters) {
    if (media.closed_form())
        return media.transmittance(ray);
    thread_local ResidualMarch march;
    if (!march.build(media, ray))
        return std::nullopt;
    const DVec3& tau_min = march.minorant_depth();
    if (!(tau_min.x < kUnderflowDepth) && !(tau_min.y < kUnderflowDepth) &&
        !(tau_min.z < kUnderflowDepth))
        return Rgb(0.0f);
    if (march.exact())
        return Rgb(glm::exp(-tau_min));
    const int nodes = unbiased_march_nodes(march.residual_bound());
    const int order = sample_series_order(rng.next_float());
    const RayMediaQuery query(media, ray);
    thread_local std::vector<DVec3> tau_hat;
    tau_hat.clear();
    for (int j = 0; j <= order; ++j)
        tau_hat.push_back(march.depth(media, query, nodes, rng.next_float(), counters));
    return Rgb(debiased_exp(tau_hat));
}

std::optional<Rgb> unbiased_march_about(const MediumSet& media, const Ray& ray, const DVec3& pivot,
                                        Pcg32& rng, VolumeCounters& counters) {
    const float order_u = rng.next_float();
    return unbiased_march_about(media, ray, pivot, SeriesRoulette{}, order_u, rng, counters);
}

std::optional<Rgb> unbiased_march_about(const MediumSet& media, const Ray& ray, const DVec3& pivot,
                                        const SeriesRoulette& roulette, float order_u, Pcg32& rng,
                                        VolumeCounters& counters) {
    const int order = roulette.sample(order_u);
    if (order == 0)
        return Rgb(glm::exp(-pivot));
    thread_local ResidualMarch march;
    if (!march.build(media, ray))
        return std::nullopt;
    const int nodes = unbiased_march_nodes(march.residual_bound());
    const RayMediaQuery query(media, ray);
    std::array<DVec3, kMaxSeriesOrder> tau_hat;
    for (int j = 0; j < order; ++j)
        tau_hat[j] = march.depth(media, query, nodes, rng.next_float(), counters);
    return Rgb(debiased_exp_about(pivot, tau_hat.data(), order, roulette));
}

}  // namespace kasumi
