// Photometric constants, the CIE photopic luminosity function and the built-in solar spectrum
// against published tables (values typed from the sources cited at each test, not from our
// own output).
#include "core/cie_1931.h"
#include "core/reference_spectra.h"
#include "core/spectrum.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

namespace kasumi {
namespace {

TEST(PublishedPhotometry, MaximumLuminousEfficacyIs683LumensPerWattAt540Terahertz) {
    // SI brochure (BIPM 2019, 9th ed., §2.3.1): the luminous efficacy of monochromatic radiation
    // of frequency 540e12 Hz is exactly 683 lm/W. That frequency is 555.171 nm in vacuum and
    // 555.016 nm in standard air (n = 1.000278 there, Peck & Reeder 1972), the medium CIE
    // tabulates V(lambda) = ybar in; V is 1 at 555 nm (CIE 15:2004) and flat to 1e-5 around it.
    const double lambda_vacuum_nm = 299792458.0 / 540e12 * 1e9;
    EXPECT_NEAR(lambda_vacuum_nm, 555.171, 1e-3);
    const double lambda_air_nm = lambda_vacuum_nm / 1.000278;
    EXPECT_NEAR(lambda_air_nm, 555.016, 1e-3);
    EXPECT_NEAR(kLuminousEfficacy * cie_1931_cmf(lambda_air_nm).y, 683.0, 0.02);
    EXPECT_EQ(cie_1931_cmf(555.0).y, 1.0);
}

TEST(PublishedPhotometry, PhotopicLuminosityFunctionMatchesTheCieTable) {
    // CIE 1931 2-degree ybar = V(lambda) (CIE 15:2004, Table T.4; ISO 23539:2005/CIE S 010),
    // including the symmetric half-maximum pair at 510 and 610 nm.
    struct Row {
        double nm, v;
    };
    for (const Row r : {Row{400.0, 0.000396}, Row{450.0, 0.038}, Row{500.0, 0.323},
                        Row{510.0, 0.503}, Row{550.0, 0.995}, Row{600.0, 0.631}, Row{610.0, 0.503},
                        Row{650.0, 0.107}, Row{700.0, 0.004102}})
        EXPECT_NEAR(cie_1931_cmf(r.nm).y, r.v, 1e-6 + 1e-4 * r.v) << r.nm << " nm";
}

double mean(const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

TEST(PublishedSolarSpectrum, BinMeansOfAstmG173SitAtTheirBinCentres) {
    // ASTM G173-03, extraterrestrial (ETR) column, W m^-2 nm^-1 (NREL distribution,
    // ASTMG173.csv): every sample in [380, 400) nm (0.5 nm steps) and [400, 410), [550, 560)
    // nm (1 nm steps). The built-in table holds Bruneton's means of these bins; each mean must
    // be the table's value at the bin centre. Placed at the bin's lower edge instead (as in
    // Bruneton's demo), 395 nm would read 1.437 instead of 1.147 (the Ca II H and K lines at
    // 393.4 and 396.8 nm) and 555 nm would be 0.44% low.
    struct Bin {
        double lower_nm;
        std::vector<double> samples;
    };
    const std::vector<Bin> bins = {
        {380.0,
         {1.152,  1.231,  1.249,   1.1224, 0.95426, 0.82313, 0.73603, 0.71095, 0.821, 0.9862,
          1.0802, 1.0296, 0.99113, 1.0279, 1.0354,  1.0186,  1.0067,  0.99743, 1.081, 1.1958}},
        {390.0, {1.2519, 1.2601, 1.3322, 1.349,  1.24,  1.0312,  0.745, 0.5912, 0.76675, 1.0557,
                 1.245,  1.3245, 1.1626, 0.8433, 0.652, 0.96142, 1.301, 1.5342, 1.6245,  1.6717}},
        {400.0, {1.6885, 1.752, 1.814, 1.74, 1.763, 1.715, 1.666, 1.63, 1.699, 1.809}},
        {550.0, {1.863, 1.859, 1.896, 1.842, 1.878, 1.889, 1.857, 1.812, 1.853, 1.755}},
    };
    const WavelengthTable& solar = solar_irradiance_astm_g173();
    for (const Bin& b : bins) {
        const double published = mean(b.samples);
        // Bruneton printed 6 significant digits.
        EXPECT_NEAR(solar.at(b.lower_nm + 5.0), published, 2e-5 * published) << b.lower_nm;
    }
}

TEST(PublishedSolarSpectrum, TableCoversTheCieRange) {
    // Every wavelength the CIE 1931 functions cover (360-830 nm) has a solar value.
    const WavelengthTable& solar = solar_irradiance_astm_g173();
    EXPECT_TRUE(solar.covers(kCieFirstNm));
    EXPECT_TRUE(solar.covers(kCieFirstNm + kCieStepNm * (kCieSamples - 1)));
}

}  // namespace
}  // namespace kasumi
