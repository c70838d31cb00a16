// CIE 1931 tables, the XYZ -> Rec.709 matrix and Planck's law against published figures.
#include "core/spectrum.h"
#include "core/cie_1931.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(Spectrum, PlanckAt2856KHasTheChromaticityOfCieIlluminantA) {
    // CIE illuminant A is by definition a Planckian radiator at 2856 K (c2 = 1.4388e-2 m K;
    // CODATA 2018 hc/k = 1.438777e-2 differs by 0.05 K here). Its chromaticity is published as
    // x = 0.44757, y = 0.40745 (CIE 15:2004, Table T.3; ISO 11664-2). The 5 nm CMF table over
    // 360-830 nm reproduces it to ~4e-5; a wrong row of the table, a swapped CMF column or a
    // wrong c2 = hc/k moves it by more than the 2e-4 allowed.
    glm::dvec3 xyz(0.0);
    for (int i = 0; i < kCieSamples; ++i) {
        const double b = planck_radiance(kCieFirstNm + kCieStepNm * i, 2856.0);
        xyz += b * glm::dvec3(kCie1931[i][0], kCie1931[i][1], kCie1931[i][2]);
    }
    const double sum = xyz.x + xyz.y + xyz.z;
    EXPECT_NEAR(xyz.x / sum, 0.44757, 2e-4);
    EXPECT_NEAR(xyz.y / sum, 0.40745, 2e-4);
}

TEST(Spectrum, PlanckIntegratesToStefanBoltzmann) {
    // π ∫ B(λ, T) dλ = σ T⁴ with σ = 5.670374419e-8 W m⁻² K⁻⁴ (CODATA 2018, exact from h, c, k).
    // Simpson's rule in ln λ from 10 nm to 1 mm (outside, < 1e-9 of the total at 5772 K).
    const double t = 5772.0;
    const int n = 20000;
    const double a = std::log(10.0), b = std::log(1e6), h = (b - a) / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double nm = std::exp(a + h * i);
        const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * planck_radiance(nm, t) * nm;  // dλ = λ d(ln λ), per nm
    }
    const double exitance = kPiD * sum * h / 3.0;
    EXPECT_NEAR(exitance, 5.670374419e-8 * std::pow(t, 4), 1e-6 * 5.670374419e-8 * std::pow(t, 4));
}

TEST(Spectrum, BinsCoverTheVisibleRange) {
    const auto nm = spectral_wavelengths_nm(47);
    EXPECT_NEAR(nm.front(), 365.0, 1e-9);
    EXPECT_NEAR(nm.back(), 825.0, 1e-9);
}

}  // namespace
}  // namespace kasumi
