#include "render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

AdaptiveCriterion adaptive_criterion(const FilmDesc& film) {
    AdaptiveCriterion c;
    c.threshold = film.noise_threshold;
    c.floor_cd_m2 = film.noise_floor_cd_m2;
    c.max_spp = film.spp;
    c.min_spp = std::min(film.min_spp, film.spp);
    return c;
}

bool keeps_sampling(const PixelConvergence& pixel, const AdaptiveCriterion& criterion) {
    if (pixel.n >= criterion.max_spp)
        return false;
    if (!(criterion.threshold > 0.0) || pixel.n < criterion.min_spp ||
        pixel.n % kAdaptiveRound != 0)
        return true;
    const double n = static_cast<double>(pixel.n);
    const double mean = pixel.sum_y / n;
    // The two-pass form is not available (samples are not kept); in double the cancellation of
    // sum_y2 - n mean² loses at most ~1e-16 * sum_y2, far below any threshold of interest.
    const double variance = std::max(0.0, (pixel.sum_y2 - n * mean * mean) / (n - 1.0));
    const double standard_error = std::sqrt(variance / n);
    return standard_error > criterion.threshold * std::max(std::abs(mean), criterion.floor_cd_m2);
}

}  // namespace kasumi
