// kasumi study: error metrics on synthetic images (exact), the standard error of a two-half
// reference, the Pareto front on known points, combination expansion and --vary parsing.
#include "study/study.h"
#include "core/error.h"
#include "core/rng.h"
#include "study/study_report.h"
#include "study/svg_plot.h"
#include "tests/scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace kasumi {
namespace {

RgbPlane plane(int w, int h, std::vector<Rgb> pixels) {
    return RgbPlane{w, h, std::move(pixels)};
}

TEST(StudyMetrics, ExactOnSyntheticImages) {
    // Reference luminances 1, 3 and 0.05: mean Ybar = 4.05 / 3 = 1.35, floor 0.1 Ybar = 0.135,
    // so the dark third pixel does not enter the max relative error.
    const RgbPlane reference = plane(3, 1, {Rgb(1.0f), Rgb(3.0f), Rgb(0.05f)});
    const RgbPlane test = plane(3, 1, {Rgb(1.5f), Rgb(3.0f), Rgb(0.25f)});
    const ImageError e = image_error(test, reference);
    const double ybar = (1.0 + 3.0 + 0.05) / 3.0;
    const double eps = (0.01 * ybar) * (0.01 * ybar);
    EXPECT_NEAR(e.eps, eps, 1e-9);
    EXPECT_NEAR(e.luminance_floor, 0.1 * ybar, 1e-7);
    // Squared differences per channel: 0.25, 0, 0.04 (three channels each, nine in all).
    EXPECT_NEAR(e.rmse, std::sqrt(3.0 * (0.25 + 0.04) / 9.0), 1e-6);
    const double rel = 3.0 * (0.25 / (1.0 + eps) + 0.04 / (0.0025 + eps)) / 9.0;
    EXPECT_NEAR(e.rel_mse, rel, 1e-6 * rel);
    EXPECT_NEAR(e.max_rel_luminance, 0.5, 1e-6);  // not 4.0 from the dark pixel
    EXPECT_EQ(e.pixels_above_floor, 2u);
    EXPECT_NEAR(e.mean_luminance_error, (4.75 - 4.05) / 4.05, 1e-6);
}

TEST(StudyMetrics, ZeroForIdenticalImagesAndScaleFree) {
    const RgbPlane a = plane(2, 1, {Rgb(0.2f, 0.5f, 0.9f), Rgb(4.0f, 1.0f, 0.0f)});
    EXPECT_EQ(image_error(a, a).rmse, 0.0);
    EXPECT_EQ(image_error(a, a).rel_mse, 0.0);
    // Relative MSE and max relative error do not change when both images scale by 1000.
    RgbPlane b = a, a1000 = a, b1000 = a;
    b.pixels[0].g = 0.6f;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        a1000.pixels[i] = a.pixels[i] * 1000.0f;
        b1000.pixels[i] = b.pixels[i] * 1000.0f;
    }
    const ImageError small = image_error(b, a), large = image_error(b1000, a1000);
    EXPECT_NEAR(large.rel_mse, small.rel_mse, 1e-5 * small.rel_mse);
    EXPECT_NEAR(large.max_rel_luminance, small.max_rel_luminance, 1e-5);
    EXPECT_NEAR(large.rmse, 1000.0 * small.rmse, 1e-3 * large.rmse);
}

TEST(StudyMetrics, SizeMismatchIsAnInputError) {
    try {
        image_error(plane(1, 1, {Rgb(1.0f)}), plane(2, 1, {Rgb(1.0f), Rgb(1.0f)}));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
    }
}

TEST(StudyMetrics, ReferenceStandardErrorExact) {
    // Halves 1 + d and 1 - d: the mean is 1 and (a - b)^2 / 4 = d^2 everywhere.
    const float d = 0.1f;
    const RgbPlane a = plane(2, 1, {Rgb(1.0f + d), Rgb(1.0f + d)});
    const RgbPlane b = plane(2, 1, {Rgb(1.0f - d), Rgb(1.0f - d)});
    const ImageError e = reference_standard_error(a, b);
    EXPECT_NEAR(e.rmse, d, 1e-6);
    EXPECT_NEAR(e.rel_mse, d * d / (1.0 + e.eps), 1e-6);
}

