// Fog given by its visibility (`visibility_m`, volume/visibility.h): the scene key, read by
// parse_medium as a scene would, must give a medium whose own Beer-Lambert transmittance over
// the visibility V is the contrast threshold eps (Koschmieder 1924; WMO-No. 8 ch. 9 for the
// meteorological optical range), and bad input must be an input error naming the key.
#include "volume/visibility.h"
#include "core/json_node.h"
#include "core/rng.h"
#include "volume/medium_json.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"

#include "../input_error.h"
#include "vdb_test_grids.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace kasumi {
namespace {

Medium parse_doc(const Json& doc) {
    return parse_medium(JsonNode(doc, "fog.json", "/media/0"), 0);
}

Medium parse(const std::string& text) {
    return parse_doc(parse_json_text(text, "fog.json"));
}

std::string error_of_doc(const Json& doc) {
    return input_error([&] { parse_doc(doc); });
}

std::string error_of(const std::string& text) {
    return error_of_doc(parse_json_text(text, "fog.json"));
}

// A box of fog [0, L] along x, crossed by a horizontal ray from x = -5 m to x = L + 5 m, so the
// path inside the fog is L long and the segment ends outside it.
Rgb transmittance_across(const Medium& medium, float length_m) {
    const MediumSet media({medium});
    return media.transmittance(Ray{Vec3(-5.0f, 1.0f, 1.0f), Vec3(1, 0, 0), 0.0f, length_m + 10.0f});
}

std::string box_fog(double visibility_m, const std::string& more = "") {
    const std::string v = std::to_string(visibility_m);
    return R"({"type": "homogeneous", "bounds": [[0, 0, 0], [)" + v +
           R"(, 2, 2]], "visibility_m": )" + v + more + "}";
}

// The default threshold is the WMO meteorological optical range's 5%: over V the medium passes
// 5% of a beam, at every visibility from a dense fog to a clear day.
TEST(FogVisibility, TransmittanceOverTheVisibilityIsTheMorThreshold) {
    for (const double v : {20.0, 60.0, 250.0, 1000.0, 20000.0}) {
        const Medium fog = parse(box_fog(v));
        const Rgb t = transmittance_across(fog, static_cast<float>(v));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(t[c], 0.05f, 0.05f * 1e-5f) << "V = " << v << " m";
        // Half the distance: the square root (Beer-Lambert is exponential in the path).
        const MediumSet media({fog});
        const Rgb half = media.transmittance(
            Ray{Vec3(-5.0f, 1.0f, 1.0f), Vec3(1, 0, 0), 0.0f, 5.0f + static_cast<float>(v / 2)});
        EXPECT_NEAR(half.g, std::sqrt(0.05f), std::sqrt(0.05f) * 1e-5f) << "V = " << v << " m";
    }
}

TEST(FogVisibility, KoschmiederThresholdGivesTwoPercent) {
    for (const double v : {20.0, 60.0, 250.0, 1000.0, 20000.0}) {
        const Rgb t = transmittance_across(parse(box_fog(v, R"(, "contrast_threshold": 0.02)")),
                                           static_cast<float>(v));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(t[c], 0.02f, 0.02f * 1e-5f) << "V = " << v << " m";
    }
    // Any threshold in (0, 1).
    const Rgb t =
        transmittance_across(parse(box_fog(100.0, R"(, "contrast_threshold": 0.3)")), 100.0f);
    EXPECT_NEAR(t.b, 0.3f, 0.3f * 1e-5f);
}

// The published constants: sigma_t V = 3.912 (Koschmieder) and 2.996 (MOR), to their 4 digits.
TEST(FogVisibility, ExtinctionMatchesThePublishedConstants) {
    const auto koschmieder = std::get<HomogeneousMedium>(
        parse(R"({"type": "homogeneous", "visibility_m": 1000, "contrast_threshold": 0.02})")
            .model);
    EXPECT_NEAR(koschmieder.sigma_t().r * 1000.0f, 3.912f, 0.0005f);
    const auto mor = std::get<HomogeneousMedium>(
        parse(R"({"type": "homogeneous", "visibility_m": 1000})").model);
    EXPECT_NEAR(mor.sigma_t().r * 1000.0f, 2.996f, 0.0005f);
    EXPECT_EQ(kMorContrastThreshold, 0.05);
    EXPECT_EQ(kKoschmiederContrastThreshold, 0.02);
}

// The albedo splits sigma_t into scattering and absorption and leaves the transmittance alone;
// without it the fog only scatters.
TEST(FogVisibility, AlbedoSplitsTheExtinction) {
    const auto white = std::get<HomogeneousMedium>(parse(box_fog(80.0)).model);
    EXPECT_EQ(white.sigma_a, Rgb(0.0f));
    const Medium tinted = parse(box_fog(80.0, R"(, "albedo": [0.9, 0.95, 1.0])"));
    const auto& m = std::get<HomogeneousMedium>(tinted.model);
    const float sigma_t = white.sigma_t().r;
    EXPECT_NEAR(m.sigma_s.r, 0.9f * sigma_t, 1e-6f * sigma_t);
    EXPECT_NEAR(m.sigma_a.r, 0.1f * sigma_t, 1e-6f * sigma_t);
    EXPECT_EQ(m.sigma_a.b, 0.0f);
    const Rgb t = transmittance_across(tinted, 80.0f);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(t[c], 0.05f, 0.05f * 1e-5f);
}

// The unbiased tracker the renderer uses for shadow rays agrees: delta tracking's mean over
// N = 40000 binary estimates of T = 0.02 has standard deviation sqrt(T (1 - T) / N) = 7.0e-4;
// the 5-sigma bound fails falsely with probability 6e-7 (fixed seed: deterministic).
TEST(FogVisibility, DeltaTrackingOverTheVisibilityAveragesToTheThreshold) {
    const MediumSet media({parse(box_fog(150.0, R"(, "contrast_threshold": 0.02)"))});
    const Ray ray{Vec3(-5.0f, 1.0f, 1.0f), Vec3(1, 0, 0), 0.0f, 160.0f};
    const int n = 40000;
    Pcg32 rng(7, 11);
    VolumeCounters counters;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        sum += estimate_transmittance(media, ray, Estimator::Delta, 0.0f, rng, counters).r;
    const double sigma = std::sqrt(0.02 * 0.98 / n);
    EXPECT_NEAR(sum / n, 0.02, 5.0 * sigma);
}

// The example scene uses the key; its fog passes 5% over the 60 m to the far post.
TEST(FogVisibility, ExampleSceneFog) {
    const std::string path = std::string(KASUMI_SOURCE_DIR) + "/data/scenes/fog_visibility.json";
    const Json doc = read_json_file(path);
    const Medium fog = parse_medium(JsonNode(doc["media"][0], path, "/media/0"), 0);
    const MediumSet media({fog});
    const Rgb t = media.transmittance(Ray{Vec3(0.0f, 1.7f, 6.0f), Vec3(0, 0, -1), 0.0f, 60.0f});
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(t[c], 0.05f, 0.05f * 1e-5f);
}

TEST(FogVisibility, VisibilityAndSigmasTogetherAreRejected) {
    for (const char* extra :
         {R"("sigma_a": 0.01, "sigma_s": 0.05)", R"("sigma_a": 0.01)", R"("sigma_s": 0.05)"}) {
        const std::string e =
            error_of(std::string(R"({"type": "homogeneous", "visibility_m": 100, )") + extra + "}");
        EXPECT_NE(e.find("/media/0/visibility_m"), std::string::npos) << e;
        EXPECT_NE(e.find("not both"), std::string::npos) << e;
    }
}

TEST(FogVisibility, BadVisibilityIsRejected) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const double v : {0.0, -0.0, -50.0, inf, -inf, nan, 1e-300}) {
        Json doc = {{"type", "homogeneous"}, {"visibility_m", v}};
        const std::string e = error_of_doc(doc);
        EXPECT_NE(e.find("/media/0/visibility_m"), std::string::npos) << v << ": " << e;
    }
    EXPECT_NE(error_of(R"({"type": "homogeneous", "visibility_m": "1 km"})").find("visibility_m"),
              std::string::npos);
}

