// The atmosphere's data: the measured solar spectrum as the sun's default (normalisation to
// illuminance_lux, colour, effect on a spectral sky), CSV coefficient tables, and ozone "auto"
// from the cross-section table and a column in Dobson units.
#include "core/error.h"
#include "core/reference_spectra.h"
#include "core/spectrum.h"
#include "sky/atmosphere_json.h"
#include "sky/sky_reference.h"
#include "sky/sky_scene.h"
#include "tests/input_error.h"
#include "tests/scratch_dir.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace kasumi {
namespace {

const std::vector<double> kRgbNm{680.0, 550.0, 440.0};

/// Luminance Y of linear Rec.709: the Y row of the Rec.709 -> XYZ matrix (IEC 61966-2-1), the
/// exact inverse of xyz_to_rec709.
double luminance_y(const glm::dvec3& rgb) {
    return 0.2126729 * rgb.x + 0.7151522 * rgb.y + 0.0721750 * rgb.z;
}

/// The sun above the atmosphere as the renderer converts it: sum_i band_to_rgb[i].
glm::dvec3 sun_rgb(const SkyScene& sky) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& c : sky.band_to_rgb)
        sum += c;
    return sum;
}

std::shared_ptr<const SkyScene> sky_with(const SunDesc& sun, int bands) {
    SkySettings settings;
    settings.mode = SkyMode::Reference;
    settings.spectral_bands = bands;
    settings.view_steps = 400;
    settings.sun_steps = 200;
    const std::vector<double> nm = bands > 0 ? spectral_wavelengths_nm(bands) : kRgbNm;
    return make_sky_scene(default_earth_atmosphere(nm, kRgbNm), sun, settings);
}

SunDesc blackbody_sun() {
    SunDesc s;
    s.spectrum = SunSpectrum::Blackbody;
    return s;
}

TEST(SolarSpectrum, IlluminanceIsExactlyTheGivenLux) {
    // Spectral mode: 683 sum_i E_i ybar_i dlambda = E; RGB mode: E times a colour of luminance 1.
    for (const SunDesc& base : {SunDesc{}, blackbody_sun()}) {
        for (const int bands : {0, 8, 16, 47, 64}) {
            SunDesc sun = base;
            sun.illuminance_lux = 96500.0;
            const auto sky = sky_with(sun, bands);
            EXPECT_NEAR(luminance_y(sun_rgb(*sky)) / sun.illuminance_lux, 1.0, 1e-6)
                << "bands " << bands << " spectrum " << static_cast<int>(base.spectrum);
        }
    }
}

TEST(SolarSpectrum, DefaultIsTheAstmTable) {
    const SunDesc sun;
    EXPECT_EQ(sun.spectrum, SunSpectrum::AstmG173);
    for (const double nm : {360.0, 550.0, 830.0})
        EXPECT_EQ(sun_relative_spectrum(sun, nm), solar_irradiance_astm_g173().at(nm));
}

TEST(SolarSpectrum, LessNearUltravioletThanTheBlackBodyAtEqualLux) {
    // At equal luminance the ASTM ETR / 5772 K Planck ratio is 0.80, 0.78, 0.66, 0.72 at the
    // 360-390 nm rows (the Fraunhofer lines and the H and K lines of Ca II at 393-397 nm), and
    // 1.06-1.11 at 440-470 nm. The spectral sun's band irradiances (through band_to_rgb, linear
    // in E_i) must show both.
    const int bands = 47;  // 10 nm bins, centres 365, 375, ...
    const auto astm = sky_with(SunDesc{}, bands);
    const auto bb = sky_with(blackbody_sun(), bands);
    const std::vector<double> nm = spectral_wavelengths_nm(bands);
    for (size_t i = 0; i < nm.size(); ++i) {
        const double ratio = astm->band_to_rgb[i].z / bb->band_to_rgb[i].z;
        if (nm[i] < 390.0) {
            EXPECT_LT(ratio, 0.85) << nm[i];
        }
        if (nm[i] > 440.0 && nm[i] < 470.0) {
            EXPECT_GT(ratio, 1.03) << nm[i];
        }
    }
}

