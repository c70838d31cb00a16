#include "render/denoise/half_buffers.h"

#include <limits>

namespace kasumi {

void HalfSums::add(int sample_index, const PixelSample& sample) {
    const int h = sample_index & 1;
    for (int c = 0; c < 3; ++c) {
        const double x = sample.radiance[c];
        radiance[h][c] += x;
        radiance2[h][c] += x * x;
    }
    const double t = luminance(sample.transmittance);
    transmittance[h] += t;
    transmittance2[h] += t * t;
}

HalfBuffers::HalfBuffers(int width, int height) : m_width(width), m_height(height) {
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    for (HalfImage& half : m_half) {
        for (int c = 0; c < 3; ++c) {
            half.radiance[c].assign(pixels, 0.0f);
            half.radiance_var[c].assign(pixels, std::numeric_limits<float>::infinity());
        }
        half.feature.assign(pixels, 1.0f);
        half.feature_var.assign(pixels, std::numeric_limits<float>::infinity());
        half.samples.assign(pixels, 0.0f);
    }
}

namespace {

/// The variance of the mean of `n` samples with sum `sum` and sum of squares `sum2`:
/// s² / n, s² = (sum2 - sum² / n) / (n - 1) (clamped at 0 against rounding); infinite for n < 2.
float variance_of_mean(double sum, double sum2, int n) {
    if (n < 2)
        return std::numeric_limits<float>::infinity();
    const double nd = static_cast<double>(n);
    const double s2 = std::max(0.0, (sum2 - sum * sum / nd) / (nd - 1.0));
    return static_cast<float>(s2 / nd);
}

}  // namespace

void HalfBuffers::set_pixel(int x, int y, const HalfSums& sums, int n) {
    const size_t i = static_cast<size_t>(y) * static_cast<size_t>(m_width) + static_cast<size_t>(x);
    for (int h = 0; h < 2; ++h) {
        const int n_half = h == 0 ? (n + 1) / 2 : n / 2;
        const double inv = n_half > 0 ? 1.0 / n_half : 0.0;
        HalfImage& half = m_half[h];
        for (int c = 0; c < 3; ++c) {
            half.radiance[c][i] = static_cast<float>(sums.radiance[h][c] * inv);
            half.radiance_var[c][i] =
                variance_of_mean(sums.radiance[h][c], sums.radiance2[h][c], n_half);
        }
        half.feature[i] = static_cast<float>(sums.transmittance[h] * inv);
        half.feature_var[i] =
            variance_of_mean(sums.transmittance[h], sums.transmittance2[h], n_half);
        half.samples[i] = static_cast<float>(n_half);
    }
}

}  // namespace kasumi
