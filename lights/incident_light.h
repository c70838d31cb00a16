#pragma once
/// What one light delivers at a point, before occlusion and media.
#include "core/color.h"
#include "core/math.h"

namespace kasumi {

/// Light arriving at a point from one light (or one sample of an extended light).
struct IncidentLight {
    Vec3 wi{0.0f, 1.0f, 0.0f};  ///< unit direction from the point toward the light
    float distance =
        kInfinity;  ///< to the light (or the sampled point on it); kInfinity at infinity
    Vec3 light_position{0.0f};  ///< the light's position, or the sampled point on an extended light
    /// Lux on a surface facing wi (normal incidence). For a sample of an extended light this is
    /// already divided by the sample's pdf: the mean over samples of irradiance * max(0, n.wi)
    /// is an unbiased estimate of the unshadowed illuminance on a surface of normal n.
    Rgb irradiance{0.0f};
};

}  // namespace kasumi
