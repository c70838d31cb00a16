#pragma once
// Shared by the statistical tests: the mean of independent samples and its standard error.
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

}  // namespace kasumi
