#pragma once
/// A spherical planet's atmosphere: Rayleigh scattering by air molecules, Mie scattering and
/// absorption by aerosols, absorption by ozone, a Lambertian ground. Coefficients per metre at
/// a set of wavelengths ("bands"); densities are dimensionless profiles of altitude. The model
/// is Bruneton's (Bruneton 2017, "A Qualitative and Quantitative Evaluation of 8 Clear Sky
/// Models", IEEE TVCG 23(12); and his precomputed_atmospheric_scattering code), also used by
/// Hillaire 2020. Geometry in double precision: the world origin is on the ground, +y up, the
/// planet centre at (0, -ground_radius_m, 0).
#include "core/math.h"
#include "phase/phase_function.h"
#include "phase/rayleigh.h"

#include <array>
#include <vector>

namespace kasumi {

/// Bands at most (spectral mode wavelengths or the three RGB-mode wavelengths).
inline constexpr int kMaxBands = 64;
using Bands = std::array<double, kMaxBands>;

/// One layer of a density profile: d(h) = exp_term exp(exp_scale_per_m h) + linear_per_m h +
/// constant_term (h altitude in metres), clamped to [0, 1] (Bruneton 2017, DensityProfileLayer).
struct DensityLayer {
    double exp_term = 0.0;
    double exp_scale_per_m = 0.0;
    double linear_per_m = 0.0;
    double constant_term = 0.0;

    double density(double h) const;
};

/// Two layers: `lower` below `lower_width_m`, `upper` above (a single layer: width 0).
struct DensityProfile {
    double lower_width_m = 0.0;
    DensityLayer lower;
    DensityLayer upper;

    double density(double h) const {
        return h < lower_width_m ? lower.density(h) : upper.density(h);
    }
    /// exp(-h / scale_height_m), the profile of well-mixed gases and aerosols.
    static DensityProfile exponential(double scale_height_m);
    /// The air of the U.S. Standard Atmosphere 1976 (NOAA/NASA/USAF, Table I) relative to sea
    /// level (1.2250 kg/m³) in two exponential layers through its densities at 0, 11 km
    /// (0.36392 kg/m³) and 32 km (0.013225, within 0.3%): scale height 9063 m in the
    /// troposphere and 6341.6 m above 11 km (the isothermal 216.65 K stratosphere,
    /// H = R T / (M g0)); within 4% of the table up to 11 km and 6% up to 40 km. The single
    /// 8 km exponential has 1.1-1.6 times the real air at 20-30 km, where twilight is made.
    static DensityProfile us_standard_1976();
    /// A tent: 0 at centre ± half_width, 1 at the centre (the ozone layer of Bruneton 2017).
    static DensityProfile tent(double center_m, double half_width_m);
    /// Integral of the density over altitude from the ground to top_altitude_m, metres (the
    /// equivalent thickness of the layer at density 1). Trapezoid rule on a 1 m grid: exact on
    /// linear pieces, relative error below 1e-8 for exponentials with scale heights > 100 m.
    double column_m(double top_altitude_m) const;
};

/// A species: coefficients at density 1, per band, 1/m.
struct AtmosphereSpecies {
    Bands scattering{};
    Bands absorption{};
    DensityProfile profile;
};

struct Atmosphere {
    int bands = 3;
    std::vector<double> wavelengths_nm{680.0, 550.0, 440.0};
    double ground_radius_m = 6360e3;
    double top_radius_m = 6460e3;
    Bands ground_albedo{};  ///< Lambertian reflectance of the ground per band
    AtmosphereSpecies rayleigh;
    AtmosphereSpecies mie;
    AtmosphereSpecies ozone;  ///< absorption only
    /// Depolarisation factor rho of the Rayleigh phase per band (rayleigh_phase); standard
    /// air's, consistent with the King factor of its cross section, unless the scene sets it.
    Bands rayleigh_depolarization{};
    PhaseFunction mie_phase = CornetteShanks{0.8f};

