#pragma once
/// Scene settings of global illumination: render.gi picks the method, render.path and
/// render.radiosity tune the reference path tracer and the radiosity solver.
#include "core/json_node.h"

#include <string>

namespace kasumi {

/// How light that bounces between surfaces is computed (render.gi).
enum class GiMode {
    None,       ///< direct light, ambient and Whitted mirrors/glass only (the default)
    Radiosity,  ///< diffuse interreflection precomputed on patches (gi/radiosity_gi.h)
    Photons,    ///< photon maps (Jensen's two-pass method)
    Path,       ///< unbiased reference path tracer (gi/path_tracer.h)
};

/// The name as written in scene files: "none", "radiosity", "photons", "path".
const char* gi_mode_name(GiMode mode);

/// Reads render.gi; an unknown name fails with the file and JSON pointer.
GiMode parse_gi_mode(const JsonNode& node);

/// render.path: the reference path tracer.
struct PathSettings {
    int max_depth = 32;  ///< surface bounces after the camera ray's hit, [0, 1024]
    int rr_depth = 3;    ///< Russian roulette starts at this bounce, [1, 1024]
};

PathSettings parse_path_settings(const JsonNode& node);

/// The radiosity system's iterative solver.
enum class RadiositySolver {
    Shooting,     ///< progressive refinement: shoot the largest unshot power (Cohen et al. 1988)
    GaussSeidel,  ///< gathering sweeps over the patches in place
};

/// render.radiosity.
struct RadiositySettings {
    float patch_size_m = 0.25f;  ///< coarse patches are at most this long on a side, > 0
    int max_subdivision = 2;     ///< adaptive levels below the coarse patches, [0, 8]
    /// A patch is split when the radiosity at its corners differs by more than this fraction of
    /// the local mean (luminance), > 0.
    float refine_threshold = 0.2f;
    RadiositySolver solver = RadiositySolver::Shooting;
    /// Stop when the residual (the luminance of unshot power, or of |B - E - ρ F B| for
    /// Gauss-Seidel, area-weighted) falls below this fraction of the emitted power, (0, 1).
    float tolerance = 1e-4f;
    int max_iterations = 100000;  ///< shots or sweeps, >= 1
    /// Visibility-tested points per patch pair for form factors (point-to-polygon, Lambert's
    /// closed form weighted by the visible fraction), [1, 256].
    int form_factor_samples = 16;
    std::string cache;  ///< file to load the solution from, else solve and save it ("" = none)
};

/// Reads render.radiosity; `cache` resolves against the scene file's directory.
RadiositySettings parse_radiosity_settings(const JsonNode& node);

}  // namespace kasumi
