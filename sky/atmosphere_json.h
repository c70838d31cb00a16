#pragma once
/// Reads an "atmosphere" object of a scene (keys in docs/scene-format.md and docs/sky.md).
#include "core/json_node.h"
#include "sky/atmosphere.h"

#include <vector>

namespace kasumi {

/// Parses `node` into an Atmosphere with coefficients at `wavelengths_nm`. Coefficients given
/// as three numbers are the values at `rgb_wavelengths_nm` (the RGB mode's red, green, blue);
/// other wavelengths interpolate them as a power law of wavelength between neighbouring nodes
/// (exact for Rayleigh's lambda^-4 and Angstrom's aerosol law). Errors name file and path.
Atmosphere parse_atmosphere(const JsonNode& node, const std::vector<double>& wavelengths_nm,
                            const std::vector<double>& rgb_wavelengths_nm);

/// Earth defaults of Bruneton 2017 / Hillaire 2020 at 680, 550, 440 nm (see docs/sky.md).
Atmosphere default_earth_atmosphere(const std::vector<double>& wavelengths_nm,
                                    const std::vector<double>& rgb_wavelengths_nm);

/// Peak number density of ozone, molecules/m³, that puts column_du Dobson units in `profile`
/// between the ground and top_altitude_m: column_du * kDobsonUnitPerM2 / profile.column_m(top).
/// Bruneton 2017: 300 DU in the 25 ± 15 km tent, 5.374e18 m⁻³.
double ozone_peak_number_density(const DensityProfile& profile, double top_altitude_m,
                                 double column_du);

/// Ozone absorption at density 1, 1/m: the 233 K cross section (core/reference_spectra.h) at
/// each wavelength times peak_number_density.
Bands ozone_absorption_auto(const std::vector<double>& wavelengths_nm, double peak_number_density);

/// Value at lambda_nm of three values given at rgb_nm (any order), power-law interpolated.
double interpolate_rgb_coefficient(const double rgb[3], const std::vector<double>& rgb_nm,
                                   double lambda_nm);

}  // namespace kasumi