TEST(FogVisibility, BadThresholdIsRejected) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const double eps : {0.0, 1.0, -0.05, 1.5, inf, nan}) {
        Json doc = {{"type", "homogeneous"}, {"visibility_m", 100.0}, {"contrast_threshold", eps}};
        const std::string e = error_of_doc(doc);
        EXPECT_NE(e.find("/media/0/contrast_threshold"), std::string::npos) << eps << ": " << e;
    }
}

TEST(FogVisibility, KeysThatNeedVisibilityAreRejectedWithoutIt) {
    std::string e = error_of(
        R"({"type": "homogeneous", "sigma_a": 0, "sigma_s": 0.1, "contrast_threshold": 0.05})");
    EXPECT_NE(e.find("/media/0/contrast_threshold"), std::string::npos) << e;
    e = error_of(R"({"type": "homogeneous", "sigma_a": 0, "sigma_s": 0.1, "albedo": 0.9})");
    EXPECT_NE(e.find("/media/0/albedo"), std::string::npos) << e;
    e = error_of(R"({"type": "homogeneous", "visibility_m": 100, "albedo": 1.2})");
    EXPECT_NE(e.find("/media/0/albedo"), std::string::npos) << e;
    e = error_of(R"({"type": "homogeneous"})");
    EXPECT_NE(e.find("visibility_m"), std::string::npos) << e;
    // The sigma form is unchanged.
    const auto m = std::get<HomogeneousMedium>(
        parse(R"({"type": "homogeneous", "sigma_a": 0.01, "sigma_s": 0.05})").model);
    EXPECT_EQ(m.sigma_a, Rgb(0.01f));
    EXPECT_EQ(m.sigma_s, Rgb(0.05f));
}

