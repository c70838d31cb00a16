#pragma once
/// Wavelength sets and the conversion of spectral radiance to the working space: CIE 1931 XYZ
/// with 683 lm/W, then linear Rec.709 (D65). Units: nm, W/(m² sr nm), cd/m².
#include "core/color.h"
#include "core/math.h"

#include <vector>

namespace kasumi {

/// Maximum luminous efficacy of radiation for photopic vision, lm/W (CIE 15:2004; the SI
/// definition of the candela fixes 683 lm/W at 540 THz).
inline constexpr double kLuminousEfficacy = 683.0;

/// The wavelengths of RGB mode: the three channels are transported at these (Bruneton & Neyret
/// 2008 and Hillaire 2020 use the same triple), nm.
inline constexpr double kRgbWavelengthsNm[3] = {680.0, 550.0, 440.0};

/// XYZ (Y in the photometric unit) to linear Rec.709 / sRGB primaries, D65 white
/// (IEC 61966-2-1:1999 matrix, as tabulated by Lindbloom).
glm::dvec3 xyz_to_rec709(const glm::dvec3& xyz);

/// n wavelengths at the midpoints of n equal bins covering [360, 830] nm.
std::vector<double> spectral_wavelengths_nm(int n);

/// Width of one bin of spectral_wavelengths_nm(n), nm.
double spectral_bin_nm(int n);

/// Planck's law: spectral radiance of a black body at temperature_k, W/(m² sr nm).
double planck_radiance(double lambda_nm, double temperature_k);

}  // namespace kasumi