    DVec3 center() const { return DVec3(0.0, -ground_radius_m, 0.0); }
    /// Distance from the planet centre of world point p, metres.
    double radius(const DVec3& p) const { return glm::length(p - center()); }
};

/// Extinction and scattering at one point, 1/m per band.
struct AtmosphereCoefficients {
    Bands sigma_t{};
    Bands sigma_s_rayleigh{};
    Bands sigma_s_mie{};
};

/// Coefficients at altitude h above the ground (metres).
AtmosphereCoefficients atmosphere_coefficients(const Atmosphere& a, double h);
/// The same into `out`, writing the atmosphere's bands only (no 3 x 64-band clearing per call:
/// the marches' inner loops reuse one `out`).
void atmosphere_coefficients(const Atmosphere& a, double h, AtmosphereCoefficients& out);

/// Rayleigh phase function of band `band`, per steradian: Chandrasekhar's form with the band's
/// depolarisation factor rho (Bucholtz 1995, eq. 12; phase/rayleigh.h),
/// 3 / (16 pi (1 + 2 gamma)) ((1 + 3 gamma) + (1 - gamma) mu²), gamma = rho / (2 - rho);
/// rho = 0 gives 3 / (16 pi) (1 + mu²).
inline double rayleigh_phase(const Atmosphere& a, int band, double mu) {
    return rayleigh_phase(a.rayleigh_depolarization[band], mu);
}
/// The Rayleigh phase of every band at scattering cosine mu.
inline void rayleigh_phase_bands(const Atmosphere& a, double mu, Bands& out) {
    for (int i = 0; i < a.bands; ++i)
        out[i] = rayleigh_phase(a, i, mu);
}
/// The one Rayleigh phase function directions are drawn from where every band shares a sample
/// (the reference's Monte Carlo orders): the band-mean depolarisation. Each band then weights
/// the sample by its own phase over this pdf (unbiased: the pdf is positive everywhere).
Rayleigh rayleigh_sampling_phase(const Atmosphere& a);

/// King correction factor of standard air F_K = (6 + 3 rho) / (6 - 7 rho) at lambda_nm: the
/// factors of N2 and O2 of Bates 1984 (Planet. Space Sci. 32, 785), Ar 1, CO2 1.15, weighted
/// by volume mixing ratio (Bodhaine et al. 1999, J. Atmos. Oceanic Technol. 16, 1854, eqs.
/// 23-27; CO2 at 360 ppm).
double king_factor_standard_air(double lambda_nm);
/// Depolarisation factor of standard air at lambda_nm, the rho of that King factor:
/// rho = 6 (F_K - 1) / (3 + 7 F_K): 0.0305 at 360 nm, 0.0283 at 550 nm, 0.0276 at 830 nm.
double rayleigh_depolarization_standard_air(double lambda_nm);

/// Rayleigh scattering coefficient of standard air (288.15 K, 1013.25 hPa) at lambda_nm, 1/m:
/// sigma = 24 pi³ (n² - 1)² / (lambda⁴ N² (n² + 2)²) F_K N (Bucholtz 1995, Appl. Opt. 34(15)
/// 2765, eqs. 2 and 8), with n of standard air from Peck & Reeder 1972 (J. Opt. Soc. Am. 62,
/// 958, eq. 2), N = 2.54743e25 m⁻³ (Bucholtz) and the King factor F_K of air from Bates 1984
/// (Planet. Space Sci. 32, 785) as combined by Bodhaine et al. 1999 (J. Atmos. Oceanic Technol.
/// 16, 1854, eq. 23; 360 ppm CO2).
double rayleigh_scattering_standard_air(double lambda_nm);

/// Per-molecule Rayleigh cross section of standard air, m².
double rayleigh_cross_section_m2(double lambda_nm);

/// Where the ray p + t d (d unit) meets a sphere about the planet centre of radius r_sphere:
/// the two roots (t0 <= t1), or false when it misses.
bool intersect_sphere(const Atmosphere& a, const DVec3& p, const DVec3& d, double r_sphere,
                      double& t0, double& t1);

/// The part [t_enter, t_exit] of the ray inside the atmosphere, ending at the ground when the
/// ray hits it (`hits_ground`). False when the ray misses the atmosphere.
bool atmosphere_segment(const Atmosphere& a, const DVec3& p, const DVec3& d, double& t_enter,
                        double& t_exit, bool& hits_ground);

}  // namespace kasumi
