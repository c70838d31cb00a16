#include "lights/goniometric_light.h"

#include "core/error.h"
#include "light_test_util.h"
#include "tests/scratch_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace kasumi {
namespace {

std::string ies_path(const std::string& name) {
    return std::string(KASUMI_SOURCE_DIR) + "/data/ies/" + name;
}

double rad(double deg) {
    return deg * kPiD / 180.0;
}

std::string test_ies(const std::string& name) {
    return std::string(KASUMI_SOURCE_DIR) + "/tests/data/ies/" + name;
}

// The distribution tests/data/ies/make_test_ies.py writes into revision_*.ies and the tilt files.
double bilateral(double gamma_deg, double c_deg) {
    return 200.0 * std::cos(rad(gamma_deg)) * (1.0 + 0.5 * std::cos(rad(c_deg))) + 50.0;
}

// The distribution of mirror_90_270.ies and full_0_360.ies: symmetric about the 90-270 plane.
double mirrored(double gamma_deg, double c_deg) {
    const double c = rad(c_deg);
    return (300.0 * std::cos(rad(gamma_deg)) + 20.0) *
           (1.0 + 0.5 * std::sin(c) + 0.2 * std::cos(2.0 * c));
}

TEST(Ies, MeasuredAnglesReturnTheTableTimesTheMultiplier) {
    const IesProfile iso = read_ies(ies_path("isotropic_1000lm.ies"));
    EXPECT_EQ(iso.format, "LM-63-2002");
    for (float g : {0.0f, 90.0f, 180.0f})
        EXPECT_NEAR(ies_candela(iso, g, 0.0f), 1000.0 / (4.0 * kPiD), 1e-3);  // stored ×2, × 0.5
    const IesProfile quad = read_ies(ies_path("quadrant_roadway.ies"));
    for (float g : {0.0f, 30.0f, 85.0f}) {
        for (float c : {0.0f, 15.0f, 45.0f, 90.0f}) {
            const double expected = 250.0 * std::cos(rad(g)) * (1.0 + 0.5 * std::cos(rad(2 * c)));
            EXPECT_NEAR(ies_candela(quad, g, c), expected, 1e-3) << g << " " << c;
        }
    }
}

TEST(Ies, InBetweenAnglesAreBilinear) {
    const IesProfile quad = read_ies(ies_path("quadrant_roadway.ies"));
    // Halfway between measured angles the value is the mean of the neighbours...
    const float a = ies_candela(quad, 30.0f, 15.0f), b = ies_candela(quad, 35.0f, 15.0f);
    const float c = ies_candela(quad, 30.0f, 30.0f), d = ies_candela(quad, 35.0f, 30.0f);
    EXPECT_NEAR(ies_candela(quad, 32.5f, 15.0f), 0.5f * (a + b), 1e-4f);
    EXPECT_NEAR(ies_candela(quad, 32.5f, 22.5f), 0.25f * (a + b + c + d), 1e-4f);
    EXPECT_NEAR(ies_candela(quad, 31.25f, 18.75f),
                0.75f * (0.75f * a + 0.25f * b) + 0.25f * (0.75f * c + 0.25f * d), 1e-4f);
    // ...and close to the analytic distribution the table samples (interpolation error of a
    // 5° × 15° grid).
    const double exact = 250.0 * std::cos(rad(32.5)) * (1.0 + 0.5 * std::cos(rad(45.0)));
    EXPECT_NEAR(ies_candela(quad, 32.5f, 22.5f), exact, 0.02 * exact);
}

TEST(Ies, SymmetriesExpandToTheFullCircle) {
    const IesProfile quad = read_ies(ies_path("quadrant_roadway.ies"));
    const IesProfile bil = read_ies(ies_path("wallwash_bilateral.ies"));
    const IesProfile iso = read_ies(ies_path("cosine_downlight.ies"));
    for (float c : {10.0f, 37.5f, 80.0f}) {
        const float q = ies_candela(quad, 40.0f, c);
        EXPECT_NEAR(ies_candela(quad, 40.0f, 180.0f - c), q, 1e-4f) << c;
        EXPECT_NEAR(ies_candela(quad, 40.0f, 180.0f + c), q, 1e-4f) << c;
        EXPECT_NEAR(ies_candela(quad, 40.0f, 360.0f - c), q, 1e-4f) << c;
        EXPECT_NEAR(ies_candela(quad, 40.0f, -c), q, 1e-4f) << c;
        EXPECT_NEAR(ies_candela(bil, 40.0f, 360.0f - 2 * c), ies_candela(bil, 40.0f, 2 * c), 1e-4f);
        EXPECT_NEAR(ies_candela(iso, 40.0f, 3 * c), ies_candela(iso, 40.0f, 0.0f), 1e-4f);
    }
    EXPECT_EQ(bil.horizontal_deg.back(), 360.0f);
    EXPECT_EQ(quad.horizontal_deg.size(), 25u);  // 0..360 in 15° steps
    // A downlight measured to 90° emits nothing upward.
    EXPECT_EQ(ies_candela(iso, 120.0f, 0.0f), 0.0f);
}

TEST(Ies, FluxOfTheTableMatchesTheFileLumens) {
    // The generator states each distribution's exact flux; the interpolated table differs by
    // its interpolation error in γ only (the trapezoid rule is exact for periodic C terms).
    for (const char* name : {"isotropic_1000lm.ies", "cosine_downlight.ies",
                             "wallwash_bilateral.ies", "quadrant_roadway.ies"}) {
        const IesProfile p = read_ies(ies_path(name));
        ASSERT_GT(p.file_lumens, 0.0) << name;
        EXPECT_NEAR(ies_flux_lm(p), p.file_lumens, 3e-3 * p.file_lumens) << name;
    }
    const IesProfile absolute = read_ies(ies_path("sideways_asymmetric.ies"));
    EXPECT_LT(absolute.file_lumens, 0.0);
    EXPECT_NEAR(ies_flux_lm(absolute), 800.0 * kPiD, 3e-3 * 800.0 * kPiD);
}

TEST(Ies, EveryRevisionGivesTheSameTable) {
    // LM-63-1986 (free-form label lines, no format line; comma delimiters; the ballast-lamp
    // photometric factor 0.5 halves its doubled values), LM-63-1991 (IESNA91, with a free-text
    // line), LM-63-1995, LM-63-2002 and LM-63-2019 (whose file generation type 1.00010 is a code,
    // not a factor).
    const std::pair<const char*, const char*> files[] = {{"revision_1986.ies", "LM-63-1986"},
                                                         {"revision_1991.ies", "LM-63-1991"},
                                                         {"revision_1995.ies", "LM-63-1995"},
                                                         {"revision_2002.ies", "LM-63-2002"},
                                                         {"revision_2019.ies", "LM-63-2019"}};
    const IesProfile reference = read_ies(test_ies("revision_2002.ies"));
    for (const auto& [name, format] : files) {
        const IesProfile p = read_ies(test_ies(name));
        EXPECT_EQ(p.format, format) << name;
        EXPECT_EQ(p.tilt.geometry, 0) << name;
        // At the measured angles: the closed form (the files hold 4 decimals).
        for (float g : {0.0f, 30.0f, 60.0f, 90.0f}) {
            for (float c : {0.0f, 90.0f, 180.0f, 270.0f})
                EXPECT_NEAR(ies_candela(p, g, c), bilateral(g, c), 1e-3) << name << " " << g;
        }
        // Everywhere: the same table as the 2002 file.
        ASSERT_EQ(p.horizontal_deg, reference.horizontal_deg) << name;
        for (size_t i = 0; i < p.candela.size(); ++i)
            EXPECT_FLOAT_EQ(p.candela[i], reference.candela[i]) << name << " " << i;
        EXPECT_FLOAT_EQ(ies_candela(p, 47.0f, 123.0f), ies_candela(reference, 47.0f, 123.0f));
    }
}

TEST(Ies, TiltIncludeScalesTheIntensityByTheMultiplier) {
    const IesProfile plain = read_ies(test_ies("revision_2002.ies"));
    const IesProfile inline_tilt = read_ies(test_ies("tilt_include.ies"));
    const IesProfile file_tilt = read_ies(test_ies("tilt_file.ies"));
    for (const IesProfile* p : {&inline_tilt, &file_tilt}) {
        EXPECT_EQ(p->tilt.geometry, 1);
        EXPECT_EQ(p->tilt.angle_deg, (std::vector<float>{0.0f, 45.0f, 90.0f}));
        // The table itself is the untilted one; the multiplier depends on the orientation.
        EXPECT_EQ(p->candela, plain.candela);
        EXPECT_FLOAT_EQ(ies_tilt_multiplier(*p, 0.0f), 0.8f);
        EXPECT_FLOAT_EQ(ies_tilt_multiplier(*p, 45.0f), 0.9f);
        EXPECT_FLOAT_EQ(ies_tilt_multiplier(*p, 22.5f), 0.85f);  // linear between pairs
        EXPECT_FLOAT_EQ(ies_tilt_multiplier(*p, 90.0f), 0.6f);
        // Past 90°, a table that stops at 90° is read at 180° − tilt (same lamp axis line).
        EXPECT_FLOAT_EQ(ies_tilt_multiplier(*p, 135.0f), 0.9f);
        EXPECT_FLOAT_EQ(ies_tilt_multiplier(*p, 180.0f), 0.8f);
    }
    EXPECT_EQ(inline_tilt.tilt.source, "INCLUDE");
    EXPECT_NE(file_tilt.tilt.source.find("vertical_lamp.tlt"), std::string::npos);
    EXPECT_FLOAT_EQ(ies_tilt_multiplier(plain, 30.0f), 1.0f);

    // In the scene: hanging straight down the light is 0.8 × the untilted table in every
    // direction; tilted 45° about x it is 0.9 × the table in the luminaire's frame.
    const std::string scene = test_ies("scene.json");
    const auto light = [&](const char* ies, const char* rotation) {
        return test::parse_light_text(std::string(R"({"type": "goniometric", "position": [0, 0, 0],
            "ies": ")") + ies + R"(", "rotation_deg": )" +
                                          rotation + "}",
                                      scene);
    };
    const auto candela = [](const Light& l, const Vec3& dir) {
        return luminance(incident_light(l, dir).irradiance);  // at 1 m
    };
    for (const char* rotation : {"0", "[45, 0, 0]", "[0, 30, 100]"}) {
        const Light untilted = light("revision_2002.ies", rotation);
        const Light tilted = light("tilt_include.ies", rotation);
        const Light from_file = light("tilt_file.ies", rotation);
        // Up axis tilted by 0°, 45° and 100° (read at 80°) from +y.
        const float m = std::string(rotation) == "[45, 0, 0]" ? 0.9f
                        : std::string(rotation) == "0"        ? 0.8f
                                                              : 0.9f - 0.3f * 35.0f / 45.0f;
        for (const Vec3& dir : {Vec3(0, -1, 0), Vec3(0.6f, -0.8f, 0), Vec3(0, 0.6f, 0.8f)}) {
            const float base = candela(untilted, dir);
            EXPECT_NEAR(candela(tilted, dir), m * base, 1e-4f * base + 1e-6f) << rotation;
            EXPECT_NEAR(candela(from_file, dir), m * base, 1e-4f * base + 1e-6f) << rotation;
        }
        EXPECT_NEAR(luminous_flux_lm(tilted), m * luminous_flux_lm(untilted),
                    1e-4f * luminous_flux_lm(untilted));
    }
}

