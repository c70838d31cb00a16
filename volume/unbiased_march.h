#pragma once
/// Unbiased ray-marching transmittance (Kettunen, d'Eon, Pantaleoni & Novák 2021, "An unbiased
/// ray-marching transmittance estimator", ACM TOG 40(4)) over a ray's majorant segments: N + 1
/// independent jittered marches of the optical depth tau, debiased by volume/debiased_exp.h
/// (N = 0 nine times in ten: one march and exp(-tau^)).
///
/// Each march estimates tau with the per-segment minorant as control: tau = integral of
/// sigma_min (exact) + integral of (sigma_t - sigma_min), the residual sampled by M stratified
/// nodes spaced evenly in the residual bound's optical depth, integral of
/// mu_r = max_c (sigma_max - sigma_min) dt (one random offset per march). A node adds
/// Delta (sigma_t - sigma_min) / mu_r with Delta = tau_bar / M, tau_bar the ray's total residual
/// bound depth; each node's term lies in [0, Delta], so the march's variance is at most
/// tau_bar² / (4 M) whatever the density does inside the bounds, and it is 0 where the bounds
/// meet (constant bricks, homogeneous media: exact Beer-Lambert, zero variance).
#include "core/rng.h"
#include "volume/debiased_exp.h"
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <optional>
#include <vector>

namespace kasumi {

/// M, the nodes of one march, for a ray whose residual bound depth is tau_bar (dimensionless):
/// Kettunen et al.'s fitted total sample count ceil(cbrt((0.015 + tau)(0.65 + tau)(60.3 + tau)))
/// spread over the E[N] + 1 marches the roulette takes on average, at least 1 and at most
/// kMaxMarchNodes.
int unbiased_march_nodes(double tau_bar);

/// The most nodes one march takes (a ray whose residual depth asks for more takes this many:
/// still unbiased, with a larger variance).
constexpr int kMaxMarchNodes = 4096;

/// The jittered residual marches of one ray (the estimator above without its debiasing): built
/// once per ray, then any number of independent unbiased estimates of the optical depth over the
/// whole ray (`depth`) or over every prefix [ray.t_min, t) at once (`Prefix`, a running sum:
/// with nodes s_j = (v + j) Delta in residual bound depth and v uniform, the sum over the nodes
/// before t has expectation integral of (sigma_t - sigma_min) up to t for every t, so one march
/// serves every t along the ray). Lives in a thread_local of its caller (its vectors are reused).
class ResidualMarch {
  public:
    /// Reads the ray's majorant segments (walk_majorants); false when a varying segment is
    /// endless (no march covers it).
    bool build(const MediumSet& media, const Ray& ray);
    /// As build, from a segment list already made for the ray (MediumSet::majorants).
    bool build(const std::vector<MajorantSegment>& segments);

    /// Integral of the minorant over the whole ray per channel (exact; +inf over an endless
    /// stretch with sigma_min > 0).
    const DVec3& minorant_depth() const { return m_tau_min; }
    /// Residual bound depth tau_bar of the whole ray (dimensionless).
    double residual_bound() const { return m_tau_bar; }
    /// Total length of the segments whose coefficients vary (metres: the ray's units).
    double varying_length() const { return m_varying_length; }
    /// Whether every segment is constant (the minorant depth is the exact optical depth).
    bool exact() const { return m_stretches.empty(); }

    /// One unbiased estimate of the optical depth over the whole ray: the minorant's exact depth
    /// plus `nodes` stratified residual nodes with offset u in [0, 1).
    DVec3 depth(const MediumSet& media, const RayMediaQuery& query, int nodes, float u,
                VolumeCounters& counters) const;

