// Image test: the default scene at low resolution against a converged reference EXR made by a
// different estimator: unbiased ratio tracking of the fog (the test renders with the default
// jittered march) at 2048 samples per pixel. Regenerate it on purpose with
// tests/render/regenerate_image_reference.sh (never by a test).
#include "core/exr_io.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace kasumi {
namespace {

constexpr const char* kReference = KASUMI_SOURCE_DIR "/tests/data/fog_street_96x54.exr";
constexpr int kTestSpp = 16;

Image render_fog_street(int spp, int seed) {
    const SceneDesc desc = load_scene(KASUMI_SOURCE_DIR "/data/scenes/fog_street.json",
                                      {{"/film/width", "96"},
                                       {"/film/height", "54"},
                                       {"/film/spp", std::to_string(spp)},
                                       {"/render/seed", std::to_string(seed)}});
    const SceneRuntime scene(desc);
    RenderOptions options;
    options.progress = false;
    const Image full = render_image(scene, options).film.to_image();
    Image rgb(full.width, full.height);
    for (const char* c : {"R", "G", "B", "surface.R", "surface.G", "surface.B"})
        rgb.add_channel(c).data = full.find(c)->data;
    rgb.metadata = {{"spp", std::to_string(spp)}, {"seed", std::to_string(seed)}};
    return rgb;
}

std::vector<double> luminances(const Image& image) {
    std::vector<double> y(image.find("R")->data.size());
    for (size_t i = 0; i < y.size(); ++i) {
        y[i] = luminance(
            Rgb(image.find("R")->data[i], image.find("G")->data[i], image.find("B")->data[i]));
    }
    return y;
}

/// Median over pixels of luminance(a) / luminance(b) for the channels `prefix`R, G, B, over
/// the pixels where b is at least `floor` times its mean.
double median_ratio(const Image& a, const Image& b, const std::string& prefix, double floor) {
    const auto lum = [&](const Image& im, size_t i) {
        return static_cast<double>(
            luminance(Rgb(im.find(prefix + "R")->data[i], im.find(prefix + "G")->data[i],
                          im.find(prefix + "B")->data[i])));
    };
    const size_t n = b.find(prefix + "R")->data.size();
    double mean = 0.0;
    for (size_t i = 0; i < n; ++i)
        mean += lum(b, i) / static_cast<double>(n);
    std::vector<double> ratios;
    for (size_t i = 0; i < n; ++i)
        if (lum(b, i) > floor * mean)
            ratios.push_back(lum(a, i) / lum(b, i));
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    return ratios[ratios.size() / 2];
}

TEST(ImageReference, FogStreetMatchesConvergedReference) {
    const Image reference = read_exr(kReference);
    const Image test = render_fog_street(kTestSpp, 1);
    const std::vector<double> a = luminances(test), b = luminances(reference);
    // Relative MSE per pixel, (a - b)² / (b² + eps²), eps = 1% of the mean luminance: the
    // metric of image-space denoising papers (e.g. Rousselle et al. 2011), robust to the
    // unbounded fog glow at a point light, whose pixels dominate any absolute error.
    double sum_ref = 0.0, sum_test = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        sum_ref += b[i];
        sum_test += a[i];
    }
    const double n = static_cast<double>(a.size());
    const double eps = 0.01 * sum_ref / n;
    double rel_mse = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
        rel_mse += (a[i] - b[i]) * (a[i] - b[i]) / (b[i] * b[i] + eps * eps);
    rel_mse /= n;
    // The surface stage alone (the `surface.*` AOV, L_surface before the fog's transmittance),
    // by the median over pixels of test / reference: the pixels' means are heavy-tailed (point
    // lights' highlights on iron and glass, n = 60 and 200, found by few of 16 jittered
    // samples: the surface mean moves by 10% between seeds) but their median is steady,
    // measured 0.9996-1.0000 for seeds 1-4 at 16 samples and for a 64-sample render; a
    // uniform 2% change of the surfaces' shading moves it by 2%. The mean and the relative MSE
    // (measured 0.977 and 1.4e-3 at seed 1) catch gross errors only.
    const double surface_median = median_ratio(test, reference, "surface.", 0.01);
    std::printf("relative MSE %.5f, mean ratio %.4f, surface median ratio %.5f\n", rel_mse,
                sum_test / sum_ref, surface_median);
    EXPECT_LT(rel_mse, 2.5e-3);
    EXPECT_NEAR(sum_test / sum_ref, 1.0, 0.04);
    EXPECT_NEAR(surface_median, 1.0, 0.005);
}

}  // namespace
}  // namespace kasumi
