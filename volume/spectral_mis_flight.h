#pragma once
/// Free-flight sampling for chromatic media by spectral MIS (Miller, Georgiev & Jarosz 2019, "A
/// null-scattering path integral formulation of light transport", ACM TOG 38(4), §5.2): one
/// channel, the hero, is chosen with probability q_c proportional to the throughput, and
/// samples the flight as delta tracking in that channel against the common (max-channel)
/// majorant mu of each segment: at a tentative collision it scatters with probability
/// sigma_s,c / mu, is absorbed with sigma_a,c / mu, else passes a null collision. Every channel
/// lambda is then weighted by the one-sample balance heuristic over the three techniques,
///   f_lambda / sum_c q_c p_c,
/// where f and p share exp(-integral of mu) and the collision density, leaving the products of
/// sigma_n = mu - sigma_t over the null collisions (and sigma_s at a scattering end): where
/// channels differ, no channel's estimate blows up the way one technique's ratio f / p does.
#include "core/rng.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"

namespace kasumi {

/// A free flight along `ray` with the contract of sample_free_flight (FreeFlight::weight times
/// an F carrying sigma_s estimates the integral of T F; over escapes the weight estimates T),
/// by spectral MIS. `throughput` (the path weight so far) steers the hero choice; all-zero
/// picks uniformly. Media that emit are not handled here: it falls back to
/// sample_free_flight. Never throws.
FreeFlight sample_free_flight_spectral_mis(const MediumSet& media, const Ray& ray,
                                           const Rgb& throughput, Pcg32& rng,
                                           VolumeCounters& counters);

}  // namespace kasumi
