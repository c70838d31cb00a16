// Wavelength tables: the CSV parser (comments, header, located errors, monotone wavelengths),
// linear interpolation (exact at rows, linear between, no extrapolation), and the built-in
// measured tables against their sources' own figures.
#include "core/csv_table.h"
#include "core/error.h"
#include "core/reference_spectra.h"
#include "tests/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace kasumi {
namespace {

TEST(CsvTable, CommentsBlankLinesAndHeader) {
    const WavelengthTable t = parse_wavelength_csv(
        "# a comment\n"
        "\n"
        "wavelength_nm, value   # header\n"
        "  400 , 1.5 # trailing comment\n"
        "\t\r\n"
        "500,2e0\r\n"
        "#600,9\n"
        "650,0\n",
        "t.csv");
    ASSERT_EQ(t.nm.size(), 3u);
    EXPECT_EQ(t.nm[0], 400.0);
    EXPECT_EQ(t.value[0], 1.5);
    EXPECT_EQ(t.nm[1], 500.0);
    EXPECT_EQ(t.value[1], 2.0);
    EXPECT_EQ(t.nm[2], 650.0);
    EXPECT_EQ(t.value[2], 0.0);
}

TEST(CsvTable, BadLinesAreLocated) {
    // Line numbers count every line, comments and blanks included.
    std::string m = input_error([] { parse_wavelength_csv("# c\n400,1\n\n450,abc\n", "bad.csv"); });
    EXPECT_NE(m.find("bad.csv:4: expected two numbers \"wavelength_nm,value\", got \"450,abc\""),
              std::string::npos)
        << m;
    m = input_error([] { parse_wavelength_csv("400,1\n450,2,3\n", "bad.csv"); });
    EXPECT_NE(m.find("bad.csv:2: expected two numbers"), std::string::npos) << m;
    m = input_error([] { parse_wavelength_csv("400\n", "bad.csv"); });
    EXPECT_NE(m.find("bad.csv:1:"), std::string::npos) << m;
    // A header is only allowed before the first row.
    m = input_error([] { parse_wavelength_csv("400,1\nnm,value\n500,2\n", "bad.csv"); });
    EXPECT_NE(m.find("bad.csv:2:"), std::string::npos) << m;
    m = input_error([] { parse_wavelength_csv("400,1\n500,-0.5\n", "bad.csv"); });
    EXPECT_NE(m.find("bad.csv:2: value must be >= 0"), std::string::npos) << m;
    m = input_error([] { parse_wavelength_csv("400,1\n500,nan\n", "bad.csv"); });
    EXPECT_NE(m.find("bad.csv:2:"), std::string::npos) << m;
    m = input_error([] { parse_wavelength_csv("# only\n400,1\n", "one.csv"); });
    EXPECT_NE(m.find("one.csv: a table needs at least two rows"), std::string::npos) << m;
}

TEST(CsvTable, NonMonotoneWavelengthsAreRejected) {
    std::string m = input_error([] { parse_wavelength_csv("400,1\n500,2\n450,3\n", "w.csv"); });
    EXPECT_NE(m.find("w.csv:3: wavelengths must strictly increase: 450 nm after 500 nm"),
              std::string::npos)
        << m;
    m = input_error([] { parse_wavelength_csv("400,1\n400,2\n", "w.csv"); });
    EXPECT_NE(m.find("w.csv:2: wavelengths must strictly increase"), std::string::npos) << m;
    m = input_error([] { parse_wavelength_csv("0,1\n400,2\n", "w.csv"); });
    EXPECT_NE(m.find("w.csv:1: wavelength must be > 0"), std::string::npos) << m;
}

TEST(CsvTable, MissingFileNamesThePath) {
    const std::string m = input_error([] { read_wavelength_csv("/nonexistent/kasumi/table.csv"); });
    EXPECT_NE(m.find("/nonexistent/kasumi/table.csv: cannot open"), std::string::npos) << m;
}

TEST(CsvTable, InterpolationIsExactAtRowsAndLinearBetween) {
    const WavelengthTable t = parse_wavelength_csv("400,1\n410,3\n430,2\n480,7.5\n", "lin.csv");
    for (size_t i = 0; i < t.nm.size(); ++i)
        EXPECT_EQ(t.at(t.nm[i]), t.value[i]) << t.nm[i];
    for (size_t i = 1; i < t.nm.size(); ++i) {
        for (const double f : {0.1, 0.25, 0.5, 0.9}) {
            const double w = t.nm[i - 1] + f * (t.nm[i] - t.nm[i - 1]);
            EXPECT_NEAR(t.at(w), t.value[i - 1] + f * (t.value[i] - t.value[i - 1]), 1e-12) << w;
        }
    }
    // Trapezoid integral of a linear table is exact: 20 + 50 + 237.5.
    EXPECT_NEAR(t.integral(), 307.5, 1e-12);
}

TEST(CsvTable, OutsideTheRangeIsAnErrorNotAClamp) {
    const WavelengthTable t = parse_wavelength_csv("400,1\n500,2\n", "range.csv");
    for (const double w : {399.999, 500.001, 0.0, 1e4}) {
        const std::string m = input_error([&] { t.at(w); });
        EXPECT_NE(m.find("range.csv: no value at"), std::string::npos) << w << ": " << m;
        EXPECT_NE(m.find("the table covers 400 to 500 nm"), std::string::npos) << m;
    }
}

TEST(ReferenceSpectra, SolarTableIntegratesToTheAstmTotal) {
    // The 48 bin means of the ASTM G173-03 ETR samples in [360 + 10 i, 370 + 10 i) nm sit at
    // their bin centres, with flat half bins to 360 and 840 nm, so the linear table's integral
    // is exactly 10 nm times their sum: 745.27 W/m² by the trapezoid rule on the standard's own
    // 0.5/1 nm table over [360, 840] nm (kAstmG173EtrIntegral360To840), i.e. 54.6% of the
    // 1366.1 W/m² the standard states for its whole ETR column.
    const WavelengthTable& s = solar_irradiance_astm_g173();
    ASSERT_EQ(s.nm.size(), 50u);
    EXPECT_EQ(s.min_nm(), 360.0);
    EXPECT_EQ(s.max_nm(), 840.0);
    double sum = 0.0;
    for (size_t i = 1; i + 1 < s.value.size(); ++i) {
        EXPECT_EQ(s.nm[i], 355.0 + 10.0 * static_cast<double>(i));
        sum += s.value[i] * 10.0;
    }
    EXPECT_NEAR(s.integral() / sum, 1.0, 1e-12);
    EXPECT_NEAR(sum / kAstmG173EtrIntegral360To840, 1.0, 0.01);
}

TEST(ReferenceSpectra, ShippedCsvFilesHoldTheCompiledTables) {
    const std::string dir = std::string(KASUMI_SOURCE_DIR) + "/data/spectra/";
    const WavelengthTable solar = read_wavelength_csv(dir + "solar_astm_g173_etr.csv");
    const WavelengthTable ozone = read_wavelength_csv(dir + "ozone_cross_section_233k.csv");
    EXPECT_EQ(solar.nm, solar_irradiance_astm_g173().nm);
    EXPECT_EQ(solar.value, solar_irradiance_astm_g173().value);
    EXPECT_EQ(ozone.nm, ozone_cross_section_233k().nm);
    EXPECT_EQ(ozone.value, ozone_cross_section_233k().value);
}

TEST(ReferenceSpectra, OzoneCrossSectionPeaksInTheChappuisBand) {
    // The Chappuis band of ozone peaks near 600 nm (Serdyuchenko et al. 2014, Fig. 1): the
    // table's maximum row is 600 nm, 5.019e-25 m²; at 440 nm it is 30 times smaller.
    const WavelengthTable& o = ozone_cross_section_233k();
    size_t peak = 0;
    for (size_t i = 0; i < o.value.size(); ++i)
        if (o.value[i] > o.value[peak])
            peak = i;
    EXPECT_EQ(o.nm[peak], 600.0);
    EXPECT_GT(o.at(600.0) / o.at(440.0), 30.0);
}

}  // namespace
}  // namespace kasumi
