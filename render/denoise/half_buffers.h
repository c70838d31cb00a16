#pragma once
/// The two half buffers of a render for film.denoise: the mean of each pixel's even-indexed
/// samples (half 0) and of its odd-indexed samples (half 1), with the variance of each mean,
/// for the beauty and for the transmittance feature (Rousselle, Knaus & Zwicker 2012, sec. 4:
/// two independent estimates of every pixel, so that one can weight the filter of the other).
///
/// Sample i of a pixel goes to half i mod 2, whatever the thread or tile order: the halves of
/// an n-sample pixel are independent means of ceil(n/2) and floor(n/2) samples. A sample that
/// is not finite counts as zero (as in the film), so the halves' weighted mean is the film's.
#include "core/film.h"

#include <cstddef>
#include <vector>

namespace kasumi {

/// The running sums of one pixel's samples, per half (double: sums of squares of up to 2^19
/// samples whose luminance spans many decades).
struct HalfSums {
    double radiance[2][3] = {};     ///< sum of the beauty, cd/m², per half and channel
    double radiance2[2][3] = {};    ///< sum of its squares
    double transmittance[2] = {};   ///< sum of the luminance of T (dimensionless)
    double transmittance2[2] = {};  ///< sum of its squares

    /// Adds the finite sample with index `sample_index` (its half is sample_index mod 2).
    void add(int sample_index, const PixelSample& sample);
};

/// One half of the film: per pixel, the mean and the variance of that mean (s² / n with s² the
/// unbiased sample variance), planes of width * height floats, top row first.
struct HalfImage {
    std::vector<float> radiance[3];      ///< mean beauty, cd/m²
    std::vector<float> radiance_var[3];  ///< variance of that mean, (cd/m²)²
    std::vector<float> feature;          ///< mean luminance of the transmittance T
    std::vector<float> feature_var;      ///< variance of that mean
    std::vector<float> samples;          ///< samples in the half
};

/// Both halves of a film, filled pixel by pixel by the renderer.
class HalfBuffers {
  public:
    HalfBuffers() = default;
    HalfBuffers(int width, int height);

    int width() const { return m_width; }
    int height() const { return m_height; }
    const HalfImage& half(int h) const { return m_half[h]; }

    /// Stores pixel (x, y) from the sums of its `n` samples (samples 0..n-1, the non-finite
    /// ones included in n as zeros). A half of fewer than 2 samples gets an infinite variance:
    /// the filter then leaves the pixel as it is and never borrows from it.
    void set_pixel(int x, int y, const HalfSums& sums, int n);

  private:
    int m_width = 0, m_height = 0;
    HalfImage m_half[2];
};

}  // namespace kasumi
