// The atmosphere's Rayleigh phase with the depolarisation of air: Chandrasekhar's form
// p = 3 / (16 pi (1 + 2 gamma)) ((1 + 3 gamma) + (1 - gamma) mu²), gamma = rho / (2 - rho)
// (Bucholtz 1995, Appl. Opt. 34, 2765, eq. 12), with rho the depolarisation of the King factor
// F_K = (6 + 3 rho) / (6 - 7 rho) that the "auto" cross section uses (Bates 1984 through
// Bodhaine et al. 1999, eqs. 23-27). Checked against Bucholtz's table of rho, its closed form,
// normalisation, the reference sky's single scattering, the sampler (chi-square) and the scene
// key atmosphere.rayleigh.depolarization.
//
// False-failure rate: one chi-square test at significance 1e-3 with a fixed seed (a given build
// passes or fails deterministically; with fresh seeds it would fail spuriously once in 1000).
#include "phase/phase_validation.h"
#include "sky/atmosphere.h"
#include "sky/atmosphere_json.h"
#include "sky/sky_reference.h"
#include "sky/sky_scene.h"
#include "tests/input_error.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

const std::vector<double> kRgbNm{680.0, 550.0, 440.0};

/// Bucholtz 1995, Table 1: depolarisation factors rho_n of air (%) from Bates 1984 at the
/// wavelengths he lists (µm). The same numbers are transcribed in the lidar codes that cite him.
struct BucholtzRow {
    double lambda_um, rho_percent;
};
constexpr BucholtzRow kBucholtzTable[] = {
    {0.200, 4.545}, {0.205, 4.384}, {0.210, 4.221}, {0.215, 4.113}, {0.220, 4.004}, {0.225, 3.895},
    {0.230, 3.785}, {0.240, 3.675}, {0.250, 3.565}, {0.260, 3.455}, {0.270, 3.400}, {0.280, 3.289},
    {0.290, 3.233}, {0.300, 3.178}, {0.310, 3.178}, {0.320, 3.122}, {0.330, 3.066}, {0.340, 3.066},
    {0.350, 3.010}, {0.360, 3.010}, {0.370, 3.010}, {0.380, 2.955}, {0.390, 2.955}, {0.400, 2.955},
    {0.450, 2.899}, {0.500, 2.842}, {0.550, 2.842}, {0.600, 2.786}, {0.650, 2.786}, {0.700, 2.786},
    {0.750, 2.786}, {0.800, 2.730}, {0.850, 2.730}, {0.900, 2.730}, {0.950, 2.730}, {1.000, 2.730}};

/// Bucholtz's eq. 12 written out as he gives it, P(Theta) = 3 / (4 (1 + 2 gamma)) ((1 + 3 gamma)
/// + (1 - gamma) cos² Theta), normalised to 4 pi; over 4 pi for a density per steradian.
double bucholtz_eq12(double rho, double cos_theta) {
    const double gamma = rho / (2.0 - rho);
    return 3.0 / (4.0 * (1.0 + 2.0 * gamma)) *
           ((1.0 + 3.0 * gamma) + (1.0 - gamma) * cos_theta * cos_theta) / (4.0 * kPiD);
}

std::vector<double> spectral_nm(int n) {
    std::vector<double> nm;
    for (int i = 0; i < n; ++i)
        nm.push_back(360.0 + (830.0 - 360.0) * (i + 0.5) / n);
    return nm;
}

Atmosphere parse(const std::string& json, const std::vector<double>& nm = kRgbNm) {
    static Json doc;  // nodes refer to it while parsing
    doc = parse_json_text(json, "scene.json");
    return parse_atmosphere(JsonNode(doc, "scene.json"), nm, kRgbNm);
}

TEST(RayleighDepolarization, StandardAirMatchesBucholtzTable) {
    // Bucholtz's rho are Bates's King factors of air rounded to 1e-3 (rho steps of 5.6e-4);
    // ours are Bates's fits for N2 and O2 combined by Bodhaine eq. 23: within 2% of the table
    // from 400 to 1000 nm and 3% below (0.2-0.39 µm, where the fits and the rounded table part
    // most). The King factor itself is (6 + 3 rho) / (6 - 7 rho) of the same rho.
    for (const BucholtzRow& row : kBucholtzTable) {
        const double nm = row.lambda_um * 1e3;
        const double rho = rayleigh_depolarization_standard_air(nm);
        const double table = row.rho_percent * 1e-2;
        EXPECT_NEAR(rho / table, 1.0, nm >= 400.0 ? 0.02 : 0.03) << nm << " nm";
        const double f = king_factor_standard_air(nm);
        EXPECT_NEAR(f, (6.0 + 3.0 * rho) / (6.0 - 7.0 * rho), 1e-12) << nm << " nm";
    }
    // Depolarisation falls with wavelength (Bates 1984).
    EXPECT_GT(rayleigh_depolarization_standard_air(360.0),
              rayleigh_depolarization_standard_air(830.0));
}

