#pragma once
/// Accuracy of the fast sky (sky/sky_luts.h) against the reference (sky/sky_reference.h) over
/// the sky dome, as the PSNR of luminance: 10 log10(peak² / MSE), peak the largest reference
/// luminance over the dome's directions (the sun's disc left out). The reference's own noise is
/// taken out of the MSE with two independent halves A and B of its paths:
/// E[(fast - (A + B)/2)²] = error² + E[(A - B)²] / 4, so MSE = raw MSE - mean((A - B)²) / 4
/// (bench/vdb_image_compare does the same for images). Camera 1.5 m above the ground of the
/// default (Bruneton 2017) atmosphere at 680, 550, 440 nm; luminance in cd/m².
#include "core/math.h"

#include <string>
#include <vector>

namespace kasumi {

struct DomePsnrOptions {
    /// Equal-area dome over the upper hemisphere on the sun's side of its vertical plane (the
    /// sky is symmetric about it): rings with sin(elevation) = (i + 0.5) / rings, azimuths
    /// (j + 0.5) 180 / azimuths degrees from the sun.
    int rings = 12, azimuths = 16;
    int paths = 512;  ///< reference paths per direction, two halves (deterministic seeds)
    int orders = 6, view_steps = 64, sun_steps = 24;  ///< the reference's settings
    /// Directory of cached references (files named by every parameter above and the sun's
    /// elevation); empty: none.
    std::string cache;
};

struct DomePsnr {
    double psnr_db = 0.0;     ///< fast sky-view table, reference noise taken out
    double raw_db = 0.0;      ///< the same with the noise left in
    double noise_db = 0.0;    ///< the reference noise's own: 10 log10(peak² / noise MSE)
    double single_db = 0.0;   ///< single scattering alone against the 1-order reference
    double march_db = 0.0;    ///< marched per direction (160 nodes) instead of the table
    double signed_rel = 0.0;  ///< mean of (fast - reference) / reference
};

/// Directions of the dome (unit, +y up, sun at azimuth 0).
std::vector<DVec3> equal_area_dome(int rings, int azimuths);

/// The PSNRs of the fast sky with the sun at `sun_elevation_deg`.
DomePsnr dome_psnr(double sun_elevation_deg, const DomePsnrOptions& options);

}  // namespace kasumi