TEST(Ies, Mirror90To270EqualsItsFullExpansion) {
    // LM-63: horizontal angles 90..270 mean bilateral symmetry about the 90-270 plane.
    const IesProfile half = read_ies(test_ies("mirror_90_270.ies"));
    const IesProfile full = read_ies(test_ies("full_0_360.ies"));
    EXPECT_EQ(half.horizontal_deg, full.horizontal_deg);  // 0, 30, ..., 360
    for (float g = 0.0f; g <= 90.0f; g += 7.5f) {
        for (float c = 0.0f; c <= 360.0f; c += 5.0f) {
            const float f = ies_candela(full, g, c);
            EXPECT_NEAR(ies_candela(half, g, c), f, 1e-4f * f) << g << " " << c;
        }
    }
    // The mirror image really differs from a 0-180 reading of the same columns: C = 0 holds the
    // 180° column, C = 30° the 150° one.
    EXPECT_NEAR(ies_candela(half, 0.0f, 0.0f), mirrored(0.0, 180.0), 1e-3);
    EXPECT_NEAR(ies_candela(half, 45.0f, 30.0f), mirrored(45.0, 150.0), 1e-3);
    EXPECT_NEAR(ies_candela(half, 45.0f, 330.0f), mirrored(45.0, 210.0), 1e-3);
    EXPECT_NEAR(ies_flux_lm(half), ies_flux_lm(full), 1e-6 * ies_flux_lm(full));
}