// A grid by its visibility: V is the visibility where density_scale × density is 1. An 8³ box of
// density 1 in voxels of V / 8: a ray through two opposite faces crosses V of density 1 (the
// trilinear ramps integrate like a sharp box, vdb_test_grids.h), so its transmittance is eps,
// and eps^2 at density_scale 2. The march at 1/200 of a voxel is deterministic and exact but for
// the trapezoid rule at the ramps' two kinks and float rounding (measured: below 1e-6 relative;
// the bound is 1e-5).
TEST(FogVisibility, GridTransmittanceOverTheVisibilityIsTheThreshold) {
    for (const double v : {40.0, 2000.0}) {
        const double voxel = v / 8.0;
        const std::string path =
            test::write_box("visibility_box_" + std::to_string(int(v)), 8, 1.0f, voxel);
        const float centre = static_cast<float>(3.5 * voxel);
        const Ray ray{Vec3(static_cast<float>(-2.0 * voxel), centre, centre), Vec3(1, 0, 0), 0.0f,
                      static_cast<float>(12.0 * voxel)};
        for (const double eps : {kMorContrastThreshold, kKoschmiederContrastThreshold}) {
            for (const double scale : {1.0, 2.0}) {
                Json keys = {{"visibility_m", v}, {"density_scale", scale}, {"albedo", 0.9}};
                if (eps != kMorContrastThreshold)
                    keys["contrast_threshold"] = eps;
                const MediumSet media({test::vdb_medium(path, keys)});
                Pcg32 rng(3, 5);
                VolumeCounters counters;
                const Rgb t = estimate_transmittance(
                    media, ray, Estimator::March, static_cast<float>(voxel / 200.0), rng, counters);
                const double expected = std::pow(eps, scale);
                EXPECT_NEAR(t.g, expected, 1e-5 * expected)
                    << "V = " << v << " m, eps = " << eps << ", density_scale " << scale;
                EXPECT_EQ(t.r, t.b);  // grey
            }
        }
    }
}

TEST(FogVisibility, GridAlbedoSplitsTheExtinctionPerUnitDensity) {
    const std::string path = test::write_box("visibility_box_split", 4, 1.0f, 1.0);
    const Medium m = test::vdb_medium(
        path, {{"visibility_m", 100.0}, {"density_scale", 3.0}, {"albedo", {0.9, 0.5, 0.0}}});
    const VdbMedium& grid = std::get<VdbMedium>(m.model);
    const float sigma_t = static_cast<float>(3.0 * extinction_from_visibility(100.0, 0.05));
    const Rgb t = grid.sigma_t_per_density();
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(t[c], sigma_t, 1e-6f * sigma_t) << c;
    EXPECT_NEAR(grid.sigma_s_per_density.r, 0.9f * sigma_t, 1e-6f * sigma_t);
    EXPECT_NEAR(grid.sigma_s_per_density.g, 0.5f * sigma_t, 1e-6f * sigma_t);
    EXPECT_EQ(grid.sigma_s_per_density.b, 0.0f);
}

TEST(FogVisibility, BadGridVisibilityIsRejected) {
    const std::string path = test::write_box("visibility_box_bad", 4, 1.0f, 1.0);
    const auto error = [&](const Json& keys) {
        return input_error([&] { test::vdb_medium(path, keys); });
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const double v : {0.0, -50.0, nan, 1e-300}) {
        const std::string e = error({{"visibility_m", v}});
        EXPECT_NE(e.find("/media/0/visibility_m"), std::string::npos) << v << ": " << e;
    }
    for (const double eps : {0.0, 1.0, nan}) {
        const std::string e = error({{"visibility_m", 100.0}, {"contrast_threshold", eps}});
        EXPECT_NE(e.find("/media/0/contrast_threshold"), std::string::npos) << eps << ": " << e;
    }
    std::string e = error({{"visibility_m", 100.0}, {"sigma_a", 0.1}, {"sigma_s", 0.1}});
    EXPECT_NE(
        e.find("/media/0/visibility_m = 100.0: give either visibility_m or sigma_a and sigma_s"),
        std::string::npos)
        << e;
    e = error({{"contrast_threshold", 0.05}});
    EXPECT_NE(e.find("/media/0/contrast_threshold = 0.05: goes with visibility_m"),
              std::string::npos)
        << e;
    // A finite V whose extinction overflows a float only once density_scale multiplies it.
    e = error({{"visibility_m", 1e-8}, {"density_scale", 1e35}});
    EXPECT_NE(e.find("/media/0/visibility_m"), std::string::npos) << e;
}

}  // namespace
}  // namespace kasumi
