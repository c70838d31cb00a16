#include "sky/sun_disc_fraction.h"

#include "sky/sky_reference.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

double sun_disc_fraction(double r, double mu_s, double rg, const SkyLuts::SunDisc& sun,
                         double& sin_horizon) {
    const double cos_h = std::min(1.0, rg / r);
    sin_horizon = -std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
    const double cos_rad = sun.cos_radius, sin_rad = sun.sin_radius;
    const double upper = sin_horizon * cos_rad + cos_h * sin_rad;  // sin(horizon + radius)
    if (mu_s > upper + 1e-9)
        return 1.0;
    const double lower = sin_horizon * cos_rad - cos_h * sin_rad;  // sin(horizon - radius)
    // sin is increasing on [-pi/2, pi/2]: valid while horizon - radius > -pi/2, i.e.
    // cos_h > sin(radius) (the horizon is not near the nadir).
    if (cos_h > sin_rad && mu_s < lower - 1e-9)
        return 0.0;
    return disc_fraction_above(std::asin(std::clamp(mu_s, -1.0, 1.0)) + std::acos(cos_h),
                               sun.radius);
}

}  // namespace kasumi
