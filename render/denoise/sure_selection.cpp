#include "render/denoise/sure_selection.h"

#include <algorithm>

namespace kasumi {

namespace {

/// The candidate's output F = alpha A' + beta B' (raw mean for candidate 0), one channel.
float candidate_value(const HalfBuffers& halves, const std::vector<CrossFiltered>& filtered_a,
                      const std::vector<CrossFiltered>& filtered_b, size_t candidate, int c,
                      size_t p) {
    const HalfImage& a = halves.half(0);
    const HalfImage& b = halves.half(1);
    const float na = a.samples[p], nb = b.samples[p];
    if (!(na + nb > 0.0f))
        return 0.0f;
    if (candidate == 0)
        return (na * a.radiance[c][p] + nb * b.radiance[c][p]) / (na + nb);
    return (na * filtered_a[candidate - 1].rgb[c][p] + nb * filtered_b[candidate - 1].rgb[c][p]) /
           (na + nb);
}

/// Every candidate's output (candidate_value) as planes, computed once.
std::vector<DenoisedBeauty> candidate_outputs(const HalfBuffers& halves,
                                              const std::vector<CrossFiltered>& filtered_a,
                                              const std::vector<CrossFiltered>& filtered_b) {
    const size_t pixels = static_cast<size_t>(halves.width()) * halves.height();
    std::vector<DenoisedBeauty> outputs(filtered_a.size() + 1);
    for (size_t i = 0; i < outputs.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            outputs[i].rgb[c].resize(pixels);
            for (size_t p = 0; p < pixels; ++p)
                outputs[i].rgb[c][p] = candidate_value(halves, filtered_a, filtered_b, i, c, p);
        }
    return outputs;
}

/// estimate_candidate_mse from the candidates' outputs (candidate_outputs).
std::vector<std::vector<float>> candidate_mse(const HalfBuffers& halves,
                                              const std::vector<unsigned char>& valid,
                                              const std::vector<CrossFiltered>& filtered_a,
                                              const std::vector<CrossFiltered>& filtered_b,
                                              const std::vector<DenoisedBeauty>& outputs) {
    const size_t pixels = valid.size();
    const size_t candidates = outputs.size();
    const HalfImage& a = halves.half(0);
    const HalfImage& b = halves.half(1);
    std::vector<std::vector<float>> mse(candidates, std::vector<float>(pixels, 0.0f));
    for (size_t p = 0; p < pixels; ++p) {
        if (valid[p] == 0)
            continue;
        const double na = a.samples[p], nb = b.samples[p];
        const double alpha = na / (na + nb), beta = nb / (na + nb);
        for (size_t i = 0; i < candidates; ++i) {
            const double wa = i == 0 ? 1.0 : filtered_a[i - 1].weight_sum[p];
            const double wb = i == 0 ? 1.0 : filtered_b[i - 1].weight_sum[p];
            double e = 0.0;
            for (int c = 0; c < 3; ++c) {
                const double va = a.radiance_var[c][p], vb = b.radiance_var[c][p];
                const double raw = alpha * a.radiance[c][p] + beta * b.radiance[c][p];
                const double f = outputs[i].rgb[c][p];
                const double var_raw = alpha * alpha * va + beta * beta * vb;
                const double cov = alpha * alpha * va / wa + beta * beta * vb / wb;
                e += (f - raw) * (f - raw) - var_raw + 2.0 * cov;
            }
            mse[i][p] = static_cast<float>(e);
        }
    }
    return mse;
}

}  // namespace

const std::vector<StrengthScale>& selection_strengths() {
    // The plain filter, then twice and four times as tolerant of colour and feature differences:
    // where the filter at k leaves variance (the silhouette, where few neighbours look alike),
    // a stronger one may have the lower error (docs/denoising.md).
    static const std::vector<StrengthScale> strengths = {{1.0f, 1.0f}, {2.0f, 2.0f}, {4.0f, 4.0f}};
    return strengths;
}

std::vector<std::vector<float>> estimate_candidate_mse(
    const HalfBuffers& halves, const std::vector<unsigned char>& valid,
    const std::vector<CrossFiltered>& filtered_a, const std::vector<CrossFiltered>& filtered_b) {
    return candidate_mse(halves, valid, filtered_a, filtered_b,
                         candidate_outputs(halves, filtered_a, filtered_b));
}

DenoisedBeauty select_strength(const HalfBuffers& halves, const std::vector<unsigned char>& valid,
                               const DenoiseSettings& settings) {
    const int width = halves.width(), height = halves.height();
    const size_t pixels = valid.size();
    const std::vector<StrengthScale>& scales = selection_strengths();
    std::vector<CrossFiltered> filtered_a, filtered_b;
    cross_filter_strengths(halves.half(1), halves.half(0), valid, width, height, settings, scales,
                           filtered_a);
    cross_filter_strengths(halves.half(0), halves.half(1), valid, width, height, settings, scales,
                           filtered_b);
    const std::vector<DenoisedBeauty> outputs = candidate_outputs(halves, filtered_a, filtered_b);
    const std::vector<std::vector<float>> mse =
        candidate_mse(halves, valid, filtered_a, filtered_b, outputs);
    const size_t candidates = mse.size();
    const size_t strongest = candidates - 1;  // its output is the normaliser's mean

    // Relative error, as the studies measure it: e / (sum of F² + 3 eps) with F the strongest
    // filter's output, eps = (0.01 Y)². The least noisy F is best: the normaliser's noise
    // weights the window's pixels at random (measured on cloud.json: the plain filter's F
    // instead gives 4-6% more error, docs/denoising.md).
    double mean = 0.0;
    size_t count = 0;
    for (size_t p = 0; p < pixels; ++p) {
        if (valid[p] == 0)
            continue;
        for (int c = 0; c < 3; ++c)
            mean += outputs[0].rgb[c][p] / 3.0;
        ++count;
    }
    mean = count > 0 ? mean / static_cast<double>(count) : 0.0;
    const double eps = (0.01 * mean) * (0.01 * mean);
    std::vector<std::vector<double>> relative(candidates, std::vector<double>(pixels, 0.0));
    for (size_t p = 0; p < pixels; ++p) {
        if (valid[p] == 0)
            continue;
        double norm = 3.0 * eps;
        for (int c = 0; c < 3; ++c) {
            const double f = outputs[strongest].rgb[c][p];
            norm += f * f;
        }
        for (size_t i = 0; i < candidates; ++i)
            relative[i][p] = norm > 0.0 ? mse[i][p] / norm : 0.0;
    }

    // Window sums in a fixed order (rows, then columns): the same for any thread count.
    std::vector<unsigned char> choice(pixels, 0);
    const int r = kSelectionRadius;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const size_t p = static_cast<size_t>(y) * width + x;
            if (valid[p] == 0)
                continue;
            size_t best = 0;
            double best_sum = 0.0;
            for (size_t i = 0; i < candidates; ++i) {
                double sum = 0.0;
                for (int qy = std::max(0, y - r); qy <= std::min(height - 1, y + r); ++qy) {
                    for (int qx = std::max(0, x - r); qx <= std::min(width - 1, x + r); ++qx)
                        sum += relative[i][static_cast<size_t>(qy) * width + qx];
                }
                if (i == 0 || sum < best_sum) {
                    best = i;
                    best_sum = sum;
                }
            }
            choice[p] = static_cast<unsigned char>(best);
        }
    }

    // The output: the choices of the 3x3 pixels around p, each candidate's output at p
    // averaged (RKZ 2012 sec. 5 smooth the selection map, so no seam shows where it changes).
    DenoisedBeauty beauty;
    for (int c = 0; c < 3; ++c) {
        beauty.rgb[c].resize(pixels);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const size_t p = static_cast<size_t>(y) * width + x;
                if (valid[p] == 0) {
                    beauty.rgb[c][p] = outputs[0].rgb[c][p];
                    continue;
                }
                double sum = 0.0, n = 0.0;
                for (int qy = std::max(0, y - 1); qy <= std::min(height - 1, y + 1); ++qy) {
                    for (int qx = std::max(0, x - 1); qx <= std::min(width - 1, x + 1); ++qx) {
                        const size_t q = static_cast<size_t>(qy) * width + qx;
                        if (valid[q] == 0)
                            continue;
                        sum += outputs[choice[q]].rgb[c][p];
                        n += 1.0;
                    }
                }
                beauty.rgb[c][p] = static_cast<float>(sum / n);
            }
        }
    }
    return beauty;
}

}  // namespace kasumi