TEST(StudyMetrics, ReferenceStandardErrorMatchesGaussianNoise) {
    // Halves are mu + N(0, s^2) per pixel and channel: their mean has standard error s / sqrt(2).
    // The estimate averages 3 x 10^4 terms (a - b)^2 / 4 whose relative standard deviation is
    // sqrt(2): the estimated variance is within 5% (6 standard deviations; false-failure rate
    // ~1e-9, and the seed is fixed).
    const int n = 10000;
    const float mu = 5.0f, s = 0.3f;
    Pcg32 rng(12345u, 7u);
    auto gauss = [&] {
        const float u1 = std::max(rng.next_float(), 1e-7f), u2 = rng.next_float();
        return std::sqrt(-2.0f * std::log(u1)) * std::cos(6.2831853f * u2);
    };
    RgbPlane a{n, 1, {}}, b{n, 1, {}};
    for (int i = 0; i < n; ++i) {
        a.pixels.push_back(Rgb(mu + s * gauss(), mu + s * gauss(), mu + s * gauss()));
        b.pixels.push_back(Rgb(mu + s * gauss(), mu + s * gauss(), mu + s * gauss()));
    }
    const ImageError e = reference_standard_error(a, b);
    EXPECT_NEAR(e.rmse * e.rmse, s * s / 2.0, 0.05 * s * s / 2.0);
}

TEST(StudyPareto, KnownPoints) {
    // (time, error): 0 (1, 10) front; 1 (2, 5) front; 2 (3, 6) dominated by 1; 3 (4, 1) front;
    // 4 (2, 5) duplicate of 1 (first kept); 5 (0.5, 20) front; 6 (5, 1) dominated by 3.
    const std::vector<double> time{1, 2, 3, 4, 2, 0.5, 5};
    const std::vector<double> error{10, 5, 6, 1, 5, 20, 1};
    EXPECT_EQ(pareto_front(time, error), (std::vector<size_t>{5, 0, 1, 3}));
    EXPECT_TRUE(pareto_front({}, {}).empty());
    EXPECT_EQ(pareto_front({3.0}, {2.0}), (std::vector<size_t>{0}));
}

TEST(StudyAxes, CombinationsLastAxisFastest) {
    const std::vector<StudyAxis> axes{{"/a", {"1", "2"}}, {"spp", {"1", "4", "16"}}};
    const auto c = expand_combinations(axes);
    ASSERT_EQ(c.size(), 6u);
    EXPECT_EQ(c[0], (std::vector<size_t>{0, 0}));
    EXPECT_EQ(c[1], (std::vector<size_t>{0, 1}));
    EXPECT_EQ(c[2], (std::vector<size_t>{0, 2}));
    EXPECT_EQ(c[3], (std::vector<size_t>{1, 0}));
    EXPECT_EQ(c[5], (std::vector<size_t>{1, 2}));
    EXPECT_EQ(expand_combinations({}).size(), 1u);
    EXPECT_EQ(
        expand_combinations({{"/a", {"1"}}, {"/b", {"x", "y"}}, {"/c", {"1", "2", "3"}}}).size(),
        6u);
}

ErrorKind kind_of(const std::string& text) {
    try {
        parse_vary(text);
    } catch (const Error& e) {
        return e.kind();
    }
    return ErrorKind::Runtime;  // did not throw
}

TEST(StudyAxes, ParseVary) {
    const StudyAxis a = parse_vary("/render/volume/step_m=0.1,0.2,0.4");
    EXPECT_EQ(a.key, "/render/volume/step_m");
    EXPECT_EQ(a.values, (std::vector<std::string>{"0.1", "0.2", "0.4"}));
    const StudyAxis arrays = parse_vary("/media/0/sigma_s=[0.1,0.2,0.3],0.5,\"a,b\"");
    EXPECT_EQ(arrays.values, (std::vector<std::string>{"[0.1,0.2,0.3]", "0.5", "\"a,b\""}));
    EXPECT_EQ(parse_vary("spp=1,4").key, "spp");
    EXPECT_EQ(study_pointers("spp"), (std::vector<std::string>{"/film/spp"}));
    EXPECT_EQ(study_pointers("/lights/0/samples+/lights/1/samples"),
              (std::vector<std::string>{"/lights/0/samples", "/lights/1/samples"}));
    EXPECT_EQ(kind_of("/lights/0/samples+samples=1,2"), ErrorKind::Usage);
    EXPECT_EQ(kind_of("step_m"), ErrorKind::Usage);              // no '='
    EXPECT_EQ(kind_of("step_m=1,2"), ErrorKind::Usage);          // not a pointer
    EXPECT_EQ(kind_of("/render/seed=1,,2"), ErrorKind::Usage);   // empty value
    EXPECT_EQ(kind_of("/render/seed=1,2,1"), ErrorKind::Usage);  // repeated value
    EXPECT_EQ(kind_of("spp=4,2.5"), ErrorKind::Usage);           // not an integer
    EXPECT_EQ(kind_of("spp=0"), ErrorKind::Usage);
    EXPECT_EQ(kind_of("=1"), ErrorKind::Usage);
}

