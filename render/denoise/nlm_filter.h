#pragma once
/// film.denoise "nlm": a consistent non-local-means filter of the beauty, cross-filtered between
/// two half buffers (Rousselle, Knaus & Zwicker 2012, "Adaptive rendering with non-local means
/// filtering", sec. 4-5; the feature weight of Rousselle, Manzi & Zwicker 2013, "Robust
/// denoising using feature and color information", sec. 4).
///
/// Each half A (even samples) is filtered with weights computed on the other half B, and B with
/// weights from A; the output is their sample-count-weighted mean. For pixel p and a neighbour q
/// within `radius` pixels, per channel c with half means u and variances of the mean V,
///
///   D_c(p, q) = [(u_p - u_q)² - (V_p + min(V_p, V_q))] / (eps + k² (V_p + V_q))   (RKZ eq. 6)
///
/// averaged over the channels and over the (2 patch + 1)² patch around p (pairs inside the
/// image), then w_colour = exp(-max(0, d²)). The transmittance feature f (luminance of T, with
/// its variance W) gives w_feature = exp(-max(0, [(f_p - f_q)² - (W_p + min(W_p, W_q))] /
/// (k_f² max(tau, W_p + W_q)))); w = min(w_colour, w_feature), w(p, p) = 1. Defaults (radius 3,
/// patch 3, k 0.85, k_f 0.6) were chosen by a study on cloud.json (docs/denoising.md).
///
/// Bias bound (why it is consistent). The weights of A's filter are functions of B alone, and
/// B is independent of A (disjoint samples), so E[A'_p] = sum_q omega_q mu_q with
/// omega_q = E[w_q / sum w] >= 0, sum omega = 1: the bias is a convex combination of the
/// neighbours' true differences mu_q - mu_p, never a product of correlated noise. Subtracting
/// the variances makes E[D] = Delta² / (2 k² V) for a pixel pair whose means differ by Delta
/// (V the variance of a half's mean, sigma = sqrt V). A neighbour whose patch differs from p's
/// in m of its P = (2 patch + 1)² pixels gets weight ~exp(-m Delta² / (2 P k² V)), so its
/// term Delta w is at most e^(-1/2) k sigma P / sqrt(m):
///   |bias_p| <~ 0.61 k sqrt(2 patch + 1) sigma   next to a straight edge (m = 2 patch + 1),
///   |bias_p| <~ 0.61 k (2 patch + 1) sigma       for an isolated pixel (m = 1),
/// up to the noise of d² itself (Jensen: noisy distances raise weights a little). sigma falls as
/// 1/sqrt(spp), so the bias does too: 4x the samples halve the bound (tests/render/
/// denoise_filter_test.cpp measures 0.21 sigma at a step of 2.8 sigma, and ~0 at 64 spp).
/// Bright, noisy pixels accept darker neighbours more readily than dark, quiet pixels accept
/// bright ones, so the image's mean luminance drifts down by a fraction of sigma: measured on
/// cloud.json in docs/denoising.md.
///
/// Deterministic: every output pixel sums its neighbours in a fixed order (offsets row by row),
/// whatever the thread count. A pixel whose halves hold fewer than 2 samples or any non-finite
/// value is neither filtered nor borrowed from.
#include "render/denoise/half_buffers.h"
#include "scene/scene.h"

#include <vector>

namespace kasumi {

/// The three planes (R, G, B) of a denoised beauty, cd/m², width * height each, top row first.
struct DenoisedBeauty {
    std::vector<float> rgb[3];
};

/// One half cross-filtered at one strength: the filtered beauty (cd/m², 3 planes) and, per
/// pixel, the sum of its weights. The pixel's own weight is 1 and the weights depend on the
/// guide half only, so 1 / weight_sum = dA'_p / dA_p, the self-influence SURE needs
/// (render/denoise/sure_selection.h); 1 where the pixel is not valid (left as it is).
struct CrossFiltered {
    std::vector<float> rgb[3];
    std::vector<float> weight_sum;
};

/// Pixels the filter may filter and borrow from: both halves hold >= 2 samples and finite
/// means and variances (1), else 0.
std::vector<unsigned char> valid_pixels(const HalfBuffers& halves);

/// A filter strength as multiples of settings.k and settings.k_feature.
struct StrengthScale {
    float k = 1.0f;          ///< colour strength k * this, > 0
    float k_feature = 1.0f;  ///< feature strength k_feature * this, > 0
};

/// cross_filter at several strengths in one pass: the patch distances are computed once and
/// divided by scales[i].k² (exact up to the epsilon of eq. 6), the feature's by
/// scales[i].k_feature². out[i] is bit-identical to cross_filter's when scales[i] is {1, 1}.
void cross_filter_strengths(const HalfImage& guide, const HalfImage& filtered,
                            const std::vector<unsigned char>& valid, int width, int height,
                            const DenoiseSettings& settings,
                            const std::vector<StrengthScale>& scales,
                            std::vector<CrossFiltered>& out);

/// Half `filtered` filtered with weights computed on half `guide` (cd/m²; see the header),
/// into `out` (3 planes of width * height). `valid[i]` != 0 for pixels that may be filtered
/// and borrowed from. Runs on the calling thread's TBB arena; same result for any thread count.
void cross_filter(const HalfImage& guide, const HalfImage& filtered,
                  const std::vector<unsigned char>& valid, int width, int height,
                  const DenoiseSettings& settings, std::vector<float> out[3]);

/// The denoised beauty of both halves: A filtered with B's weights and B with A's, averaged
/// with their sample counts as weights (cd/m²). Pixels without two valid halves keep their
/// sample mean. With settings.select, the strength is chosen per pixel by the estimated MSE
/// (render/denoise/sure_selection.h).
DenoisedBeauty denoise_beauty(const HalfBuffers& halves, const DenoiseSettings& settings);

}  // namespace kasumi
