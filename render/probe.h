#pragma once
/// Probes: measurements along one ray, reported as JSON by `kasumi probe`.
#include "render/scene_runtime.h"

namespace kasumi {

struct RadianceProbe {
    Rgb radiance{0.0f};  ///< mean over samples, cd/m²
    Rgb stderr_{0.0f};   ///< standard error of the mean per channel
    float luminance_cd_m2 = 0.0f;
    int samples = 0;
};

/// What one camera ray from `origin` along `direction` sees, averaged over `spp` samples with
/// generators keyed by (sample, seed).
RadianceProbe probe_radiance(const SceneRuntime& scene, const Vec3& origin, const Vec3& direction,
                             int spp);

struct TransmittanceProbe {
    Rgb transmittance{1.0f};  ///< mean over samples
    Rgb stderr_{0.0f};        ///< standard error of the mean per channel
    int samples = 0;
};

/// Transmittance of all media of the scene on the segment from `from` to `to` (surfaces
/// ignored), averaged over `samples` estimates by `estimator` with generators keyed by
/// (sample, seed). The march uses the scene's step.
TransmittanceProbe probe_transmittance(const SceneRuntime& scene, const Vec3& from, const Vec3& to,
                                       Estimator estimator, int samples);

}  // namespace kasumi
