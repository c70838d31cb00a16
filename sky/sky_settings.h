#pragma once
/// How the sky is rendered: `render.sky`, `render.spectral`, `render.wavelengths_nm`.
#include "core/json_node.h"

#include <vector>

namespace kasumi {

enum class SkyMode {
    Reference,  ///< brute-force ray marching in double precision (sky/sky_reference.h)
    Fast,       ///< precomputed tables after Hillaire 2020 (sky/sky_luts.h)
};

struct SkySettings {
    SkyMode mode = SkyMode::Fast;
    /// Reference mode: scattering events per path (1 = single scattering); orders above one
    /// are estimated by Monte Carlo continuation (one path per order per sample).
    int orders = 4;
    int view_steps = 96;  ///< reference mode: quadrature nodes along a view ray
    int sun_steps = 32;   ///< reference mode: quadrature nodes toward the sun
    /// 0: RGB mode (three wavelengths); N > 0: N wavelengths across 360-830 nm.
    int spectral_bands = 0;
    /// RGB mode wavelengths of the R, G, B channels, nm (default 680, 550, 440).
    std::vector<double> rgb_wavelengths_nm{680.0, 550.0, 440.0};
    /// Light shafts (render/sky_shafts.h): surfaces and media shadow the sun's single
    /// scattering in the air over the first `shaft_distance_m` of every camera ray, sampled at
    /// `shaft_samples` jittered strata.
    bool shafts = false;
    /// Fast mode: aerial perspective of camera rays from the camera-frustum table
    /// (sky/aerial_perspective.h; render.sky.aerial_perspective "table", default) or marched
    /// per pixel ("march").
    bool aerial_table = true;
    double shaft_distance_m = 200.0;
    int shaft_samples = 16;
};

/// Reads the keys "sky", "spectral" and "wavelengths_nm" of a `render` object into `sky`.
void parse_sky_render_keys(JsonObjectReader& render, SkySettings& sky);

const char* sky_mode_name(SkyMode mode);

}  // namespace kasumi
