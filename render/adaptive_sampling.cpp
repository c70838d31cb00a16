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
    c.window = film.noise_window;
    return c;
}

double PixelConvergence::variance() const {
    const double count = static_cast<double>(n);
    const double m = sum_y / count;
    // The two-pass form is not available (samples are not kept); in double the cancellation of
    // sum_y2 - n mean² loses at most ~1e-16 * sum_y2, far below any threshold of interest.
    return std::max(0.0, (sum_y2 - count * m * m) / (count - 1.0));
}

bool keeps_sampling(const PixelConvergence& pixel, const AdaptiveCriterion& criterion) {
    if (pixel.n >= criterion.max_spp)
        return false;
    if (!(criterion.threshold > 0.0) || pixel.n < criterion.min_spp ||
        pixel.n % kAdaptiveRound != 0)
        return true;
    const double mean = pixel.mean();
    const double standard_error = std::sqrt(pixel.variance() / pixel.n);
    return standard_error > criterion.threshold * std::max(std::abs(mean), criterion.floor_cd_m2);
}

std::vector<int> neighbourhood_sample_counts(const std::vector<PixelConvergence>& pilot, int width,
                                             int height, const AdaptiveCriterion& criterion) {
    std::vector<int> counts(pilot.size(), criterion.max_spp);
    if (criterion.min_spp >= criterion.max_spp)
        return counts;  // nothing left to decide (and a 1-sample pilot has no variance)
    // Each pilot's mean and variance once (a pixel is the neighbour of up to (2r + 1)² - 1).
    std::vector<double> means(pilot.size()), variances(pilot.size());
    for (size_t i = 0; i < pilot.size(); ++i) {
        means[i] = pilot[i].mean();
        variances[i] = pilot[i].variance();
    }
    const int r = criterion.window;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum_mean = 0.0, sum_variance = 0.0;
            int neighbours = 0;
            for (int v = std::max(0, y - r); v <= std::min(height - 1, y + r); ++v)
                for (int u = std::max(0, x - r); u <= std::min(width - 1, x + r); ++u) {
                    if (u == x && v == y)
                        continue;  // left out: the count must not read the pixel's own samples
                    const size_t q = static_cast<size_t>(v) * width + u;
                    sum_mean += means[q];
                    sum_variance += variances[q];
                    ++neighbours;
                }
            if (neighbours == 0)
                continue;  // no neighbour to judge by: spp
            const double mean = sum_mean / neighbours, variance = sum_variance / neighbours;
            const double error =
                criterion.threshold * std::max(std::abs(mean), criterion.floor_cd_m2);
            // n with sqrt(variance / n) = error; in double, capped before the conversion.
            const double needed =
                std::min(variance / (error * error), static_cast<double>(criterion.max_spp));
            int n = static_cast<int>(std::ceil(needed / kAdaptiveRound)) * kAdaptiveRound;
            n = std::clamp(n, criterion.min_spp, criterion.max_spp);
            counts[static_cast<size_t>(y) * width + x] = n;
        }
    return counts;
}

}  // namespace kasumi
