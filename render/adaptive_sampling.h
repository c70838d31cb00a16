#pragma once
/// Adaptive sampling: when a pixel has taken enough samples.
///
/// Pixels are sampled in rounds of kAdaptiveRound samples, every sample with the generator of
/// its (pixel, sample, frame, seed) key, so a pixel's first n samples are those of a uniform
/// render of n spp. After each round from `min_spp` samples on, a pixel stops when the relative
/// standard error of its mean luminance Y (cd/m²) is at most the threshold:
///
///   sqrt(s² / n) <= threshold * max(mean Y, floor),  s² = sum (Y_i - mean Y)² / (n - 1),
///
/// with `floor` (film.noise_floor_cd_m2) making black pixels converge on an absolute error.
/// The decision reads only the pixel's own samples, so the image does not depend on the thread
/// count or the tile order.
///
/// Stopping on a noisy error estimate biases the mean (an early-stop bias): a pixel whose
/// running mean is by chance high has a small *relative* error and stops early, one whose mean
/// is low goes on and regresses toward the truth. The remedy here is pbrt's and Cycles' (their
/// minimum sample count): no pixel stops before min_spp samples, when the variance estimate is
/// within ~sqrt(2 / min_spp) of its value and the mean within ~threshold of its own; decisions
/// are taken only at round ends. tests/render/adaptive_sampling_test.cpp bounds the bias left
/// against a uniform render of another seed, and fails a planted rule that stops low means.
#include "scene/scene.h"

#include <cstdint>

namespace kasumi {

/// Samples per round: the granularity of the stopping decision.
inline constexpr int kAdaptiveRound = 8;

/// The stopping rule of one render (film.noise_threshold, noise_floor_cd_m2, min_spp, spp).
struct AdaptiveCriterion {
    double threshold = 0.0;  ///< relative standard error of the mean luminance; 0: off
    double floor_cd_m2 = 1e-3;
    int min_spp = 16;
    int max_spp = 16;
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
};

/// True when the pixel may take another sample under `criterion` (always below min_spp,
/// never at max_spp). Called after every sample; decides only at round ends (n a multiple of
/// kAdaptiveRound).
bool keeps_sampling(const PixelConvergence& pixel, const AdaptiveCriterion& criterion);

}  // namespace kasumi
