// film.denoise on a real render (cloud.json, multiple scattering through a VDB cloud, 48x27):
// the denoised image is closer to a high-spp render of another seed than the raw one, its mean
// luminance agrees with it within the stated bound, the raw beauty survives as noisy.R/G/B, the
// image does not depend on the thread count; the plan names the stage; bad values exit 3.
#include "core/error.h"
#include "render/renderer.h"
#include "scene/plan.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

SceneDesc small_cloud(int spp, int seed, const char* denoise) {
    return load_scene(KASUMI_SOURCE_DIR "/data/scenes/cloud.json",
                      {{"/film/width", "48"},
                       {"/film/height", "27"},
                       {"/film/spp", std::to_string(spp)},
                       {"/render/seed", std::to_string(seed)},
                       {"/film/denoise", denoise}});
}

std::vector<double> luminances(const Image& image, const char* prefix = "") {
    const std::string p(prefix);
    const ImageChannel *r = image.find(p + "R"), *g = image.find(p + "G"), *b = image.find(p + "B");
    EXPECT_TRUE(r != nullptr && g != nullptr && b != nullptr) << prefix;
    std::vector<double> y(r != nullptr ? r->data.size() : 0);
    for (size_t i = 0; i < y.size(); ++i)
        y[i] = luminance(Rgb(r->data[i], g->data[i], b->data[i]));
    return y;
}

/// Relative MSE sum (x - ref)² / sum ref² of the luminance.
double rel_mse(const std::vector<double>& x, const std::vector<double>& ref) {
    double e = 0.0, s = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        e += (x[i] - ref[i]) * (x[i] - ref[i]);
        s += ref[i] * ref[i];
    }
    return e / s;
}

double mean(const std::vector<double>& y) {
    double s = 0.0;
    for (double v : y)
        s += v;
    return s / static_cast<double>(y.size());
}

// 16 spp, denoised, against 1024 spp of another seed. The raw 16-spp image is the R/G/B of
// the same render kept in noisy.R/G/B, so both errors are measured on one set of samples.
// Measured: relative MSE 0.079 raw, 0.038 denoised; mean luminance 0.992 (raw) and 0.976
// (denoised) of the reference's. Tested: the denoised error at most 0.7 of the raw one, and the
// filter's own shift of the mean luminance (denoised against raw, same samples: -1.6%, the
// downward drift of docs/denoising.md, larger at this coarse 48x27 than at 96x54) within 3%.
TEST(DenoiseRender, CloserToReferenceAndSameMeanLuminance) {
    const Image reference =
        render_image(SceneRuntime(small_cloud(1024, 11, "\"off\"")), quiet(0)).film.to_image();
    RenderOptions with_noisy = quiet(0);
    with_noisy.aovs |= kAovNoisy;  // the raw beauty beside the denoised one
    const Image denoised =
        render_image(SceneRuntime(small_cloud(16, 3, "\"nlm\"")), with_noisy).film.to_image();
    const auto y_ref = luminances(reference), y_denoised = luminances(denoised),
               y_raw = luminances(denoised, "noisy.");
    const double e_raw = rel_mse(y_raw, y_ref), e_denoised = rel_mse(y_denoised, y_ref);
    EXPECT_LT(e_denoised, 0.7 * e_raw) << "raw " << e_raw << " denoised " << e_denoised;
    EXPECT_NEAR(mean(y_denoised) / mean(y_raw), 1.0, 0.03);
    EXPECT_NEAR(mean(y_raw) / mean(y_ref), 1.0, 0.03);
    std::printf("rel MSE raw %.4f denoised %.4f; mean luminance ratio %.4f (raw %.4f)\n", e_raw,
                e_denoised, mean(y_denoised) / mean(y_ref), mean(y_raw) / mean(y_ref));
    // The raw beauty is the film's plain mean: exactly what the filter saw.
    const Image off =
        render_image(SceneRuntime(small_cloud(16, 3, "\"off\"")), with_noisy).film.to_image();
    EXPECT_EQ(luminances(off), y_raw);
    EXPECT_EQ(off.find("noisy.R"), nullptr);
}