TEST(StudyAxes, MostAccurateValue) {
    EXPECT_EQ(most_accurate_value(parse_vary("/render/volume/step_m=0.4,0.1,0.2")), "0.1");
    EXPECT_EQ(most_accurate_value(parse_vary("/lights/0/samples=1,16,4")), "16");
    EXPECT_EQ(most_accurate_value(parse_vary("/render/volume/integrator=multiple,single")),
              "multiple");
    EXPECT_EQ(most_accurate_value(parse_vary("/render/volume/estimator=march,delta,ratio")),
              "ratio");
}

TEST(StudyDocument, CreatesMissingParents) {
    const ScratchDir dir("kasumi_study_");
    const std::string path = dir.write("s.json", R"({"film": {"width": 4}})");
    const Json doc = study_document(path, {"/render/volume/step_m=0.5", "/film/spp=3"});
    EXPECT_EQ(doc["render"]["volume"]["step_m"].get<double>(), 0.5);
    EXPECT_EQ(doc["film"]["spp"].get<int>(), 3);
    EXPECT_EQ(doc["film"]["width"].get<int>(), 4);
}

TEST(StudyDocument, WildcardsExpandOverArraysAndObjects) {
    const Json doc = Json::parse(R"({"lights": [{"a": 1}, {"a": 2}, {"a": 3}],
                                     "materials": {"x/y": {"kd": 1}, "z": {"kd": 2}},
                                     "empty": []})");
    EXPECT_EQ(
        expand_wildcards(doc, "/lights/*/samples", "s.json"),
        (std::vector<std::string>{"/lights/0/samples", "/lights/1/samples", "/lights/2/samples"}));
    // Object keys are re-escaped (RFC 6901: '/' is ~1); nlohmann keeps keys sorted.
    EXPECT_EQ(expand_wildcards(doc, "/materials/*/kd", "s.json"),
              (std::vector<std::string>{"/materials/x~1y/kd", "/materials/z/kd"}));
    EXPECT_EQ(expand_wildcards(doc, "/render/seed", "s.json"),
              (std::vector<std::string>{"/render/seed"}));
    for (const char* bad : {"/empty/*/x", "/missing/*", "/lights/0/a/*"}) {
        try {
            expand_wildcards(doc, bad, "s.json");
            FAIL() << bad;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input) << bad;
            EXPECT_NE(std::string(e.what()).find(std::string("s.json: ") + bad), std::string::npos)
                << e.what();
        }
    }
}

TEST(StudyDocument, ObjectValuesMergeIntoObjects) {
    const ScratchDir dir("kasumi_study_");
    const std::string path = dir.write("s.json", R"({"lights": [{"type": "point", "shadows": "map",
                                            "shadow_map": {"resolution": 64, "bias": 0.1}},
                                           {"type": "point"}]})");
    // Merge (RFC 7396): members replace or add, nested objects merge, null removes.
    const Json doc = study_document_of(
        path, std::vector<StudySetting>{
                  {"/lights/*", R"({"shadow_map": {"resolution": 512}, "samples": 4})", true},
                  {"/lights/0", R"({"shadows": null})", true}});
    EXPECT_FALSE(doc["lights"][0].contains("shadows"));
    EXPECT_EQ(doc["lights"][0]["shadow_map"]["resolution"].get<int>(), 512);
    EXPECT_EQ(doc["lights"][0]["shadow_map"]["bias"].get<double>(), 0.1);
    EXPECT_EQ(doc["lights"][1]["samples"].get<int>(), 4);
    EXPECT_EQ(doc["lights"][1]["type"].get<std::string>(), "point");
    // Without merge an object replaces the value, and a missing object is created either way.
    const Json replaced = study_document_of(
        path, std::vector<StudySetting>{{"/lights/0/shadow_map", R"({"resolution": 8})", false},
                                        {"/render/volume", R"({"step_m": 2})", true}});
    EXPECT_FALSE(replaced["lights"][0]["shadow_map"].contains("bias"));
    EXPECT_EQ(replaced["render"]["volume"]["step_m"].get<double>(), 2.0);
    // The string form expands wildcards too.
    const Json set = study_document(path, {"/lights/*/samples=2"});
    EXPECT_EQ(set["lights"][0]["samples"].get<int>(), 2);
    EXPECT_EQ(set["lights"][1]["samples"].get<int>(), 2);
}

