#pragma once
/// The illuminance probe: lux on a small surface at a point, light by light, as `kasumi probe
/// illuminance` reports it.
#include "render/scene_runtime.h"

#include <string>
#include <vector>

namespace kasumi {

/// How one light's illuminance was obtained.
enum class IlluminanceMethod {
    Analytic,  ///< the closed form (unoccluded): exact
    Ray,       ///< a delta light and one shadow ray: exact
    Sampled,   ///< mean of `samples` points on an extended light, one shadow ray each
};

struct LightIlluminance {
    std::string name;
    IlluminanceMethod method = IlluminanceMethod::Analytic;
    double lux = 0.0;
    double stderr_lux = 0.0;  ///< standard error of the mean (sampled only)
    int samples = 0;          ///< shadow rays traced (0 for analytic)
};

struct IlluminanceProbe {
    double lux = 0.0;  ///< sum over lights
    std::vector<LightIlluminance> per_light;
};

/// Illuminance in lux at `at` on a surface of unit normal `normal` (light from the side the
/// normal points to). Without `shadows`, or for a light with "shadows": "none", or in a scene
/// without surfaces, each light's closed form (unshadowed_irradiance). With them, delta lights
/// take one shadow ray and extended lights the plain unbiased mean of `samples` samples, each
/// times its visibility, generators keyed by (light, sample, seed). Media are left out: this is
/// the illuminance a meter would read in clear air.
IlluminanceProbe probe_illuminance(const SceneRuntime& scene, const Vec3& at, const Vec3& normal,
                                   bool shadows, int samples);

/// "analytic", "ray" or "sampled".
std::string illuminance_method_name(IlluminanceMethod method);

}  // namespace kasumi
