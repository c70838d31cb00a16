#pragma once
/// film.denoise "select": per pixel, the strength of the cross-filtered non-local means
/// (render/denoise/nlm_filter.h) whose estimated mean squared error is least: the raw mean, or
/// the filter at (k, k_feature) times 1, 2 or 4. Where the plain filter leaves variance (at
/// the cloud's silhouette few neighbours look alike) a more tolerant one may win; where the
/// pixel is already precise or the filters' bias shows, a weaker one (Rousselle, Knaus &
/// Zwicker 2012, sec. 5, select between filters per pixel by an error estimate; Li, Wu &
/// Chuang 2012, "SURE-based optimization for adaptive sampling and reconstruction", eq. 3-5).
///
/// The estimate (SURE, Stein 1981, for a smoother linear in the data it averages). Per pixel p
/// and channel, with half means A, B (variances of the mean V_A, V_B, sample counts n_A, n_B,
/// alpha = n_A / (n_A + n_B), beta = 1 - alpha), a candidate's output F = alpha A' + beta B'
/// and the raw mean R = alpha A + beta B:
///
///   MSE(F) = E[(F - R)²] - Var(R) + 2 Cov(F, R),
///   Var(R) = alpha² V_A + beta² V_B,   Cov(F, R) = alpha² V_A / W_A + beta² V_B / W_B,
///
/// where W_A is the sum of the weights of A's filter at p (the pixel's own weight is 1, and the
/// weights are functions of B only, so dA'_p / dA_p = 1 / W_A exactly). Each term is an unbiased
/// estimate of its expectation, so the estimate e = (F - R)² - Var(R) + 2 Cov(F, R) is unbiased
/// wherever E[A' | B] does not depend on B_p (a region of constant expectation: tests/render/
/// denoise_selection_test.cpp); next to structure it misses the covariance of A's weights with
/// B_p, -2 alpha beta (Cov(A'_p, B_p) + Cov(B'_p, A_p)), second order in the weights' noise.
/// For the raw mean (W = 1) e = Var(R) exactly.
///
/// Selection: e / (F² + eps) (relative, as the studies measure; F the strongest filter's output,
/// eps = (0.01 Y)² with Y the image's mean), summed over the channels and a
/// (2 kSelectionRadius + 1)² window of valid pixels; the candidate of least sum is the pixel's
/// choice (ties to the weaker). The output averages, at p, the outputs of the candidates chosen
/// in the 3x3 pixels around p (RKZ 2012 smooth the selection map the same way). The window
/// averages the estimate's noise and keeps the choice nearly independent of the pixel's own.
///
/// Bias: that of the candidates chosen; at most the strongest's, whose straight-edge bound
/// (docs/denoising.md) is 4 times the plain filter's, 0.61 (4 k) sqrt(2 patch + 1) standard
/// errors of a half's mean, and like it falls as 1 / sqrt(spp). The estimate underestimates
/// the filters' error next to structure (the missing covariance above; measured in the test),
/// which leans the choice towards stronger filters there; the bias is measured on a step edge
/// and on cloud.json (ΔȲ/Ȳ, docs/denoising.md).
#include "render/denoise/nlm_filter.h"

#include <vector>

namespace kasumi {

/// Half-width of the window the error estimates are summed over, pixels.
constexpr int kSelectionRadius = 3;

/// The candidates' strengths as multiples of settings.k and settings.k_feature, after the raw
/// mean (candidate 0): {1, 1}, {2, 2}, {4, 4}.
const std::vector<StrengthScale>& selection_strengths();

/// Per candidate (0: the raw mean, then the filter at selection_strengths()[i - 1]) and
/// pixel, the estimate e of the output's MSE of the header, summed over the channels,
/// (cd/m²)²; 0 where the pixel is not valid. `filtered_a[i]` is half A filtered with B's
/// weights at strength i, `filtered_b[i]` the converse.
std::vector<std::vector<float>> estimate_candidate_mse(
    const HalfBuffers& halves, const std::vector<unsigned char>& valid,
    const std::vector<CrossFiltered>& filtered_a, const std::vector<CrossFiltered>& filtered_b);

/// The denoised beauty (cd/m²) with the candidate of least windowed relative error per pixel
/// (header). Pixels that are not valid keep their sample mean.
DenoisedBeauty select_strength(const HalfBuffers& halves, const std::vector<unsigned char>& valid,
                               const DenoiseSettings& settings);

}  // namespace kasumi
