#pragma once
/// Reads an "atmosphere" object of a scene (keys in docs/scene-format.md and docs/sky.md).
#include "core/json_node.h"
#include "volume/atmosphere.h"

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

/// Value at lambda_nm of three values given at rgb_nm (any order), power-law interpolated.
double interpolate_rgb_coefficient(const double rgb[3], const std::vector<double>& rgb_nm,
                                   double lambda_nm);

}  // namespace kasumi