TEST(RayleighDepolarization, PhaseIsBucholtzClosedFormAndNormalised) {
    // Every band of a spectral atmosphere and of the RGB one, default depolarisation ("auto").
    for (const std::vector<double>& nm : {kRgbNm, spectral_nm(24)}) {
        const Atmosphere a = default_earth_atmosphere(nm, kRgbNm);
        for (int b = 0; b < a.bands; ++b) {
            const double rho = rayleigh_depolarization_standard_air(nm[static_cast<size_t>(b)]);
            EXPECT_DOUBLE_EQ(a.rayleigh_depolarization[b], rho);
            for (double mu = -1.0; mu <= 1.0; mu += 0.125)
                EXPECT_NEAR(rayleigh_phase(a, b, mu) / bucholtz_eq12(rho, mu), 1.0, 1e-12);
            // 2 pi ∫ p dmu = 1 and 2 pi ∫ mu p dmu = 0: Simpson's rule, exact for the
            // quadratic (and the cubic) up to rounding.
            constexpr int n = 64;
            double norm = 0.0, mean = 0.0;
            for (int k = 0; k <= n; ++k) {
                const double mu = -1.0 + 2.0 * k / n;
                const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
                norm += w * rayleigh_phase(a, b, mu);
                mean += w * mu * rayleigh_phase(a, b, mu);
            }
            const double h = 2.0 / n;
            EXPECT_NEAR(2.0 * kPiD * norm * h / 3.0, 1.0, 1e-12);
            EXPECT_NEAR(2.0 * kPiD * mean * h / 3.0, 0.0, 1e-12);
        }
    }
    // Against the table's rho at 550 nm (2.842%): the phase within 2e-4 at every angle (our
    // rho, 2.832%, differs by 1e-4 absolute; p moves by about rho / 2 relative per unit rho).
    const Atmosphere a = default_earth_atmosphere({550.0}, kRgbNm);
    for (double mu = -1.0; mu <= 1.0; mu += 0.25)
        EXPECT_NEAR(rayleigh_phase(a, 0, mu) / bucholtz_eq12(0.02842, mu), 1.0, 2e-4);
    // The depolarised phase is flatter: forward and backward 1.4% below the old one, at 90°
    // 1.4% above ((1 + gamma) / (1 + 2 gamma) and (1 + 3 gamma) / (1 + 2 gamma), gamma = 0.0144).
    EXPECT_NEAR(rayleigh_phase(a, 0, 1.0) / (3.0 / (8.0 * kPiD)), 1.0 - 0.014, 1e-3);
    EXPECT_NEAR(rayleigh_phase(a, 0, 0.0) / (3.0 / (16.0 * kPiD)), 1.0 + 0.014, 1e-3);
}

/// Reference single scattering (Rayleigh only, black ground) from 1.5 m along elevation and
/// azimuth, sun 20° up at azimuth 180°.
Bands single_scattering(const Atmosphere& air, double elev_deg, double az_deg) {
    Atmosphere a = air;
    a.mie.scattering.fill(0.0);
    a.mie.absorption.fill(0.0);
    a.ozone.absorption.fill(0.0);
    a.ground_albedo.fill(0.0);
    SunDesc sun;
    sun.elevation_deg = 20.0;
    sun.azimuth_deg = 180.0;
    SkySettings settings;
    settings.mode = SkyMode::Reference;
    settings.view_steps = 256;
    settings.sun_steps = 64;
    const auto sky = make_sky_scene(a, sun, settings);
    Pcg32 rng(1, 2);
    return reference_sky(*sky, DVec3(0.0, 1.5, 0.0), sun_direction(elev_deg, az_deg), 1e30, false,
                         1, rng)
        .radiance;
}

