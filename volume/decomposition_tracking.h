#pragma once
/// Free-flight sampling by decomposition tracking (Kutz, Habel, Li & Novák 2017, "Spectral and
/// Decomposition Tracking for Rendering Heterogeneous Volumes", ACM TOG 36(4), §4): on each
/// majorant segment the extinction splits into a control part, the segment's minorant
/// c = min_channel sigma_min (constant there), and the residual sigma_t - c <= mu - c. The
/// collisions of the control part are drawn analytically (exponential in c, no density lookup);
/// the residual's by spectral tracking against the residual majorant mu - c; the earlier one is
/// the flight's event. Where the minorant equals the majorant no lookup is made at all.
#include "core/rng.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"

namespace kasumi {

/// The control part of segment `s` of a walk: a grey extinction c (1/m) that every channel's
/// sigma_t exceeds throughout the segment, and its coefficients {c, albedo * c} (the medium's
/// albedo sigma_s / sigma_t, constant per medium). Zero (no control) where the segment holds
/// several media or one whose albedo varies (height fog, "other" media).
struct ControlExtinction {
    float sigma_c = 0.0f;
    PointCoefficients k;
};
ControlExtinction control_extinction(const MediumSet& media, const MajorantSegment& s);

/// A free flight along `ray` with the contract of sample_free_flight (FreeFlight::weight times
/// an F carrying FreeFlight::k.sigma_s estimates the integral of T F over the ray; over
/// escapes the weight estimates T), by decomposition tracking. At a control collision the
/// flight scatters with weight 1 / c and k = the control's coefficients (absorption is in
/// k.sigma_s = albedo c); at a residual tentative collision spectral tracking chooses scattering
/// (k = the residual's coefficients sigma - control) or a null collision, as
/// sample_free_flight does with the full coefficients. Media that emit fall back to
/// sample_free_flight. Unbiased. Never throws.
FreeFlight sample_free_flight_decomposition(const MediumSet& media, const Ray& ray,
                                            const Rgb& throughput, Pcg32& rng,
                                            VolumeCounters& counters);

}  // namespace kasumi
