#pragma once
/// Adaptive sampling: how many samples a pixel takes.
///
/// Pixels are sampled in rounds of kAdaptiveRound samples, every sample with the generator of
/// its (pixel, sample, frame, seed) key, so a pixel's first n samples are those of a uniform
/// render of n spp. Every pixel takes a pilot of `min_spp` samples. Two rules then decide how
/// many more it takes, up to `spp`, both aiming at a relative standard error of its mean
/// luminance Y (cd/m²) of `threshold`:
///
/// - window r >= 1 (film.noise_window, the default 2): the **neighbourhood pilot** rule. The
///   pixel's count is fixed once, after the pilot, from the pilot samples of its neighbours
///   within Chebyshev distance r in the same tile, the pixel itself left out:
///
///     n = s_W² / (threshold * max(mean_W, floor))²,  rounded up to a round, in [min_spp, spp],
///
///   mean_W the neighbours' mean of their pilot means, s_W² the mean of their unbiased pilot
///   variances. The count is a function of other pixels' pilot samples, which every pixel takes
///   whatever any rule decides, so it is independent of the pixel's own samples and the mean of
///   its first n samples is unbiased for any n: no early-stop bias at all, however heavy the
///   tail (a pixel whose pilot missed its rare bright paths is not what decides its count).
///   Neighbours in the tile only: the image depends on render.tile_size, never on the threads.
///   A pixel with no neighbour in its tile (a 1-pixel tile) takes spp.
/// - window 0: the pixel's **own** samples, tested after every round from min_spp on:
///
///     sqrt(s² / n) <= threshold * max(mean Y, floor),  s² = sum (Y_i - mean Y)² / (n - 1).
///
///   Biased: a pixel whose running mean is low *and* whose spread is small stops early. On
///   exponential samples (relative spread 1) the bias is within threshold / 40, but on a
///   heavy-tailed pixel (rare bright paths: the WDAS cloud) a pilot that missed the tail has a
///   low mean and no spread and stops: -3% of the WDAS cloud's mean luminance at threshold 0.1.
///
/// `floor` (film.noise_floor_cd_m2) makes black pixels converge on an absolute error.
/// tests/render/adaptive_sampling_test.cpp measures both rules on heavy-tailed pixels and the
/// neighbourhood rule's render against a uniform render of another seed.
#include "scene/scene.h"

#include <cstdint>
#include <vector>

namespace kasumi {

/// Samples per round: the granularity of the stopping decision.
inline constexpr int kAdaptiveRound = 8;

/// The stopping rule of one render (film.noise_threshold, noise_floor_cd_m2, min_spp,
/// noise_window, spp).
struct AdaptiveCriterion {
    double threshold = 0.0;  ///< relative standard error of the mean luminance; 0: off
    double floor_cd_m2 = 1e-3;
    int min_spp = 16;  ///< the pilot every pixel takes
    int max_spp = 16;
    int window = 2;  ///< neighbourhood radius, pixels; 0: each pixel's own samples
};

/// The criterion of a film; threshold 0 (off) when film.noise_threshold is 0.
AdaptiveCriterion adaptive_criterion(const FilmDesc& film);

/// The running luminance statistics of one pixel (double: sums of up to 2^20 squared samples).
struct PixelConvergence {
    int n = 0;            ///< samples taken
    double sum_y = 0.0;   ///< sum of the samples' luminance, cd/m²
    double sum_y2 = 0.0;  ///< sum of their squares

    void add(double y) {
        ++n;
        sum_y += y;
        sum_y2 += y * y;
    }
    double mean() const { return sum_y / n; }
    /// The unbiased sample variance, (cd/m²)²; needs n >= 2.
    double variance() const;
};

/// Window 0: true when the pixel may take another sample under its own samples (always below
/// min_spp, never at max_spp). Called after every sample; decides only at round ends (n a
/// multiple of kAdaptiveRound).
bool keeps_sampling(const PixelConvergence& pixel, const AdaptiveCriterion& criterion);

/// Window >= 1: the sample count of every pixel of a width x height tile (row-major), from the
/// pilot statistics `pilot` (every pixel with n = min_spp samples) of its neighbours within
/// criterion.window, itself left out (see above). Counts in [min_spp, max_spp], multiples of
/// kAdaptiveRound except at min_spp and max_spp.
std::vector<int> neighbourhood_sample_counts(const std::vector<PixelConvergence>& pilot, int width,
                                             int height, const AdaptiveCriterion& criterion);

}  // namespace kasumi
