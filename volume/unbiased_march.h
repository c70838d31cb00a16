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
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <optional>

namespace kasumi {

/// M, the nodes of one march, for a ray whose residual bound depth is tau_bar (dimensionless):
/// Kettunen et al.'s fitted total sample count ceil(cbrt((0.015 + tau)(0.65 + tau)(60.3 + tau)))
/// spread over the E[N] + 1 marches the roulette takes on average, at least 1 and at most
/// kMaxMarchNodes.
int unbiased_march_nodes(double tau_bar);

/// The most nodes one march takes (a ray whose residual depth asks for more takes this many:
/// still unbiased, with a larger variance).
constexpr int kMaxMarchNodes = 4096;

/// An unbiased estimate of the transmittance exp(-integral of sigma_t) over
/// [ray.t_min, ray.t_max] per channel. Signed: a single estimate can fall below 0 or exceed 1
/// (the power-series corrections), its mean lies in [0, 1]. Exact where every medium has a
/// closed form, and where the media's minorant depth exceeds 110 in every channel (exp(-110)
/// is 0 in float) it returns 0. std::nullopt when a non-constant segment is endless (no march
/// can cover it; the caller falls back to a tracker). Never throws, never NaN.
std::optional<Rgb> unbiased_march_transmittance(const MediumSet& media, const Ray& ray, Pcg32& rng,
                                                VolumeCounters& counters);

}  // namespace kasumi
