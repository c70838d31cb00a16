#pragma once
// Shared by the statistical tests: the mean of independent samples and its standard error.
#include "core/rng.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace kasumi {

/// A sample mean and its standard error.
struct MeanAndError {
    double mean = 0.0, stderr_ = 0.0;
};

/// Accumulates independent samples x_1..x_n; the standard error of their mean is
/// sqrt((mean(x²) - mean(x)²) / (n - 1)), the unbiased variance estimate over n (needs n >= 2).
class SampleMean {
  public:
    void add(double x) {
        m_sum += x;
        m_sum_sq += x * x;
        ++m_n;
    }
    MeanAndError result() const {
        const double n = static_cast<double>(m_n);
        const double mean = m_sum / n;
        return {mean, std::sqrt(std::max(0.0, m_sum_sq / n - mean * mean) / (n - 1.0))};
    }

  private:
    double m_sum = 0.0, m_sum_sq = 0.0;
    int64_t m_n = 0;
};

/// The mean of n samples `sample(rng)`, sample i drawn from its own stream Pcg32(seed, i), so
/// the result does not depend on how many draws a sample takes.
template <typename Sample>
MeanAndError mean_over_streams(int n, uint64_t seed, Sample&& sample) {
    SampleMean m;
    for (int i = 0; i < n; ++i) {
        Pcg32 rng(seed, static_cast<uint64_t>(i));
        m.add(sample(rng));
    }
    return m.result();
}

}  // namespace kasumi