TEST(Ies, NoSymmetryBelow360ClosesTheCircle) {
    // Last horizontal angle in (180, 360]: no lateral symmetry; between the last plane and
    // 360° = 0° the intensity is interpolated between the two.
    const IesProfile p = parse_ies(
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 4 1 2 0 0 0\n1 1 10\n0 90\n0 90 180 270\n"
        "10 10\n20 20\n30 30\n40 40\n",
        "open.ies");
    EXPECT_EQ(p.horizontal_deg.back(), 360.0f);
    EXPECT_FLOAT_EQ(ies_candela(p, 45.0f, 270.0f), 40.0f);
    EXPECT_FLOAT_EQ(ies_candela(p, 45.0f, 315.0f), 25.0f);
    EXPECT_FLOAT_EQ(ies_candela(p, 45.0f, 360.0f), 10.0f);
}

TEST(GoniometricLight, OrientationInTheScene) {
    const std::string file = std::string(KASUMI_SOURCE_DIR) + "/data/ies/scene.json";
    const Light hanging = test::parse_light_text(
        R"({"type": "goniometric", "position": [0, 0, 0], "ies": "sideways_asymmetric.ies"})",
        file);
    // Default frame: nadir toward −y, C = 0° toward +x, C = 90° toward −z.
    const auto candela = [](const Light& l, const Vec3& dir) {
        return luminance(incident_light(l, dir).irradiance);  // at 1 m
    };
    EXPECT_NEAR(candela(hanging, Vec3(0, -1, 0)), 100.0f, 1e-3f);
    EXPECT_NEAR(candela(hanging, Vec3(1, 0, 0)), 400.0f, 1e-3f);
    EXPECT_NEAR(candela(hanging, Vec3(-1, 0, 0)), 100.0f, 1e-3f);
    EXPECT_NEAR(candela(hanging, Vec3(0, 0, -1)), 250.0f, 1e-3f);
    const Light turned = test::parse_light_text(
        R"({"type": "goniometric", "position": [0, 0, 0], "ies": "sideways_asymmetric.ies",
            "rotation_deg": 90})",
        file);
    // 90° about +y takes +x to −z.
    EXPECT_NEAR(candela(turned, Vec3(0, 0, -1)), 400.0f, 1e-3f);
    const Light tilted = test::parse_light_text(
        R"({"type": "goniometric", "position": [0, 0, 0], "ies": "sideways_asymmetric.ies",
            "rotation_deg": [0, 0, 90]})",
        file);
    // 90° about +z takes +x (C = 0°) to +y.
    EXPECT_NEAR(candela(tilted, Vec3(0, 1, 0)), 400.0f, 1e-3f);
}