TEST(SolarSpectrum, RgbColourOfTheSun) {
    // Both spectra are white to within 10%, red above blue (the sun is not D65); the ASTM table
    // is bluer than the 5772 K black body overall (more light at 440-480 nm outweighs less
    // below 400 nm, where the CIE functions are small).
    const glm::dvec3 a = sun_rgb_color(SunDesc{});
    const glm::dvec3 b = sun_rgb_color(blackbody_sun());
    for (const glm::dvec3& c : {a, b}) {
        EXPECT_NEAR(luminance_y(c), 1.0, 1e-6);  // the matrices carry 7 digits
        EXPECT_GT(c.x, c.z);
        EXPECT_NEAR(c.x, 1.0, 0.15);
        EXPECT_NEAR(c.z, 1.0, 0.15);
    }
    EXPECT_GT(a.z / a.x, 1.03 * b.z / b.x);
    // RGB mode hands these colours to the sun.
    SunDesc sun;
    sun.illuminance_lux = 1000.0;
    const auto sky = sky_with(sun, 0);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(sky->band_to_rgb[static_cast<size_t>(i)][i], 1000.0 * a[i], 1e-9);
}

TEST(SolarSpectrum, SpectralSkyIsBluerWithTheAstmTable) {
    // Same atmosphere and lux, single scattering at the zenith, sun at 30 deg: the per-band
    // radiance (per unit irradiance) is the same, the sun's spectrum reweights it. The sky's
    // blue/red ratio must rise with the ASTM sun (it rises by 7% for the sun itself).
    SunDesc a;
    a.elevation_deg = 30.0;
    SunDesc b = blackbody_sun();
    b.elevation_deg = 30.0;
    const auto sa = sky_with(a, 24);
    const auto sb = sky_with(b, 24);
    Pcg32 rng(3, 4);
    const SkySample s =
        reference_sky(*sa, DVec3(0.0, 1.0, 0.0), DVec3(0.0, 1.0, 0.0), 1e30, false, 1, rng);
    const Rgb ca = sa->to_rgb(s.radiance);
    const Rgb cb = sb->to_rgb(s.radiance);
    ASSERT_GT(ca.r, 0.0f);
    ASSERT_GT(cb.r, 0.0f);
    const double shift = (ca.b / ca.r) / (cb.b / cb.r);
    EXPECT_GT(shift, 1.03) << "sky b/r ASTM " << ca.b / ca.r << " black body " << cb.b / cb.r;
    std::printf("zenith sky b/r: ASTM %.4f, 5772 K %.4f (x%.4f); luminance ratio %.4f\n",
                ca.b / ca.r, cb.b / cb.r, shift, luminance(ca) / luminance(cb));
}

TEST(OzoneAuto, PeakDensityAndColumnOfBruneton) {
    // Bruneton 2017 (demo.cc): 300 DU over a tent of integral 15 km gives a peak number
    // density of 300 * 2.687e20 / 15000 = 5.374e18 m^-3.
    const DensityProfile tent = DensityProfile::tent(25000.0, 15000.0);
    EXPECT_NEAR(tent.column_m(100000.0) / 15000.0, 1.0, 1e-9);
    EXPECT_NEAR(ozone_peak_number_density(tent, 100000.0, 300.0) / 5.374e18, 1.0, 1e-9);
    // A tent cut by the ground (centre 5 km, half width 15 km): 15000 - 10000² / (2 * 15000).
    EXPECT_NEAR(
        DensityProfile::tent(5000.0, 15000.0).column_m(100000.0) / (15000.0 - 1e8 / 30000.0), 1.0,
        1e-9);
    // ... and by the top of the atmosphere (top at 30 km): 15000 - 10000² / (2 * 15000).
    EXPECT_NEAR(tent.column_m(30000.0) / (15000.0 - 1e8 / 30000.0), 1.0, 1e-9);
}

TEST(OzoneAuto, DefaultsAreBrunetonsPeakCoefficients) {
    // The 233 K cross sections at 680, 550, 440 nm (1.209e-25, 3.5e-25, 1.582e-26 m²) times
    // 5.374e18 m^-3: Bruneton's 0.650e-6, 1.881e-6, 0.085e-6 1/m.
    const Atmosphere a = default_earth_atmosphere(kRgbNm, kRgbNm);
    EXPECT_NEAR(a.ozone.absorption[0] / 0.650e-6, 1.0, 1e-3);
    EXPECT_NEAR(a.ozone.absorption[1] / 1.881e-6, 1.0, 1e-3);
    EXPECT_NEAR(a.ozone.absorption[2] / 0.0850e-6, 1.0, 2e-3);
}

