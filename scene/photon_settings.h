#pragma once
/// Scene settings of photon mapping (render.photons; used when render.gi is "photons").
#include "core/json_node.h"

#include <cstdint>

namespace kasumi {

/// How photons around a point are weighted in a density estimate (gi/photon/photon_estimate.h).
enum class PhotonFilter {
    Box,           ///< every photon counts alike: Σ ΔΦ / (π r²)
    Cone,          ///< w = 1 - d / (k r), k = 1.1 (Jensen 2001, §7.2.2)
    Epanechnikov,  ///< w ∝ 1 - d² / r², the kernel of least asymptotic MSE (Silverman 1986, §3.3)
};

/// render.photons. Counts are photons *emitted* for each map (a pass of its own, so each map's
/// photons sum exactly to the lights' flux); 0 turns a map off.
struct PhotonSettings {
    uint64_t global_count = 200000;   ///< photons emitted for the global map, [0, 1e8]
    uint64_t caustic_count = 200000;  ///< photons emitted for the caustic map (L S+ D), [0, 1e8]
    uint64_t volume_count = 100000;   ///< photons emitted for the volume map, [0, 1e8]
    int k = 80;                       ///< photons per density estimate, [1, 10000]
    float max_radius_m = 0.25f;       ///< search radius of the density estimates, metres, > 0
    int final_gather_samples = 32;    ///< gather rays per diffuse camera hit, [0, 4096]
    PhotonFilter filter =
        PhotonFilter::Cone;  ///< surface estimates ("box", "cone", "epanechnikov")
    int max_bounces = 32;    ///< surface and volume events per photon path, [1, 1024]
    /// Photons emitted from the lights for the shadow map (gi/photon/photon_shadow.h), [0, 1e8];
    /// 0 (the default) turns shadow photons off: every shadow test is a ray.
    uint64_t shadow_count = 0;
    int shadow_k = 16;  ///< nearest shadow-map photons that decide a point's visibility, [1, 1000]
};

/// Reads render.photons; unknown keys and out-of-range values fail with file and JSON pointer.
PhotonSettings parse_photon_settings(const JsonNode& node);

/// "box", "cone" or "epanechnikov".
const char* photon_filter_name(PhotonFilter filter);

}  // namespace kasumi