TEST(GoniometricLight, FluxRescalesTheTable) {
    const std::string file = std::string(KASUMI_SOURCE_DIR) + "/data/ies/scene.json";
    const Light light = test::parse_light_text(
        R"({"type": "goniometric", "position": [0, 2, 0], "ies": "cosine_downlight.ies",
            "flux_lm": 3000})",
        file);
    EXPECT_NEAR(luminous_flux_lm(light), 3000.0f, 0.5f);
    const IesProfile p = read_ies(ies_path("cosine_downlight.ies"));
    const float scale = static_cast<float>(3000.0 / ies_flux_lm(p));
    EXPECT_NEAR(luminance(incident_light(light, Vec3(0)).irradiance), scale * 500.0f / 4.0f, 1e-2f);
}

std::string ies_error(const std::string& text) {
    try {
        parse_ies(text, "bad.ies");
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        return e.what();
    }
    return "";
}

const char* kGood =
    "IESNA:LM-63-2002\n[TEST] x\nTILT=NONE\n1 100 1 3 1 1 2 0 0 0\n1 1 10\n0 45 90\n0\n"
    "10 20 30\n";

TEST(Ies, BadFilesNameTheLine) {
    EXPECT_NO_THROW(parse_ies(kGood, "good.ies"));
    const auto replace = [](std::string s, const std::string& from, const std::string& to) {
        return s.replace(s.find(from), from.size(), to);
    };
    const std::string good = kGood;
    EXPECT_NE(ies_error(replace(good, "IESNA:LM-63-2002", "IESNA:LM-63-2003"))
                  .find("bad.ies:1: unsupported format line"),
              std::string::npos);
    // TILT=INCLUDE reads the tilt block from the next line: "1 100 1 ..." is geometry 1, 100
    // pairs, and angles 1, 3, 1 do not increase.
    EXPECT_NE(ies_error(replace(good, "TILT=NONE", "TILT=INCLUDE"))
                  .find("bad.ies:4: tilt angles must increase"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "TILT=NONE", "TILT=INCLUDE\n4 1 0 1"))
                  .find("bad.ies:4: the lamp-to-luminaire geometry (1, 2 or 3) must be"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "TILT=NONE", "TILT=INCLUDE\n1 2\n0 90\n1 -0.5"))
                  .find("bad.ies:6: tilt multiplying factors must be in [0, 1e30]"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "TILT=NONE", "TILT=no_such.tlt"))
                  .find("bad.ies:3: cannot open the tilt file no_such.tlt"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "TILT=NONE", "TILT=")).find("bad.ies:3: TILT= names nothing"),
              std::string::npos);
    // LM-63-1986 has no format line, so any first line is a label; without TILT= it never ends.
    EXPECT_NE(ies_error("Some luminaire\nanother label\n1 2 3\n")
                  .find("bad.ies:3: file ends before the TILT= line (LM-63-1986)"),
              std::string::npos);
    EXPECT_NE(ies_error("").find("bad.ies:0: empty file"), std::string::npos);
    EXPECT_NE(ies_error(replace(good, "3 1 1 2", "3 1 2 2")).find("bad.ies:4: photometric type 2"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "0 45 90", "0 90 45"))
                  .find("bad.ies:6: vertical angles must increase"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "10 20 30", "10 -20 30"))
                  .find("bad.ies:8: candela values must be >= 0"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "10 20 30\n", "10 20\n")).find("file ends before candela"),
              std::string::npos);
    EXPECT_NE(
        ies_error(replace(good, "10 20 30", "10 20 30 40")).find("bad.ies:8: unexpected data"),
        std::string::npos);
    EXPECT_NE(ies_error(replace(replace(good, "3 1 1 2", "3 2 1 2"), "0\n10 20 30",
                                "0 45\n10 20 30 10 20 30"))
                  .find("bad.ies:7: type C horizontal angles must be 0 alone, 0 to 90"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(replace(good, "3 1 1 2", "3 2 1 2"), "0\n10 20 30",
                                "90 180\n10 20 30 10 20 30"))
                  .find("bad.ies:7: type C horizontal angles must be 0 alone"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "1 1 10", "1 1 x")).find("bad.ies:5: expected a number"),
              std::string::npos);
    // From LM-63-1995 on, label lines are [KEYWORD] lines; 1986 and 1991 allow free text.
    EXPECT_NE(ies_error(replace(good, "[TEST] x", "garbage"))
                  .find("bad.ies:2: expected a [KEYWORD] line or TILT= in an LM-63-2002 file"),
              std::string::npos);
    EXPECT_NO_THROW(parse_ies(
        replace(replace(good, "[TEST] x", "garbage"), "IESNA:LM-63-2002", "IESNA91"), "good.ies"));
    EXPECT_NO_THROW(parse_ies(replace(good, "IESNA:LM-63-2002\n", "free text\n"), "good.ies"));
}

