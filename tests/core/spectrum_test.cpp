// CIE 1931 tables, the XYZ -> Rec.709 matrix and Planck's law against published figures.
#include "core/spectrum.h"
#include "core/cie_1931.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

TEST(Spectrum, YbarIsOneAt555AndIntegratesToThePublishedSum) {
    EXPECT_DOUBLE_EQ(cie_1931_cmf(555.0).y, 1.0);
    // CIE 15:2004: sum of ybar over 360-830 nm at 5 nm steps is 21.371 (x 5 nm = 106.857).
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int i = 0; i < kCieSamples; ++i) {
        sx += kCie1931[i][0];
        sy += kCie1931[i][1];
        sz += kCie1931[i][2];
    }
    EXPECT_NEAR(sy * 5.0, 106.857, 0.02);
    // The equal-energy illuminant E has x = y = z = 1/3: the three sums agree within 0.1%.
    EXPECT_NEAR(sx / sy, 1.0, 1e-3);
    EXPECT_NEAR(sz / sy, 1.0, 1e-3);
}

TEST(Spectrum, D65WhiteMapsToEqualRgb) {
    // D65 white point (x, y) = (0.3127, 0.3290), Y = 1.
    const double x = 0.3127, y = 0.3290;
    const glm::dvec3 xyz(x / y, 1.0, (1.0 - x - y) / y);
    const glm::dvec3 rgb = xyz_to_rec709(xyz);
    EXPECT_NEAR(rgb.r, 1.0, 1e-3);
    EXPECT_NEAR(rgb.g, 1.0, 1e-3);
    EXPECT_NEAR(rgb.b, 1.0, 1e-3);
}

TEST(Spectrum, PlanckPeakFollowsWiensLaw) {
    // Wien's displacement constant b = 2.897771955e-3 m K (CODATA 2018).
    const double t = 5772.0;
    const double peak_nm = 2.897771955e-3 / t * 1e9;
    EXPECT_GT(planck_radiance(peak_nm, t), planck_radiance(peak_nm - 5.0, t));
    EXPECT_GT(planck_radiance(peak_nm, t), planck_radiance(peak_nm + 5.0, t));
}

TEST(Spectrum, BinsCoverTheVisibleRange) {
    const auto nm = spectral_wavelengths_nm(47);
    EXPECT_NEAR(nm.front(), 365.0, 1e-9);
    EXPECT_NEAR(nm.back(), 825.0, 1e-9);
}

}  // namespace
}  // namespace kasumi