TEST(SvgPlot, OneLinePerSeriesAndFrontRings) {
    LinePlot plot;
    plot.title = "a < b";
    plot.series = {{"s1", {{0.1, 1.0}, {1.0, 0.1}}}, {"s2", {{0.2, 2.0}, {0.0, 1.0}}}};
    plot.front = {{0.1, 1.0}, {1.0, 0.1}};
    const std::string svg = svg_line_plot(plot);
    size_t polylines = 0;
    for (size_t p = svg.find("<polyline"); p != std::string::npos; p = svg.find("<polyline", p + 1))
        ++polylines;
    EXPECT_EQ(polylines, 3u);  // two series and the front
    EXPECT_NE(svg.find("a &lt; b"), std::string::npos);
    EXPECT_EQ(svg.rfind("</svg>\n"), svg.size() - 7);
    // Three plottable series points (the x = 0 one is left out) plus two rings and a legend ring.
    size_t circles = 0;
    for (size_t p = svg.find("<circle"); p != std::string::npos; p = svg.find("<circle", p + 1))
        ++circles;
    EXPECT_EQ(circles, 6u);
}

TEST(SvgPlot, LinearAxisAndDecadesClampedAtTheBottom) {
    LinePlot plot;  // as `kasumi phase plot` draws p(theta)
    plot.x = {"angle", AxisScale::Linear, 0.0, 180.0, 30.0};
    plot.y.label = "p";
    plot.y.max_decades = 2;
    plot.series = {{"curve", {{0.0, 100.0}, {90.0, 0.0}, {180.0, 1e-5}}, false}};
    const std::string svg = svg_line_plot(plot);
    for (const char* label : {">0<", ">30<", ">90<", ">180<", ">1<", ">10<", ">100<", ">curve<"})
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    EXPECT_EQ(svg.find(">0.1<"), std::string::npos);  // two decades below the top only
    EXPECT_EQ(svg.find("<circle"), std::string::npos);
    // 0 and 1e-5 sit on the bottom edge (y = 420) at x = 0, 90 and 180 degrees (80 to 540).
    EXPECT_NE(svg.find("points=\"80.0,40.0 310.0,420.0 540.0,420.0 \""), std::string::npos) << svg;
}

TEST(StudyRun, ErrorFallsWithSamplesAndFilesAreWritten) {
    // Homogeneous fog lit by a point light, 12x8 pixels. Monte Carlo variance falls as 1/spp
    // and the 512-spp reference adds its own: MSE(1 spp) ~ s^2 (1 + 1/512) against
    // MSE(16 spp) ~ s^2 (1/16 + 1/512), a ratio near 15; asserting 4 leaves a wide margin.
    // Seeds are fixed, so the test is deterministic.
    const ScratchDir dir("kasumi_study_");
    const std::string path = dir.write("fog.json", R"({
      "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "film": {"width": 12, "height": 8, "spp": 1},
      "lights": [{"type": "point", "position": [0.5, 1, 0], "intensity_cd": 100}],
      "media": [{"type": "homogeneous", "bounds": [[-3, -3, -3], [3, 3, 3]],
                 "sigma_a": 0.05, "sigma_s": 0.3}],
      "render": {"seed": 3, "threads": 1}
    })");
    StudySpec spec;
    spec.scene_path = path;
    spec.axes = {parse_vary("spp=1,16")};
    spec.repeats = 1;
    spec.threads = 1;
    spec.reference_spp = 512;
    const StudyResult r = run_study(spec);
    ASSERT_EQ(r.rows.size(), 2u);
    EXPECT_EQ(r.rows[0].spp, 1);
    EXPECT_EQ(r.rows[1].spp, 16);
    EXPECT_GT(r.rows[0].error.rel_mse, 4.0 * r.rows[1].error.rel_mse);
    EXPECT_TRUE(r.reference.has_standard_error);
    EXPECT_LT(r.reference.standard_error.rel_mse, r.rows[1].error.rel_mse);
    write_study(r, (dir.path() / "out").string());
    for (const char* f : {"study.csv", "study.md", "study.svg"})
        EXPECT_TRUE(std::filesystem::exists(dir.path() / "out" / f)) << f;
}

