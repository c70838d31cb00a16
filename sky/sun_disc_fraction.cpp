#include "sky/sun_disc_fraction.h"

#include "sky/sky_reference.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

HorizonAt horizon_at(double r, double rg, const SkyLuts::SunDisc& sun) {
    HorizonAt h;
    h.cos_h = std::min(1.0, rg / r);
    h.sin_horizon = -std::sqrt(std::max(0.0, 1.0 - h.cos_h * h.cos_h));
    h.upper = h.sin_horizon * sun.cos_radius + h.cos_h * sun.sin_radius;  // sin(horizon + radius)
    h.lower = h.sin_horizon * sun.cos_radius - h.cos_h * sun.sin_radius;  // sin(horizon - radius)
    return h;
}

double sun_disc_fraction(const HorizonAt& h, double mu_s, const SkyLuts::SunDisc& sun) {
    if (mu_s > h.upper + 1e-9)
        return 1.0;
    // sin is increasing on [-pi/2, pi/2]: valid while horizon - radius > -pi/2, i.e.
    // cos_h > sin(radius) (the horizon is not near the nadir).
    if (h.cos_h > sun.sin_radius && mu_s < h.lower - 1e-9)
        return 0.0;
    return disc_fraction_above(std::asin(std::clamp(mu_s, -1.0, 1.0)) + std::acos(h.cos_h),
                               sun.radius);
}

double sun_disc_fraction(double r, double mu_s, double rg, const SkyLuts::SunDisc& sun,
                         double& sin_horizon) {
    const HorizonAt h = horizon_at(r, rg, sun);
    sin_horizon = h.sin_horizon;
    return sun_disc_fraction(h, mu_s, sun);
}

}  // namespace kasumi