Atmosphere parse(const std::string& json, const std::vector<double>& nm,
                 const std::string& file = "scene.json") {
    static Json doc;  // nodes refer to it while parsing
    doc = parse_json_text(json, file);
    return parse_atmosphere(JsonNode(doc, file), nm, kRgbNm);
}

TEST(OzoneAuto, ZenithOpticalDepthIsCrossSectionTimesColumn) {
    // Ozone only: the vertical optical depth from the ground is sigma(lambda) * N with
    // N = column_du * 2.687e20 m^-2, whatever the tent's shape (here 350 DU, 22 +- 12 km).
    const std::vector<double> nm{600.0, 550.0, 440.0};
    Atmosphere a = parse(R"({"ozone": {"absorption": "auto", "column_du": 350,
                             "center_m": 22000, "half_width_m": 12000}})",
                         nm);
    a.rayleigh.scattering.fill(0.0);
    a.mie.scattering.fill(0.0);
    a.mie.absorption.fill(0.0);
    const double top = a.top_radius_m - a.ground_radius_m;
    const Bands tau =
        atmosphere_optical_depth(a, DVec3(0.0), DVec3(0.0, 1.0, 0.0), 0.0, top, 20000);
    for (size_t i = 0; i < nm.size(); ++i) {
        const double expected = ozone_cross_section_233k().at(nm[i]) * 350.0 * kDobsonUnitPerM2;
        EXPECT_NEAR(tau[i] / expected, 1.0, 1e-3) << nm[i];
    }
    // 600 nm, the Chappuis peak: 5.019e-25 * 350 * 2.687e20 = 0.0472.
    EXPECT_NEAR(tau[0], 0.0472, 0.0005);
    EXPECT_NE(input_error([&] {
                  parse(R"({"ozone": {"absorption": 1e-6, "column_du": 300}})", nm);
              }).find("/ozone/column_du"),
              std::string::npos);
}

TEST(CoefficientTables, CsvFileRelativeToTheSceneInterpolatesLinearly) {
    const ScratchDir dir("kasumi_sky_data_");
    dir.write("ray.csv", "# test table\nwavelength_nm,value\n360,4e-5\n600,1e-5\n830,0.2e-5\n");
    std::filesystem::create_directories(dir.path() / "tables");
    dir.write("tables/mie.csv", "350,3e-6\n850,5e-6\n");
    const std::string scene = (dir.path() / "scene.json").string();
    const std::vector<double> nm = spectral_wavelengths_nm(16);
    const Atmosphere a = parse(R"({"rayleigh": {"scattering": "ray.csv"},
        "mie": {"scattering": {"table": "tables/mie.csv", "scale": 0.5},
                "extinction": {"table": "tables/mie.csv"}}})",
                               nm, scene);
    for (size_t i = 0; i < nm.size(); ++i) {
        const double w = nm[i];
        const double ray = w <= 600.0 ? 4e-5 + (w - 360.0) / 240.0 * (1e-5 - 4e-5)
                                      : 1e-5 + (w - 600.0) / 230.0 * (0.2e-5 - 1e-5);
        EXPECT_NEAR(a.rayleigh.scattering[i] / ray, 1.0, 1e-12) << w;
        const double mie = 3e-6 + (w - 350.0) / 500.0 * 2e-6;
        EXPECT_NEAR(a.mie.scattering[i] / (0.5 * mie), 1.0, 1e-12) << w;
        EXPECT_NEAR(a.mie.absorption[i] / (0.5 * mie), 1.0, 1e-12) << w;
    }
    // RGB mode samples the same table at the three wavelengths (exact at a row: 600 nm).
    const Atmosphere rgb =
        parse(R"({"rayleigh": {"scattering": "ray.csv"}})", {680.0, 600.0, 440.0}, scene);
    EXPECT_DOUBLE_EQ(rgb.rayleigh.scattering[1], 1e-5);
    EXPECT_NEAR(rgb.rayleigh.scattering[0], 1e-5 + 80.0 / 230.0 * -0.8e-5, 1e-18);
}

