#include "sky/atmosphere.h"

namespace kasumi {

double DensityLayer::density(double h) const {
    const double d = exp_term * std::exp(exp_scale_per_m * h) + linear_per_m * h + constant_term;
    return std::clamp(d, 0.0, 1.0);
}

DensityProfile DensityProfile::exponential(double scale_height_m) {
    DensityProfile p;
    p.upper.exp_term = 1.0;
    p.upper.exp_scale_per_m = -1.0 / scale_height_m;
    return p;
}

DensityProfile DensityProfile::us_standard_1976() {
    constexpr double kTropopauseM = 11000.0;
    constexpr double kDensityAtTropopause = 0.36392 / 1.2250;  // Table I, kg/m³ over sea level
    constexpr double kStratosphereScaleM = 6341.6;  // 8.31432 x 216.65 / (0.0289644 x 9.80665)
    const double troposphere_scale_m = kTropopauseM / std::log(1.0 / kDensityAtTropopause);
    DensityProfile p;
    p.lower_width_m = kTropopauseM;
    p.lower.exp_term = 1.0;
    p.lower.exp_scale_per_m = -1.0 / troposphere_scale_m;
    p.upper.exp_term = kDensityAtTropopause * std::exp(kTropopauseM / kStratosphereScaleM);
    p.upper.exp_scale_per_m = -1.0 / kStratosphereScaleM;
    return p;
}

DensityProfile DensityProfile::tent(double center_m, double half_width_m) {
    DensityProfile p;
    p.lower_width_m = center_m;
    p.lower.linear_per_m = 1.0 / half_width_m;
    p.lower.constant_term = 1.0 - center_m / half_width_m;
    p.upper.linear_per_m = -1.0 / half_width_m;
    p.upper.constant_term = 1.0 + center_m / half_width_m;
    return p;
}

double DensityProfile::column_m(double top_altitude_m) const {
    const int n = std::max(1, static_cast<int>(std::ceil(top_altitude_m)));
    const double step = top_altitude_m / n;
    double sum = 0.5 * (density(0.0) + density(top_altitude_m));
    for (int i = 1; i < n; ++i)
        sum += density(step * i);
    return sum * step;
}

AtmosphereCoefficients atmosphere_coefficients(const Atmosphere& a, double h) {
    AtmosphereCoefficients c;
    atmosphere_coefficients(a, h, c);
    return c;
}

void atmosphere_coefficients(const Atmosphere& a, double h, AtmosphereCoefficients& c) {
    const double d_r = a.rayleigh.profile.density(h);
    const double d_m = a.mie.profile.density(h);
    const double d_o = a.ozone.profile.density(h);
    for (int i = 0; i < a.bands; ++i) {
        c.sigma_s_rayleigh[i] = d_r * a.rayleigh.scattering[i];
        c.sigma_s_mie[i] = d_m * a.mie.scattering[i];
        c.sigma_t[i] = c.sigma_s_rayleigh[i] + d_r * a.rayleigh.absorption[i] + c.sigma_s_mie[i] +
                       d_m * a.mie.absorption[i] +
                       d_o * (a.ozone.scattering[i] + a.ozone.absorption[i]);
    }
}

Rayleigh rayleigh_sampling_phase(const Atmosphere& a) {
    double sum = 0.0;
    for (int i = 0; i < a.bands; ++i)
        sum += a.rayleigh_depolarization[i];
    return Rayleigh{static_cast<float>(a.bands > 0 ? sum / a.bands : 0.0)};
}

double king_factor_standard_air(double lambda_nm) {
    const double lambda_um = lambda_nm * 1e-3;
    const double s2 = 1.0 / (lambda_um * lambda_um);  // wavenumber squared, 1/µm²
    // Bates 1984 King factors of N2 and O2 (Bodhaine eqs. 24, 25); Ar 1, CO2 1.15 (eqs. 26,
    // 27); weighted by volume mixing ratio (eq. 23, CO2 at 360 ppm).
    const double f_n2 = 1.034 + 3.17e-4 * s2;
    const double f_o2 = 1.096 + 1.385e-3 * s2 + 1.448e-4 * s2 * s2;
    return (78.084 * f_n2 + 20.946 * f_o2 + 0.934 * 1.0 + 0.036 * 1.15) /
           (78.084 + 20.946 + 0.934 + 0.036);
}

double rayleigh_depolarization_standard_air(double lambda_nm) {
    const double f = king_factor_standard_air(lambda_nm);
    return 6.0 * (f - 1.0) / (3.0 + 7.0 * f);
}

double rayleigh_cross_section_m2(double lambda_nm) {
    const double lambda_um = lambda_nm * 1e-3;
    const double s2 = 1.0 / (lambda_um * lambda_um);  // wavenumber squared, 1/µm²
    // Peck & Reeder 1972, eq. 2: (n - 1) 1e8 of standard air (15 °C, 101325 Pa, dry, 300 ppm).
    const double n_minus_1 =
        (8060.51 + 2480990.0 / (132.274 - s2) + 17455.7 / (39.32957 - s2)) * 1e-8;
    const double n = 1.0 + n_minus_1;
    const double f_king = king_factor_standard_air(lambda_nm);
    constexpr double kNumberDensity = 2.54743e25;  // m⁻³, Bucholtz 1995 at 288.15 K, 1013.25 hPa
    const double lambda_m = lambda_nm * 1e-9;
    const double n2 = n * n;
    const double ratio = (n2 - 1.0) / (n2 + 2.0);
    return 24.0 * kPiD * kPiD * kPiD * ratio * ratio /
           (std::pow(lambda_m, 4) * kNumberDensity * kNumberDensity) * f_king;
}

double rayleigh_scattering_standard_air(double lambda_nm) {
    return rayleigh_cross_section_m2(lambda_nm) * 2.54743e25;
}

bool intersect_sphere(const Atmosphere& a, const DVec3& p, const DVec3& d, double r_sphere,
                      double& t0, double& t1) {
    // |o + t d|² = R² with o relative to the centre; b = o.d, c = |o|² - R². The discriminant
    // is formed as R² - |o - b d|² (the squared distance of closest approach), which keeps its
    // precision for rays tangent to a sphere of planetary radius.
    const DVec3 o = p - a.center();
    const double b = glm::dot(o, d);
    const DVec3 closest = o - b * d;
    const double disc = r_sphere * r_sphere - glm::dot(closest, closest);
    if (disc < 0.0)
        return false;
    const double s = std::sqrt(disc);
    const double c = glm::dot(o, o) - r_sphere * r_sphere;
    // Stable roots: q = -(b + sign(b) s); t0 = q, t1 = c / q (Press et al., Numerical Recipes).
    const double q = -(b + std::copysign(s, b));
    double r0 = q, r1 = q != 0.0 ? c / q : -b;
    if (r0 > r1)
        std::swap(r0, r1);
    t0 = r0;
    t1 = r1;
    return true;
}

bool atmosphere_segment(const Atmosphere& a, const DVec3& p, const DVec3& d, double& t_enter,
                        double& t_exit, bool& hits_ground) {
    hits_ground = false;
    double t0 = 0.0, t1 = 0.0;
    if (!intersect_sphere(a, p, d, a.top_radius_m, t0, t1) || t1 <= 0.0)
        return false;
    t_enter = std::max(t0, 0.0);
    t_exit = t1;
    // Only a ray heading toward the centre can meet the ground; a tangent ray from ground level
    // (b = 0) grazes it and goes on. Points rounded just below the ground hit it at once.
    double g0 = 0.0, g1 = 0.0;
    if (glm::dot(p - a.center(), d) < 0.0 && intersect_sphere(a, p, d, a.ground_radius_m, g0, g1) &&
        g1 > 0.0) {
        t_exit = std::max(g0, 0.0);
        hits_ground = true;
    }
    return t_exit > t_enter || hits_ground;
}

}  // namespace kasumi