TEST(Ies, BadTiltFileNamesItsOwnLine) {
    // TILT=<filename> is read relative to the IES file; its errors name the tilt file's line.
    const ScratchDir scratch("kasumi_ies_tilt_");
    const std::filesystem::path& dir = scratch.path();
    std::filesystem::create_directories(dir / "sub");
    std::ofstream(dir / "sub" / "lamp.tlt") << "3\n2\n0 90\n1.0 x\n";
    std::ofstream(dir / "extra.tlt") << "2 2 0 90 1 0.5\n7\n";
    const std::string ies =
        "IESNA:LM-63-1995\n[TEST] t\nTILT=sub/lamp.tlt\n1 100 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n"
        "10 20\n";
    const std::string where = (dir / "x.ies").string();
    std::string what;
    try {
        parse_ies(ies, where);
    } catch (const Error& e) {
        what = e.what();
    }
    EXPECT_NE(what.find((dir / "sub" / "lamp.tlt").string() +
                        ":4: expected a number for tilt multiplying factors"),
              std::string::npos)
        << what;
    what.clear();
    try {
        std::string s = ies;
        parse_ies(s.replace(s.find("sub/lamp.tlt"), 12, "extra.tlt"), where);
    } catch (const Error& e) {
        what = e.what();
    }
    EXPECT_NE(what.find((dir / "extra.tlt").string() + ":2: unexpected data after the tilt"),
              std::string::npos)
        << what;
}

TEST(GoniometricLight, BadIesFileIsAnInputErrorNamingSceneAndPointer) {
    try {
        test::parse_light_text(
            R"({"type": "goniometric", "position": [0, 0, 0], "ies": "missing.ies"})",
            "/tmp/scene.json");
        FAIL();
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/tmp/scene.json: /lights/0/ies"), std::string::npos) << what;
        EXPECT_NE(what.find("/tmp/missing.ies: cannot open"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace kasumi
