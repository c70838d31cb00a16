// Adaptive sampling on heavy-tailed pixels (render/adaptive_sampling.h): pixels whose luminance
// is mostly dim with rare bright samples, like a cloud's dark side lit by rare high-order paths.
// The neighbourhood pilot rule (film.noise_window >= 1) leaves the mean unbiased; the pixel's
// own rule (window 0) stops the pixels whose pilot missed the tail and is caught.
#include "core/rng.h"
#include "render/adaptive_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace kasumi {
namespace {

// A sample: kDim, or kDim + kBright with probability kP. Mean kDim + kP kBright = 0.2, relative
// standard deviation sqrt(kP (1 - kP)) kBright / mean = 3.1; a 16-sample pilot misses the tail
// with probability (1 - kP)^16 = 0.67, and then has mean 0.1 and no spread.
constexpr double kDim = 0.1, kBright = 4.0, kP = 1.0 / 40.0;
constexpr double kTrueMean = kDim + kP * kBright;
constexpr int kTile = 16, kTiles = 48;

double heavy_tailed(Pcg32& rng) {
    return rng.next_float() < static_cast<float>(kP) ? kDim + kBright : kDim;
}

/// The mean over kTiles tiles of kTile² pixels of each pixel's sample mean, every pixel
/// sampling its own stream; its standard error from the spread of the tile means (a tile's
/// pixels are not independent under the neighbourhood rule; tiles are).
struct GridMean {
    double mean = 0.0;
    double standard_error = 0.0;
    double mean_samples = 0.0;
};
GridMean grid_mean(const AdaptiveCriterion& criterion) {
    const int pixels = kTile * kTile;
    double sum = 0.0, sum2 = 0.0, samples = 0.0;
    for (int t = 0; t < kTiles; ++t) {
        std::vector<Pcg32> rngs;
        std::vector<PixelConvergence> stats(pixels);
        for (int p = 0; p < pixels; ++p)
            rngs.emplace_back(static_cast<uint64_t>(t * pixels + p), 0x7a11);
        std::vector<int> counts(pixels, criterion.max_spp);
        if (criterion.window > 0) {
            for (int p = 0; p < pixels; ++p)
                while (stats[p].n < criterion.min_spp)
                    stats[p].add(heavy_tailed(rngs[p]));
            counts = neighbourhood_sample_counts(stats, kTile, kTile, criterion);
            for (int p = 0; p < pixels; ++p)
                while (stats[p].n < counts[p])
                    stats[p].add(heavy_tailed(rngs[p]));
        } else
            for (int p = 0; p < pixels; ++p) {
                do
                    stats[p].add(heavy_tailed(rngs[p]));
                while (keeps_sampling(stats[p], criterion));
            }
        double tile_sum = 0.0;
        for (const PixelConvergence& p : stats) {
            tile_sum += p.mean();
            samples += p.n;
        }
        const double tile_mean = tile_sum / pixels;
        sum += tile_mean;
        sum2 += tile_mean * tile_mean;
    }
    const double n = kTiles;
    const double mean = sum / n;
    return {mean, std::sqrt((sum2 / n - mean * mean) / (n - 1.0)), samples / (n * kTile * kTile)};
}

AdaptiveCriterion criterion_of(float threshold, int window) {
    FilmDesc film;
    film.spp = 1024;
    film.min_spp = 16;
    film.noise_threshold = threshold;
    film.noise_window = window;
    return adaptive_criterion(film);
}

// The neighbourhood rule's stated bound is zero bias: its mean is within 4 standard errors of
// the truth (false failure ~6e-5), and the standard error is small enough that a planted 2%
// bias would fail. It adapts: the pixels take about (relative sd / threshold)² = 244 (0.2) and
// 108 (0.3) samples, not spp. The pixel's own rule (window 0, today's rule before this one)
// fails the same check: the pilots that missed the tail stop at 16 samples and 0.1.
TEST(AdaptiveHeavyTail, NeighbourhoodRuleIsUnbiasedWhereTheOwnRuleIsNot) {
    const double relative_sd = std::sqrt(kP * (1.0 - kP)) * kBright / kTrueMean;
    for (const float threshold : {0.2f, 0.3f}) {
        for (const int window : {1, 2}) {
            const GridMean g = grid_mean(criterion_of(threshold, window));
            EXPECT_NEAR(g.mean, kTrueMean, 4.0 * g.standard_error)
                << "threshold " << threshold << " window " << window;
            EXPECT_LT(4.0 * g.standard_error, 0.02 * kTrueMean) << "no teeth for a 2% bias";
            const double expected = relative_sd * relative_sd / (threshold * threshold);
            EXPECT_GT(g.mean_samples, 0.7 * expected) << threshold << " " << window;
            EXPECT_LT(g.mean_samples, 1.5 * expected + kAdaptiveRound) << threshold;
        }
        const GridMean own = grid_mean(criterion_of(threshold, 0));
        EXPECT_GT(std::abs(own.mean - kTrueMean), 4.0 * own.standard_error + threshold / 40.0)
            << "the own-pixel rule's early stop went unnoticed at threshold " << threshold;
    }
}

// A pixel's count does not read its own pilot: changing it (a bright tail sample, or none)
// leaves its count as it was and moves its neighbours'. Counts lie in [min_spp, spp], on round
// ends; a pixel without neighbours (a 1 x 1 tile) takes spp; flat pilots take min_spp.
TEST(AdaptiveHeavyTail, CountsReadTheNeighboursOnly) {
    const AdaptiveCriterion c = criterion_of(0.2f, 1);
    std::vector<PixelConvergence> pilot(5 * 4);
    for (size_t p = 0; p < pilot.size(); ++p)
        for (int k = 0; k < 16; ++k)
            pilot[p].add(k == static_cast<int>(p % 16) ? kDim + kBright : kDim);
    const std::vector<int> before = neighbourhood_sample_counts(pilot, 5, 4, c);
    PixelConvergence& centre = pilot[1 * 5 + 2];
    centre = PixelConvergence{};
    for (int k = 0; k < 16; ++k)
        centre.add(kDim);
    const std::vector<int> after = neighbourhood_sample_counts(pilot, 5, 4, c);
    EXPECT_EQ(after[1 * 5 + 2], before[1 * 5 + 2]);
    EXPECT_NE(after[1 * 5 + 1], before[1 * 5 + 1]);  // its neighbour read the change
    EXPECT_EQ(after[3 * 5 + 4], before[3 * 5 + 4]);  // out of its window
    for (const int n : before) {
        EXPECT_GE(n, c.min_spp);
        EXPECT_LE(n, c.max_spp);
        EXPECT_TRUE(n % kAdaptiveRound == 0 || n == c.min_spp || n == c.max_spp) << n;
    }
    EXPECT_EQ(neighbourhood_sample_counts({pilot[0]}, 1, 1, c), std::vector<int>{c.max_spp});
    std::vector<PixelConvergence> flat(9);
    for (PixelConvergence& p : flat)
        for (int k = 0; k < 16; ++k)
            p.add(2.0);
    EXPECT_EQ(neighbourhood_sample_counts(flat, 3, 3, c), std::vector<int>(9, c.min_spp));
}

}  // namespace
}  // namespace kasumi
