#pragma once
/// Particle size distributions for polydisperse Mie scattering: number densities n(r) per unit
/// radius (r in µm), normalised so ∫ n(r) dr = 1.
#include <variant>

namespace kasumi {

/// Log-normal: n(r) = exp(-(ln r - ln r_g)² / (2 sigma²)) / (r sigma sqrt(2π)), with median
/// radius r_g in µm (> 0) and sigma = ln of the geometric standard deviation (> 0).
struct LogNormalSizes {
    double median_radius_um = 1.0;
    double sigma = 0.3;
};

/// Deirmendjian's modified gamma (Deirmendjian 1969, "Electromagnetic Scattering on Spherical
/// Polydispersions", eq. 2.40): n(r) ∝ r^alpha exp(-b r^gamma), written with the mode radius
/// r_c (µm, > 0), alpha > 0, gamma > 0, so b = alpha / (gamma r_c^gamma).
/// Deirmendjian's cloud C.1 is alpha = 6, gamma = 1, r_c = 4 µm.
struct ModifiedGammaSizes {
    double mode_radius_um = 4.0;
    double alpha = 6.0;
    double gamma = 1.0;
};

using SizeDistribution = std::variant<LogNormalSizes, ModifiedGammaSizes>;

/// n(r) per µm, normalised to 1 over r in (0, ∞).
double number_density(const SizeDistribution& d, double radius_um);

/// A radius interval holding all but ~1e-12 of ∫ n(r) r² Q dr for Q bounded (the scattering
/// weight r² shifts the mass to larger radii than n(r) alone).
void scattering_radius_range(const SizeDistribution& d, double& r_min_um, double& r_max_um);

/// The radius at which n(r) r³ (scattering weight per unit ln r) peaks, in µm.
double dominant_radius_um(const SizeDistribution& d);

}  // namespace kasumi
