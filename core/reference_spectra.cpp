#include "core/reference_spectra.h"

namespace kasumi {

namespace {

constexpr int kRows = 48;  // bins [360, 370), ..., [830, 840) nm

std::vector<double> table_nm() {
    std::vector<double> nm(kRows);
    for (int i = 0; i < kRows; ++i)
        nm[static_cast<size_t>(i)] = 360.0 + 10.0 * i;
    return nm;
}

/// The 48 means of [360 + 10 i, 370 + 10 i) nm placed at their bin centres 365, ..., 835 nm,
/// where a bin mean estimates the function (to second order in the bin width), plus flat half
/// bins to 360 and 840 nm so the table still covers the CIE range 360-830 nm. The linear
/// table then integrates to exactly 10 nm times the sum of the means over [360, 840] nm.
WavelengthTable centred_bin_means(const double (&means)[kRows], const char* source) {
    std::vector<double> nm{360.0}, value{means[0]};
    for (int i = 0; i < kRows; ++i) {
        nm.push_back(365.0 + 10.0 * i);
        value.push_back(means[i]);
    }
    nm.push_back(840.0);
    value.push_back(means[kRows - 1]);
    return make_wavelength_table(nm, value, source);
}

// "Reference Solar Spectral Irradiance: ASTM G-173", ETR column, W m^-2 nm^-1, the means of
// the ASTM samples in [360 + 10 i, 370 + 10 i) nm; copied from E. Bruneton,
// precomputed_atmospheric_scattering (2017), atmosphere/demo/demo.cc, kSolarIrradiance, who
// uses each mean as the value at the bin's lower edge (a 5 nm shift: 1.437 instead of 1.147
// at 395 nm, where the Ca II H and K lines sit). We place them at the bin centres.
// data/spectra/solar_astm_g173_etr.csv holds the same table.
constexpr double kSolarIrradiance[kRows] = {
    1.11776, 1.14259, 1.01249, 1.14716, 1.72765, 1.73054, 1.6887,  1.61253, 1.91198, 2.03474,
    2.02042, 2.02212, 1.93377, 1.95809, 1.91686, 1.8298,  1.8685,  1.8931,  1.85149, 1.8504,
    1.8341,  1.8345,  1.8147,  1.78158, 1.7533,  1.6965,  1.68194, 1.64654, 1.6048,  1.52143,
    1.55622, 1.5113,  1.474,   1.4482,  1.41018, 1.36775, 1.34188, 1.31429, 1.28303, 1.26758,
    1.2367,  1.2082,  1.18737, 1.14683, 1.12362, 1.1058,  1.07124, 1.04992};

// Ozone at 233 K, m^2 per molecule (IUP Bremen, Serdyuchenko et al. 2014), each value the mean
// over [lambda, lambda + 10) nm; copied from Bruneton 2017, demo.cc, kOzoneCrossSection.
// Unlike the solar table, each mean stays at its bin's lower edge lambda, Bruneton's
// placement: the default atmosphere then reproduces the ozone coefficients Bruneton 2017 and
// Hillaire 2020 publish (0.650e-6, 1.881e-6, 0.085e-6 1/m at 680, 550, 440 nm); at the bin
// centres they would be 0.721e-6, 1.771e-6, 0.065e-6.
// data/spectra/ozone_cross_section_233k.csv holds the same numbers.
constexpr double kOzoneCrossSection[kRows] = {
    1.18e-27,  2.182e-28, 2.818e-28, 6.636e-28, 1.527e-27, 2.763e-27, 5.52e-27,  8.451e-27,
    1.582e-26, 2.316e-26, 3.669e-26, 4.924e-26, 7.752e-26, 9.016e-26, 1.48e-25,  1.602e-25,
    2.139e-25, 2.755e-25, 3.091e-25, 3.5e-25,   4.266e-25, 4.672e-25, 4.398e-25, 4.701e-25,
    5.019e-25, 4.305e-25, 3.74e-25,  3.215e-25, 2.662e-25, 2.238e-25, 1.852e-25, 1.473e-25,
    1.209e-25, 9.423e-26, 7.455e-26, 6.566e-26, 5.105e-26, 4.15e-26,  4.228e-26, 3.237e-26,
    2.451e-26, 2.801e-26, 2.534e-26, 1.624e-26, 1.465e-26, 2.078e-26, 1.383e-26, 7.105e-27};

}  // namespace

const WavelengthTable& solar_irradiance_astm_g173() {
    static const WavelengthTable t = centred_bin_means(
        kSolarIrradiance, "the built-in ASTM G173-03 extraterrestrial solar spectrum");
    return t;
}

const WavelengthTable& ozone_cross_section_233k() {
    static const WavelengthTable t = make_wavelength_table(
        table_nm(), std::vector<double>(kOzoneCrossSection, kOzoneCrossSection + kRows),
        "the built-in ozone cross section (233 K)");
    return t;
}

}  // namespace kasumi