TEST(CoefficientTables, ErrorsNameSceneFilePointerCsvLineAndRange) {
    const ScratchDir dir("kasumi_sky_data_");
    dir.write("bad.csv", "400,1e-6\n500,x\n");
    dir.write("short.csv", "400,1e-6\n700,2e-6\n");
    const std::string scene = (dir.path() / "scene.json").string();
    const std::vector<double> nm = spectral_wavelengths_nm(8);
    std::string m =
        input_error([&] { parse(R"({"ozone": {"absorption": "bad.csv"}})", nm, scene); });
    EXPECT_NE(m.find("scene.json: /ozone/absorption"), std::string::npos) << m;
    EXPECT_NE(m.find("bad.csv:2: expected two numbers"), std::string::npos) << m;
    m = input_error([&] { parse(R"({"rayleigh": {"scattering": "short.csv"}})", nm, scene); });
    EXPECT_NE(m.find("/rayleigh/scattering"), std::string::npos) << m;
    EXPECT_NE(m.find("short.csv"), std::string::npos) << m;
    EXPECT_NE(m.find("the table covers 400 to 700 nm"), std::string::npos) << m;
    m = input_error([&] { parse(R"({"rayleigh": {"scattering": "missing.csv"}})", nm, scene); });
    EXPECT_NE(m.find("missing.csv: cannot open"), std::string::npos) << m;
    m = input_error([&] { parse(R"({"ground_albedo": "auto"})", nm, scene); });
    EXPECT_NE(m.find("/ground_albedo"), std::string::npos) << m;
    // Inline rows obey the same range rule (no clamping).
    m = input_error([&] {
        parse(R"({"mie": {"scattering": {"table": [[500, 1e-6], [600, 1e-6]]}}})", nm, scene);
    });
    EXPECT_NE(m.find("/mie/scattering/table"), std::string::npos) << m;
}

TEST(SunSpectrumKeys, BlackbodyTableAndErrors) {
    const ScratchDir dir("kasumi_sky_data_");
    dir.write("flat.csv", "300,1\n900,1\n");
    dir.write("narrow.csv", "500,1\n600,1\n");
    const std::string file = (dir.path() / "scene.json").string();
    Json doc;
    auto sun = [&](const std::string& json) {
        doc = parse_json_text(json, file);
        return parse_sun(JsonNode(doc, file));
    };
    EXPECT_EQ(sun(R"({})").spectrum, SunSpectrum::AstmG173);
    EXPECT_EQ(sun(R"({"spectrum": "astm_g173"})").spectrum, SunSpectrum::AstmG173);
    const SunDesc bb = sun(R"({"spectrum": "blackbody"})");
    EXPECT_EQ(bb.spectrum, SunSpectrum::Blackbody);
    EXPECT_EQ(bb.blackbody_k, kSunTemperatureK);
    EXPECT_EQ(sun(R"({"spectrum": {"blackbody_K": 6500}})").blackbody_k, 6500.0);
    const SunDesc flat = sun(R"({"spectrum": "flat.csv"})");
    EXPECT_EQ(flat.spectrum, SunSpectrum::Table);
    EXPECT_EQ(sun_relative_spectrum(flat, 455.5), 1.0);
    // An equal-energy spectrum has the chromaticity of CIE illuminant E: x = y = 1/3.
    const glm::dvec3 e = sun_rgb_color(flat);
    const glm::dvec3 xyz_e(1.0, 1.0, 1.0);
    EXPECT_NEAR(e.x, xyz_to_rec709(xyz_e).x, 2e-3);
    EXPECT_NEAR(e.z, xyz_to_rec709(xyz_e).z, 2e-3);
    EXPECT_NE(input_error([&] {
                  sun(R"({"spectrum": {"blackbody_K": 10}})");
              }).find("/spectrum/blackbody_K"),
              std::string::npos);
    EXPECT_NE(input_error([&] { sun(R"({"spectrum": 5})"); }).find("/spectrum"), std::string::npos);
    // A table narrower than the spectral wavelengths: an error naming it when the sky is built.
    const SunDesc narrow = sun(R"({"spectrum": "narrow.csv"})");
    const std::string m = input_error([&] { sky_with(narrow, 16); });
    EXPECT_NE(m.find("/spectrum"), std::string::npos) << m;
    EXPECT_NE(m.find("the table covers 500 to 600 nm"), std::string::npos) << m;
}

}  // namespace
}  // namespace kasumi
