#pragma once
/// The CIE 1931 2° standard colorimetric observer, tabulated every 5 nm from 360 to 830 nm
/// (CIE 15:2004, Table T.4; values as distributed by the CVRL, cvrl.org, "CIE 1931 2-deg XYZ
/// CMFs"). Dimensionless; ybar is the photopic luminous efficiency V(lambda).
#include "core/math.h"

namespace kasumi {

inline constexpr double kCieFirstNm = 360.0;
inline constexpr double kCieStepNm = 5.0;
inline constexpr int kCieSamples = 95;  ///< 360, 365, ..., 830 nm

/// (xbar, ybar, zbar) at 360 + 5 i nm.
extern const double kCie1931[kCieSamples][3];

/// Colour-matching functions at lambda_nm, linearly interpolated; zero outside [360, 830] nm.
glm::dvec3 cie_1931_cmf(double lambda_nm);

}  // namespace kasumi