// film.denoise "select" (render/denoise/sure_selection.h) at 16 and 64 spp (seeds 3-6, errors
// averaged) against 4096 spp of seed 11, raw: the selected image stays below the raw one and
// its error falls with the samples. Measured (rel. MSE of the luminance, 48x27): raw 0.144 ->
// 0.0333, select 0.0386 -> 0.0157 (2.5x), the plain filter 0.0406 -> 0.0161 (2.5x). Tested:
// select below 0.7 of raw at both, and falling >= 1.8x from 16 to 64 spp. A selection stuck
// on the raw mean fails the first; the plain filter alone would pass both (at this coarse
// size, nearly all silhouette, the selection gains 2-5% on it: docs/denoising.md).
TEST(DenoiseRender, SelectedErrorFallsWithSamplesAndStaysBelowRaw) {
    constexpr int kSeeds = 4;  // one seed's error is itself noisy (rare bright paths)
    const Image reference =
        render_image(SceneRuntime(small_cloud(4096, 11, "\"off\"")), quiet(0)).film.to_image();
    const auto y_ref = luminances(reference);
    RenderOptions with_noisy = quiet(0);
    with_noisy.aovs |= kAovNoisy;
    double e_select[2] = {}, e_plain[2] = {}, e_raw[2] = {};
    for (int i = 0; i < 2; ++i) {
        const int spp = i == 0 ? 16 : 64;
        for (int seed = 3; seed < 3 + kSeeds; ++seed) {
            const Image selected =
                render_image(SceneRuntime(small_cloud(spp, seed, R"({"select": true})")),
                             with_noisy)
                    .film.to_image();
            const Image plain =
                render_image(SceneRuntime(small_cloud(spp, seed, "\"nlm\"")), quiet(0))
                    .film.to_image();
            e_raw[i] += rel_mse(luminances(selected, "noisy."), y_ref) / kSeeds;
            e_select[i] += rel_mse(luminances(selected), y_ref) / kSeeds;
            e_plain[i] += rel_mse(luminances(plain), y_ref) / kSeeds;
        }
        std::printf("%d spp: rel MSE raw %.5f select %.5f plain nlm %.5f\n", spp, e_raw[i],
                    e_select[i], e_plain[i]);
        EXPECT_LT(e_select[i], 0.7 * e_raw[i]) << spp << " spp";
    }
    EXPECT_LT(e_select[1], e_select[0] / 1.8) << e_select[0] << " -> " << e_select[1];
}

TEST(DenoiseRender, BitIdenticalWithOneAndTwoThreads) {
    for (const char* denoise : {R"({"method": "nlm", "radius": 5})", R"({"select": true})"}) {
        const SceneRuntime scene(small_cloud(16, 5, denoise));
        const Image one = render_image(scene, quiet(1)).film.to_image();
        const Image two = render_image(scene, quiet(2)).film.to_image();
        ASSERT_EQ(one.channels.size(), two.channels.size());
        for (size_t c = 0; c < one.channels.size(); ++c)
            EXPECT_EQ(one.channels[c].data, two.channels[c].data) << one.channels[c].name;
    }
}

PlanStage denoise_stage(const char* text) {
    for (const PlanStage& s : make_plan(scene_from_text(text)).stages)
        if (s.name == "denoise")
            return s;
    ADD_FAILURE() << "no denoise stage";
    return PlanStage{};
}

TEST(DenoiseRender, PlanNamesTheStage) {
    EXPECT_FALSE(denoise_stage(R"({"film": {"spp": 16}})").enabled);
    const PlanStage on = denoise_stage(R"({"film": {"spp": 16, "denoise": "nlm"}})");
    EXPECT_TRUE(on.enabled);
    EXPECT_NE(on.reason.find("non-local means"), std::string::npos) << on.reason;
    const PlanStage select = denoise_stage(R"({"film": {"spp": 16, "denoise": {"select": true}}})");
    EXPECT_NE(select.reason.find("SURE"), std::string::npos) << select.reason;
    EXPECT_EQ(on.reason.find("SURE"), std::string::npos) << on.reason;
    const PlanStage few = denoise_stage(R"({"film": {"spp": 2, "denoise": {"radius": 3}}})");
    EXPECT_NE(few.reason.find("stay raw"), std::string::npos) << few.reason;
}

TEST(DenoiseRender, BadValueIsAnInputErrorWithItsPointer) {
    for (const char* bad : {"\"oidn\"", "1", "true", "null", R"({"method": "median"})",
                            R"({"radius": 0})", R"({"k": -1})", R"({"patch": 9})",
                            R"({"strength": 1})", R"({"select": 1})", R"({"select": "yes"})"}) {
        try {
            scene_from_text(std::string(R"({"film": {"denoise": )") + bad + "}}");
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input) << bad;
            EXPECT_NE(std::string(e.what()).find("/film/denoise"), std::string::npos) << e.what();
        }
    }
    const DenoiseSettings d =
        scene_from_text(R"({"film": {"denoise": {"radius": 4, "k": 0.3}}})").film.denoise;
    EXPECT_TRUE(d.enabled);
    EXPECT_EQ(d.radius, 4);
    EXPECT_EQ(d.k, 0.3f);
    EXPECT_FALSE(d.select);
    EXPECT_TRUE(scene_from_text(R"({"film": {"denoise": {"select": true}}})").film.denoise.select);
    EXPECT_FALSE(scene_from_text(R"({"film": {"denoise": "off"}})").film.denoise.enabled);
}

}  // namespace
}  // namespace kasumi
