#include "lights/goniometric_light.h"

#include "core/error.h"
#include "light_test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

std::string ies_path(const std::string& name) {
    return std::string(KASUMI_SOURCE_DIR) + "/data/ies/" + name;
}

double rad(double deg) {
    return deg * kPiD / 180.0;
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
    EXPECT_NE(
        ies_error(replace(good, "IESNA:LM-63-2002", "IESNA91")).find("bad.ies:1: unsupported"),
        std::string::npos);
    EXPECT_NE(ies_error(replace(good, "TILT=NONE", "TILT=INCLUDE")).find("bad.ies:3:"),
              std::string::npos);
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
                  .find("bad.ies:7: type C horizontal angles must start at 0 and end at 0, 90"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "1 1 10", "1 1 x")).find("bad.ies:5: expected a number"),
              std::string::npos);
    EXPECT_NE(ies_error(replace(good, "[TEST] x", "garbage")).find("bad.ies:2:"),
              std::string::npos);
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
