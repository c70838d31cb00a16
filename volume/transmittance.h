#pragma once
/// Transmittance estimators over a MediumSet and free-flight distance sampling, all walking the
/// per-brick majorants the media report along a ray (no global majorant). See docs/volumes.md.
#include "core/rng.h"
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <optional>
#include <string>
#include <vector>

namespace kasumi {

/// Scene-file names: "march", "delta", "ratio", "residual-ratio", "unbiased-march".
const char* estimator_name(Estimator estimator);
std::optional<Estimator> estimator_from_name(const std::string& name);

/// The march step in metres: step_voxels times the finest grid's voxel when both are given,
/// else step_m.
float march_step_m(const MediumSet& media, const VolumeSettings& settings);

/// An estimate of the transmittance exp(-integral of sigma_t) over [ray.t_min, ray.t_max] per
/// channel, in [0, 1] except for UnbiasedMarch, whose single estimates are signed and may exceed
/// 1 (their mean is in [0, 1]; volume/unbiased_march.h). Unbiased for Delta, Ratio,
/// ResidualRatio, UnbiasedMarch; March (step `step_m`, offset jittered per call) is biased by
/// O(step²) where the density is smooth, and exact (the closed form, MediumSet::transmittance)
/// when every medium has one. Never throws.
Rgb estimate_transmittance(const MediumSet& media, const Ray& ray, Estimator estimator,
                           float step_m, Pcg32& rng, VolumeCounters& counters);

/// The outcome of free-flight sampling along a ray.
struct FreeFlight {
    bool scattered =
        false;  ///< a real scattering collision at t; else the path left [t_min, t_max]
    float t = 0.0f;
    Vec3 position{0.0f};
    uint32_t media_mask = 0;
    /// The coefficients at `position` (the lookup that chose the scattering event).
    PointCoefficients k;
    /// Factor to multiply into the path throughput. Expectations: over scattering outcomes,
    /// weight * F(t) estimates the integral of T(t) F(t) dt for any F that vanishes where
    /// sigma_s does (F carries sigma_s, e.g. sigma_s p L); over escapes, weight estimates T.
    Rgb weight{1.0f};
    /// Light emitted by the media along the flight toward the ray origin (cd/m²), already
    /// multiplied by the `throughput` passed in: at each tentative collision t_i,
    /// sum throughput W_i sigma_a L_e(t_i) / mu, with W_i the weight before the choice there;
    /// its expectation is the integral of T(t) sigma_a L_e dt (the null-collision form of the
    /// emission term; 0 when no medium emits).
    Rgb emitted{0.0f};
};

/// One tentative collision of the ratio-tracked walk along a ray (track_collisions).
struct TrackedCollision {
    float t = 0.0f;
    Vec3 position{0.0f};
    uint32_t media_mask = 0;
    PointCoefficients k;  ///< sigma_t, sigma_s at the collision, 1/m
    /// T^(t) / mu(t): the walk's transmittance estimate up to t (collisions before t only)
    /// over the rate of the collisions. For any g, E[sum_i weight_i g(t_i)] is the integral of
    /// T(t) g(t) dt over the ray (Campbell's theorem for the Poisson process of rate mu, with
    /// the history before t_i independent of the collision at t_i).
    Rgb weight{0.0f};
};

/// What track_collisions returns besides the collisions.
struct TrackedWalk {
    /// T^ at the ray's end: an unbiased estimate of the whole ray's transmittance (0 when
    /// Russian roulette ended the walk).
    Rgb transmittance{0.0f};
    /// Roulette ended the walk at t = stopped_at (else kInfinity).
    float stopped_at = kInfinity;
    /// The free flight decided on the same collisions (only when a throughput is passed):
    /// `out` index of its scattering collision, or -1 (none: it escaped, was absorbed, or is
    /// undecided because the walk stopped first, see flight_open).
    int scatter = -1;
    bool flight_open = false;  ///< the walk stopped before the free flight ended
    Rgb flight_weight{1.0f};   ///< the free flight's weight so far (FreeFlight::weight)
};

/// Ratio tracking for in-scattering (a collision estimator with null collisions; Novák,
/// Georgiev, Hanika & Jarosz 2018, "Monte Carlo Methods for Volumetric Light Transport
/// Simulation", CGF 37(2), §6.2; the transmittance weights are those of residual ratio
/// tracking, Novák et al. 2014 §4, with the per-brick minorant as control): walks the tentative
/// collisions of rate mu = the segment's scalar majorant max_c sigma_max toward the ray's end,
/// keeping T^ = exp(-integral of the minorant) times the product of
/// (1 - (sigma_t - sigma_min) / mu) over the collisions passed, with Russian roulette once T^
/// falls below 0.05 (unbiased). Every collision where sigma_s (or emission) is non-zero is
/// appended to `out` (cleared first) with its weight. With a `throughput`, spectral tracking
/// (as sample_free_flight) also runs on the same collisions and picks the path's next
/// scattering event: one walk serves the transmittance, the in-scattering of every collision
/// and the free flight (each unbiased on its own). Never throws.
TrackedWalk track_collisions(const MediumSet& media, const Ray& ray, const Rgb* throughput,
                             Pcg32& rng, VolumeCounters& counters,
                             std::vector<TrackedCollision>& out);

/// Spectral tracking (Kutz et al. 2017, "Spectral and Decomposition Tracking for Rendering
/// Heterogeneous Volumes", ACM TOG 36(4), §3, absorption folded into the weights): walks
/// collisions with the scalar (max-channel) majorant of each segment and picks scattering or a
/// null collision with probabilities proportional to the throughput-weighted sigma_s and
/// sigma_n = majorant - sigma_t. `throughput` is the path weight so far (it steers the choices).
/// For grey media and grey throughput this is delta tracking with absorption as a weight.
FreeFlight sample_free_flight(const MediumSet& media, const Ray& ray, const Rgb& throughput,
                              Pcg32& rng, VolumeCounters& counters);

}  // namespace kasumi