TEST(StudyRun, BuildTimingRendersTheSameImages) {
    // Timing the build as well (each repeat builds the runtime from the parsed scene) must not
    // change what is rendered: with fixed seeds the errors equal those of render-only timing,
    // for an axis that merges an object into every light (ray-traced shadows vs a shadow map).
    const ScratchDir dir("kasumi_study_");
    const std::string path = dir.write("shadow.json", R"({
      "camera": {"position": [0, 3, 5], "look_at": [0, 0, 0]},
      "film": {"width": 12, "height": 8, "spp": 1, "jitter": false},
      "materials": {"m": {"type": "phong", "kd": 0.7}},
      "shapes": [{"type": "quad", "material": "m",
                  "vertices": [[-3, 0, 3], [3, 0, 3], [3, 0, -3], [-3, 0, -3]]},
                 {"type": "sphere", "material": "m", "center": [0, 0.5, 0], "radius": 0.5}],
      "lights": [{"type": "point", "position": [0.5, 3, 0], "intensity_cd": 10}],
      "render": {"seed": 3}
    })");
    StudySpec spec;
    spec.scene_path = path;
    // The automatic reference takes the last object listed: ray-traced shadows.
    spec.axes = {parse_vary(R"(/lights/*={"shadows":"map","shadow_map":{"resolution":64}},)"
                            R"({"shadows":"ray"})")};
    spec.repeats = 2;
    spec.threads = 1;
    spec.reference_spp = 4;
    const StudyResult render_only = run_study(spec);
    spec.timing = StudyTiming::BuildRender;
    const StudyResult with_build = run_study(spec);
    ASSERT_EQ(with_build.rows.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(with_build.rows[i].error.rmse, render_only.rows[i].error.rmse) << i;
        EXPECT_EQ(with_build.rows[i].seconds.size(), 2u);
    }
    // Pixel centres and a point light: no randomness, so ray-traced shadows equal the
    // ray-traced reference exactly, and the 64² map (texels ~9 cm, PCF over 3x3 of them)
    // changes pixels along the ball's shadow edge.
    EXPECT_GT(with_build.rows[0].error.rmse, 0.0);
    EXPECT_EQ(with_build.rows[1].error.rmse, 0.0);
    EXPECT_NE(study_markdown(with_build).find("shadow_map.resolution=64, shadows=map"),
              std::string::npos);
}

TEST(StudyRun, ProbeAgainstExactBeerLambert) {
    // A homogeneous box of sigma_t = 0.05 + 0.3 = 0.35 /m crossed over d = 6 m: the exact
    // reference must be exp(-2.1) in every channel. Delta tracking averages Bernoulli
    // estimates of p = T, s.e. sqrt(p (1 - p) / N) = 0.0033 at N = 1e4; |error| < 4 s.e. fails
    // with probability 6e-5 (fixed seeds: deterministic). The march is exact in a homogeneous
    // medium (optical depth integrated analytically), so its error is rounding only.
    const ScratchDir dir("kasumi_study_");
    const std::string path = dir.write("fog.json", R"({
      "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "film": {"width": 4, "height": 4, "spp": 1},
      "media": [{"type": "homogeneous", "bounds": [[-3, -3, -3], [3, 3, 3]],
                 "sigma_a": 0.05, "sigma_s": 0.3}],
      "render": {"seed": 3, "threads": 1}
    })");
    StudySpec spec;
    spec.scene_path = path;
    spec.axes = {parse_vary("/render/volume/estimator=march,delta"), parse_vary("spp=10000")};
    spec.repeats = 1;
    StudyProbe probe;
    probe.kind = StudyProbe::Kind::Transmittance;
    probe.a = Vec3(0.0f, 0.0f, -5.0f);
    probe.b = Vec3(0.0f, 0.0f, 5.0f);
    probe.exact_beer_lambert = true;
    spec.probe = probe;
    const StudyResult r = run_study(spec);
    const double exact = std::exp(-0.35 * 6.0);
    EXPECT_TRUE(r.reference.exact);
    EXPECT_EQ(r.width, 1);
    ASSERT_EQ(r.rows.size(), 2u);
    EXPECT_LT(r.rows[0].error.rmse, 1e-6);  // march
    const double se = std::sqrt(exact * (1.0 - exact) / 1e4);
    EXPECT_GT(r.rows[1].error.rmse, 0.0);  // delta tracking is noisy
    EXPECT_LT(r.rows[1].error.rmse, 4.0 * se);
    // The reference is the closed form: shifting the exact value by 1% shows up as a 1% error
    // of the exact march.
    spec.probe->exact_beer_lambert = false;
    spec.probe->exact = Rgb(static_cast<float>(1.01 * exact));
    const StudyResult shifted = run_study(spec);
    EXPECT_NEAR(shifted.rows[0].error.max_rel_luminance, 0.01 / 1.01, 1e-5);
    EXPECT_FALSE(study_markdown(shifted).find("transmittance from (0, 0, -5) to (0, 0, 5)") ==
                 std::string::npos);
}

}  // namespace
}  // namespace kasumi
