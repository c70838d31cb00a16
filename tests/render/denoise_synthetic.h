#pragma once
// Synthetic half buffers for the denoise tests (tests/render/denoise_*_test.cpp): a kSize²
// image whose pixel (x, y) takes n samples of a known distribution, so every expectation is
// known exactly.
#include "core/rng.h"
#include "render/denoise/half_buffers.h"
#include "scene/scene.h"

#include <cmath>
#include <cstdint>
#include <functional>

namespace kasumi {
namespace denoise_test {

constexpr int kSize = 24;  // image width and height, pixels
constexpr int kCentre = kSize / 2;

/// Half buffers of a kSize² image whose pixel (x, y) takes `n` samples mean(x) + noise(rng):
/// `draw(x, rng)` returns one sample of the beauty's channels (all three equal).
inline HalfBuffers synthetic(uint64_t seed, int n, const std::function<float(int, Pcg32&)>& draw) {
    HalfBuffers halves(kSize, kSize);
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            Pcg32 rng(seed * 1000003u + static_cast<uint64_t>(y * kSize + x), 0xde5015e);
            HalfSums sums;
            for (int s = 0; s < n; ++s) {
                PixelSample sample;
                sample.radiance = Rgb(draw(x, rng));
                sample.transmittance = Rgb(0.5f);
                sums.add(s, sample);
            }
            halves.set_pixel(x, y, sums, n);
        }
    }
    return halves;
}

/// Exponential samples of mean 1 (relative standard deviation 1: a cloud pixel's skew).
inline float exponential(Pcg32& rng) {
    return static_cast<float>(-std::log(1.0 - static_cast<double>(rng.next_float())));
}

/// Standard normal samples (Box-Muller).
inline float gaussian(Pcg32& rng) {
    const double u1 = 1.0 - static_cast<double>(rng.next_float());
    const double u2 = rng.next_float();
    return static_cast<float>(std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2));
}

/// The straight-edge bias bound of the filter at settings s (render/denoise/nlm_filter.h),
/// 0.61 k sqrt(2 patch + 1) standard errors of a half's mean, for unit noise per sample and n
/// samples a pixel (n / 2 a half).
inline double straight_edge_bound(const DenoiseSettings& s, int n) {
    return 0.61 * s.k * std::sqrt(2.0 * s.patch + 1.0) / std::sqrt(n / 2.0);
}

}  // namespace denoise_test
}  // namespace kasumi