TEST(RayleighDepolarization, SkySingleScatteringRatioFollowsThePhase) {
    // Looking at the sun (Theta = 0) and 90° from it at the same elevation (azimuth 90°): the
    // ratio of single-scattered radiance with depolarisation to that without is, per band, the
    // ratio of the phases, p_rho(1) / p_rho(0) over p_0(1) / p_0(0) = (1 + gamma) / (1 + 3 gamma)
    // (the path integrals cancel), 0.975 at 550 nm. With the phase of rho = 0 it would be 1.
    for (const std::vector<double>& nm : {kRgbNm, spectral_nm(8)}) {
        const Atmosphere depolarised = default_earth_atmosphere(nm, kRgbNm);
        Atmosphere plain = depolarised;
        plain.rayleigh_depolarization.fill(0.0);
        const Bands toward = single_scattering(depolarised, 20.0, 180.0);
        const Bands side = single_scattering(depolarised, 20.0, 90.0);
        const Bands toward_0 = single_scattering(plain, 20.0, 180.0);
        const Bands side_0 = single_scattering(plain, 20.0, 90.0);
        // Scattering cosine at 90° of azimuth, both 20° up: sin² 20°.
        const double mu_side = std::pow(std::sin(20.0 * kPiD / 180.0), 2);
        for (int b = 0; b < depolarised.bands; ++b) {
            const double rho = depolarised.rayleigh_depolarization[b];
            const double expected = (bucholtz_eq12(rho, 1.0) / bucholtz_eq12(rho, mu_side)) /
                                    (bucholtz_eq12(0.0, 1.0) / bucholtz_eq12(0.0, mu_side));
            const double measured = (toward[b] / side[b]) / (toward_0[b] / side_0[b]);
            EXPECT_NEAR(measured / expected, 1.0, 1e-9) << "band " << b;
            EXPECT_LT(expected, 0.98);  // the test can tell the phases apart
        }
    }
}

TEST(RayleighDepolarization, SamplingPhaseIsTheBandMeanAndPassesChiSquare) {
    const Atmosphere a = default_earth_atmosphere(spectral_nm(16), kRgbNm);
    double mean = 0.0;
    for (int b = 0; b < a.bands; ++b)
        mean += a.rayleigh_depolarization[b] / a.bands;
    const Rayleigh sampling = rayleigh_sampling_phase(a);
    EXPECT_NEAR(sampling.rho, mean, 1e-7);
    ValidationOptions options;
    options.seed = 7;
    options.samples = 400000;
    options.significance = 1e-3;
    const ChiSquareResult chi =
        chi_square_test(PhaseFunction(sampling), glm::normalize(Vec3(0.3f, -0.5f, 0.8f)), options);
    EXPECT_TRUE(chi.passed) << chi.table;
}

TEST(RayleighDepolarization, SceneKey) {
    // Default and "auto": standard air per band; a number: that rho at every band; 0 is the
    // phase 3 / (16 pi) (1 + mu²).
    const std::vector<double> nm = spectral_nm(4);
    for (const char* json : {R"({})", R"({"rayleigh": {"depolarization": "auto"}})",
                             R"({"rayleigh": {"scattering": "auto"}})"}) {
        const Atmosphere a = parse(json, nm);
        for (int b = 0; b < a.bands; ++b)
            EXPECT_DOUBLE_EQ(a.rayleigh_depolarization[b],
                             rayleigh_depolarization_standard_air(nm[static_cast<size_t>(b)]));
    }
    const Atmosphere fixed = parse(R"({"rayleigh": {"depolarization": 0.0279}})", nm);
    for (int b = 0; b < fixed.bands; ++b)
        EXPECT_DOUBLE_EQ(fixed.rayleigh_depolarization[b], 0.0279);
    const Atmosphere none = parse(R"({"rayleigh": {"depolarization": 0}})", nm);
    for (double mu : {-1.0, -0.3, 0.0, 0.6, 1.0})
        EXPECT_NEAR(rayleigh_phase(none, 2, mu), 3.0 / (16.0 * kPiD) * (1.0 + mu * mu), 1e-15);
    for (const char* bad :
         {R"({"rayleigh": {"depolarization": -0.01}})", R"({"rayleigh": {"depolarization": 1}})",
          R"({"rayleigh": {"depolarization": "standard"}})",
          R"({"rayleigh": {"depolarization": [0.03, 0.03, 0.03]}})"}) {
        const std::string message = input_error([&] { parse(bad); });
        EXPECT_NE(message.find("/rayleigh/depolarization"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace kasumi
