// film.denoise "select" (render/denoise/sure_selection.h) on synthetic half buffers whose
// expectation is known: the per-pixel SURE estimate of each candidate's MSE is unbiased where
// the expectation is constant, and the selected output's bias next to a step edge stays within
// the filter's stated bound and falls with the sample count.
#include "render/denoise/sure_selection.h"
#include "tests/render/denoise_synthetic.h"
#include "tests/sample_mean.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

namespace kasumi {
namespace {

using namespace denoise_test;  // NOLINT: the synthetic images of tests/render/denoise_synthetic.h

using Draw = std::function<float(int, Pcg32&)>;

/// Per candidate, the mean over `trials` images of (estimate - true squared error) at the
/// pixels x in [x0, x1), y in [8, 16) (averaged per image, so the images are the independent
/// draws), and the same for the estimate without its divergence term 2 Cov(F, R) (the planted
/// bug); `mu(x)` is the exact expectation.
struct EstimateBias {
    std::vector<MeanAndError> sure, without_divergence;
    std::vector<double> mean_estimate;
};
EstimateBias estimate_bias(int trials, int n, const Draw& draw,
                           const std::function<double(int)>& mu, int x0, int x1) {
    const DenoiseSettings settings;
    const std::vector<StrengthScale>& scales = selection_strengths();
    const size_t candidates = scales.size() + 1;
    std::vector<SampleMean> sure(candidates), naive(candidates), estimate(candidates);
    for (int t = 0; t < trials; ++t) {
        const HalfBuffers halves = synthetic(static_cast<uint64_t>(t) + 7001, n, draw);
        const std::vector<unsigned char> valid = valid_pixels(halves);
        std::vector<CrossFiltered> fa, fb;
        cross_filter_strengths(halves.half(1), halves.half(0), valid, kSize, kSize, settings,
                               scales, fa);
        cross_filter_strengths(halves.half(0), halves.half(1), valid, kSize, kSize, settings,
                               scales, fb);
        const auto mse = estimate_candidate_mse(halves, valid, fa, fb);
        const HalfImage &a = halves.half(0), &b = halves.half(1);
        for (size_t i = 0; i < candidates; ++i) {
            double d = 0.0, d_naive = 0.0, e = 0.0, count = 0.0;
            for (int y = 8; y < 16; ++y) {
                for (int x = x0; x < x1; ++x) {
                    const size_t p = static_cast<size_t>(y) * kSize + x;
                    const double alpha = a.samples[p] / (a.samples[p] + b.samples[p]);
                    const double beta = 1.0 - alpha;
                    double truth = 0.0, divergence = 0.0;
                    for (int c = 0; c < 3; ++c) {
                        const double fa_c = i == 0 ? a.radiance[c][p] : fa[i - 1].rgb[c][p];
                        const double fb_c = i == 0 ? b.radiance[c][p] : fb[i - 1].rgb[c][p];
                        const double f = alpha * fa_c + beta * fb_c;
                        truth += (f - mu(x)) * (f - mu(x));
                        const double wa = i == 0 ? 1.0 : fa[i - 1].weight_sum[p];
                        const double wb = i == 0 ? 1.0 : fb[i - 1].weight_sum[p];
                        divergence += 2.0 * (alpha * alpha * a.radiance_var[c][p] / wa +
                                             beta * beta * b.radiance_var[c][p] / wb);
                    }
                    d += mse[i][p] - truth;
                    d_naive += mse[i][p] - divergence - truth;
                    e += mse[i][p];
                    count += 1.0;
                }
            }
            sure[i].add(d / count);
            naive[i].add(d_naive / count);
            estimate[i].add(e / count);
        }
    }
    EstimateBias out;
    for (size_t i = 0; i < candidates; ++i) {
        out.sure.push_back(sure[i].result());
        out.without_divergence.push_back(naive[i].result());
        out.mean_estimate.push_back(estimate[i].result().mean);
    }
    return out;
}

// A constant image (expectation 1 in each channel), exponential noise, 16 samples a pixel, 400
// images: for every candidate (raw, k/2, k) the estimate minus the true squared error averages
// to 0 within 4 SE (false failure ~6e-5 each). The raw candidate's estimate is its variance
// exactly, the filtered ones' are not: the test catches a wrong divergence (dropping the term
// 2 Cov(F, R), the planted bug, is off by > 4 SE for the raw mean and the plain filter: -0.38
// and -0.011 against SE 0.002) and a wrong variance of R. Measured: within 0.1-0.8 SE.
// The filter at k has the least estimated error on a flat image (so it is the one selected).
TEST(SureSelection, EstimateUnbiasedOnConstantImage) {
    const Draw draw = [](int, Pcg32& rng) { return exponential(rng); };
    const EstimateBias b = estimate_bias(
        400, 16, draw, [](int) { return 1.0; }, 8, 16);
    for (size_t i = 0; i < b.sure.size(); ++i) {
        std::printf(
            "candidate %zu: estimate %.5f, estimate - truth %.6f +- %.6f; without the "
            "divergence %.6f +- %.6f\n",
            i, b.mean_estimate[i], b.sure[i].mean, b.sure[i].stderr_, b.without_divergence[i].mean,
            b.without_divergence[i].stderr_);
        EXPECT_NEAR(b.sure[i].mean, 0.0, 4.0 * b.sure[i].stderr_) << "candidate " << i;
        if (i <= 1) {  // the raw mean and the plain filter (stronger ones have W >> 1)
            EXPECT_GT(std::abs(b.without_divergence[i].mean), 4.0 * b.without_divergence[i].stderr_)
                << "the planted missing divergence went unnoticed, candidate " << i;
        }
    }
    EXPECT_LT(b.mean_estimate.back(), b.mean_estimate.front() / 4.0);
}

// Next to a step edge (1 -> 2, Gaussian sigma 1 per sample) the estimate at the column left of
// the edge: printed (the header states it misses a second-order covariance there).
TEST(SureSelection, EstimateNextToAnEdge) {
    const Draw draw = [](int x, Pcg32& rng) { return (x < kCentre ? 1.0f : 2.0f) + gaussian(rng); };
    const auto mu = [](int x) { return x < kCentre ? 1.0 : 2.0; };
    const EstimateBias b = estimate_bias(400, 16, draw, mu, kCentre - 1, kCentre);
    for (size_t i = 0; i < b.sure.size(); ++i) {
        std::printf("edge, candidate %zu: estimate %.5f, estimate - truth %.6f +- %.6f\n", i,
                    b.mean_estimate[i], b.sure[i].mean, b.sure[i].stderr_);
    }
}

/// The mean bias of the selected output at the pixel left of a vertical step (1 left, 2 right)
/// with Gaussian noise of standard deviation 1 per sample, n samples a pixel.
MeanAndError selected_edge_bias(int n, int trials) {
    DenoiseSettings settings;
    settings.select = true;
    SampleMean bias;
    for (int t = 0; t < trials; ++t) {
        const HalfBuffers halves = synthetic(static_cast<uint64_t>(t), n, [](int x, Pcg32& rng) {
            return (x < kCentre ? 1.0f : 2.0f) + gaussian(rng);
        });
        const DenoisedBeauty out = denoise_beauty(halves, settings);
        double sum = 0.0;
        for (int y = 8; y < 16; ++y)
            sum += out.rgb[0][static_cast<size_t>(y) * kSize + kCentre - 1] - 1.0;
        bias.add(sum / 8.0);
    }
    return bias.result();
}

// The selected output next to the step: within the plain filter's straight-edge bound at k
// (0.61 k sqrt(2 patch + 1) standard errors of a half's mean; the stated bound of the selection
// is 4x that, the strongest candidate's) and at most ~half of it left at 4x the samples.
// Measured 0.272 +- 0.004 at 16 spp (bound 0.485), 0.044 +- 0.003 at 64 (0.243). 300 images.
TEST(SureSelection, EdgeBiasBoundedAndFalling) {
    const auto bound = [](int n) { return straight_edge_bound(DenoiseSettings{}, n); };
    const MeanAndError b16 = selected_edge_bias(16, 300);
    const MeanAndError b64 = selected_edge_bias(64, 300);
    std::printf(
        "selected edge bias: 16 spp %.4f +- %.4f (bound %.4f), 64 spp %.4f +- %.4f "
        "(bound %.4f)\n",
        b16.mean, b16.stderr_, bound(16), b64.mean, b64.stderr_, bound(64));
    EXPECT_LE(std::abs(b16.mean), bound(16) + 4.0 * b16.stderr_);
    EXPECT_LE(std::abs(b64.mean), bound(64) + 4.0 * b64.stderr_);
    EXPECT_LT(b64.mean, 0.6 * b16.mean + 4.0 * b64.stderr_) << b16.mean << " -> " << b64.mean;
}

}  // namespace
}  // namespace kasumi