    /// A running march: prefix(t) estimates the optical depth over [ray.t_min, t), t
    /// non-decreasing between calls.
    struct Prefix {
        int nodes = 1;
        double delta = 0.0;  ///< residual bound depth between nodes
        float u = 0.0f;
        int next = 0;         ///< index of the next node not yet summed
        size_t stretch = 0;   ///< stretch holding node `next`
        size_t segment = 0;   ///< minorant segment at the last t
        DVec3 residual{0.0};  ///< sum of the nodes before the last t
    };
    Prefix start_prefix(int nodes, float u) const;
    DVec3 prefix(const MediumSet& media, const RayMediaQuery& query, Prefix& p, float t,
                 VolumeCounters& counters) const;

  private:
    /// A segment whose coefficients vary: the march samples its residual sigma_t - sigma_min.
    struct Stretch {
        MajorantSegment s;
        BrickRef brick;
        bool has_brick = false;
        float mu = 0.0f;      ///< residual bound max_c (sigma_max - sigma_min), 1/m
        double depth0 = 0.0;  ///< residual bound depth before the stretch, dimensionless
    };
    /// Every finite segment with its minorant depth before it (for prefixes).
    struct MinorantSegment {
        float t0 = 0.0f, t1 = 0.0f;
        Rgb sigma_min{0.0f};
        DVec3 depth0{0.0};
    };
    void reset();
    bool add(const MajorantSegment& s, const BrickRef* brick);
    /// The node at residual bound depth `depth` (stretch index advanced from i): its t and the
    /// term Delta (sigma_t - sigma_min) / mu.
    DVec3 node(const MediumSet& media, const RayMediaQuery& query, double depth, double delta,
               size_t& i, float* t_out) const;

    std::vector<Stretch> m_stretches;
    std::vector<MinorantSegment> m_segments;
    DVec3 m_tau_min{0.0};
    double m_tau_bar = 0.0;
    double m_varying_length = 0.0;
    bool m_bounded = true;
};

/// An unbiased estimate of the transmittance exp(-integral of sigma_t) over
/// [ray.t_min, ray.t_max] per channel. Signed: a single estimate can fall below 0 or exceed 1
/// (the power-series corrections), its mean lies in [0, 1]. Exact where every medium has a
/// closed form, and where the media's minorant depth exceeds 110 in every channel (exp(-110)
/// is 0 in float) it returns 0. std::nullopt when a non-constant segment is endless (no march
/// can cover it; the caller falls back to a tracker). Never throws, never NaN.
std::optional<Rgb> unbiased_march_transmittance(const MediumSet& media, const Ray& ray, Pcg32& rng,
                                                VolumeCounters& counters);

/// An unbiased estimate of the transmittance over the ray about a control optical depth `pivot`
/// per channel (any value fixed before the call, e.g. a light cache's depth): exp(-pivot) nine
/// times in ten, else debiased_exp_about over N independent jittered residual marches (the
/// roulette SeriesRoulette{}; each march as in unbiased_march_transmittance). Unbiased whatever
/// the pivot; its variance is about exp(-2 tau) (tau_p - tau)² / P(N >= 1) plus the marches'
/// own, so a close control makes corrections small and the estimate cheap (E[N] = 0.319
/// marches). std::nullopt only when a correction is drawn and a varying segment is endless
/// (never for a bounded grid); the caller then falls back, and for such rays the result is
/// biased. Never throws, never NaN.
std::optional<Rgb> unbiased_march_about(const MediumSet& media, const Ray& ray, const DVec3& pivot,
                                        Pcg32& rng, VolumeCounters& counters);

/// unbiased_march_about with the order's law and uniform given: N = roulette.sample(order_u).
/// Unbiased whenever order_u is uniform on [0, 1) and independent of the marches; it may be
/// correlated with other calls' order_u (volume/debiased_march_single.h stratifies the orders
/// of the shadow rays along one camera ray). Draws no random number for N = 0.
std::optional<Rgb> unbiased_march_about(const MediumSet& media, const Ray& ray, const DVec3& pivot,
                                        const SeriesRoulette& roulette, float order_u, Pcg32& rng,
                                        VolumeCounters& counters);

}  // namespace kasumi
