#include "volume/debiased_exp.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace kasumi {

namespace {

constexpr double kStopAtZero = 0.9;    ///< p_z: the roulette stops at order 0
constexpr int kAlwaysTaken = 2;        ///< K: orders 1..K follow once order 0 is passed
constexpr double kContinuation = 2.0;  ///< c: past K, order k follows with min(1, c / k)

/// P(N >= k) for k = 0..kMaxSeriesOrder, computed once.
const std::array<double, kMaxSeriesOrder + 1>& survival_table() {
    static const std::array<double, kMaxSeriesOrder + 1> table = [] {
        std::array<double, kMaxSeriesOrder + 1> p{};
        p[0] = 1.0;
        for (int k = 1; k <= kMaxSeriesOrder; ++k)
            p[k] =
                k <= kAlwaysTaken ? 1.0 - kStopAtZero : p[k - 1] * std::min(1.0, kContinuation / k);
        return p;
    }();
    return table;
}

}  // namespace

double series_order_survival(int k) {
    if (k < 0)
        return 1.0;
    return k <= kMaxSeriesOrder ? survival_table()[k] : 0.0;
}

double expected_series_order() {
    // E[N] = sum_{k >= 1} P(N >= k).
    double sum = 0.0;
    for (int k = 1; k <= kMaxSeriesOrder; ++k)
        sum += survival_table()[k];
    return sum;
}

int sample_series_order(float u) {
    const auto& p = survival_table();
    int n = 0;
    while (n < kMaxSeriesOrder && p[n + 1] > u)
        ++n;
    return n;
}

DVec3 debiased_exp(const std::vector<DVec3>& tau_hat) {
    const int count = static_cast<int>(tau_hat.size());
    if (count == 0)
        return DVec3(0.0);
    const int n = count - 1;
    const auto& p = survival_table();
    // 1 / (k! P(N >= k)): the series coefficient over the probability of reaching order k.
    std::array<double, kMaxSeriesOrder + 1> coefficient{};
    double factorial = 1.0;
    for (int k = 0; k <= n; ++k) {
        factorial *= std::max(k, 1);
        coefficient[k] = 1.0 / (factorial * p[k]);
    }
    DVec3 result(0.0);
    for (int c = 0; c < 3; ++c) {
        bool finite = true;
        for (const DVec3& t : tau_hat)
            finite = finite && t[c] < HUGE_VAL;
        if (!finite)
            continue;  // exp(-inf) = 0, and the differences inf - inf would be NaN
        double sum = 0.0;
        for (int j = 0; j < count; ++j) {
            const double pivot = tau_hat[j][c];
            // Elementary symmetric means m_k of the differences x_i = pivot - tau^_i, i != j,
            // built one x at a time: after i values, m_k = e_k / C(i, k), and adding x gives
            // m_k += (k / i) (m_{k-1} x - m_k) (from e_k' = e_k + x e_{k-1}). Means stay of the
            // order of x^k where the sums e_k would grow by binomial factors.
            std::array<double, kMaxSeriesOrder + 1> m{};
            m[0] = 1.0;
            int seen = 0;
            for (int i = 0; i < count; ++i) {
                if (i == j)
                    continue;
                ++seen;
                const double x = pivot - tau_hat[i][c];
                for (int k = seen; k >= 1; --k)
                    m[k] += (static_cast<double>(k) / seen) * (m[k - 1] * x - m[k]);
            }
            double series = 0.0;
            for (int k = 0; k <= n; ++k)
                series += m[k] * coefficient[k];
            // exp(-pivot) underflows to 0 for pivot > ~745: skip the term rather than risk
            // 0 * inf should a (vanishingly rare) high order overflow the series.
            const double weight = std::exp(-pivot);
            if (weight > 0.0)
                sum += weight * series;
        }
        result[c] = sum / count;
    }
    return result;
}

double SeriesRoulette::survival(int k) const {
    if (k <= 0)
        return 1.0;
    if (k > kMaxSeriesOrder)
        return 0.0;
    double p = first;
    for (int j = 2; j <= k; ++j)
        p *= std::min(1.0, continuation / j);
    return p;
}

int SeriesRoulette::sample(float u) const {
    // P(N >= k) falls with k: walk up while the next order's survival exceeds u.
    int n = 0;
    double p = first;
    while (n < kMaxSeriesOrder && p > u) {
        ++n;
        p *= std::min(1.0, continuation / (n + 1));
    }
    return n;
}

DVec3 debiased_exp_about(const DVec3& pivot, const DVec3* tau_hat, int count,
                         const SeriesRoulette& roulette) {
    const int n = std::min(std::max(count, 0), kMaxSeriesOrder);
    DVec3 result(0.0);
    for (int c = 0; c < 3; ++c) {
        bool finite = pivot[c] < HUGE_VAL;
        for (int i = 0; i < n; ++i)
            finite = finite && tau_hat[i][c] < HUGE_VAL;
        const double weight = std::exp(-pivot[c]);
        if (!finite || !(weight > 0.0))
            continue;
        // Elementary symmetric means, built one difference at a time (as in debiased_exp).
        // Only orders 0..n are read: clear those (zeroing all 65 cost 5% of a render).
        std::array<double, kMaxSeriesOrder + 1> m;
        std::fill(m.begin(), m.begin() + n + 1, 0.0);
        m[0] = 1.0;
        for (int i = 0; i < n; ++i) {
            const double x = pivot[c] - tau_hat[i][c];
            for (int k = i + 1; k >= 1; --k)
                m[k] += (static_cast<double>(k) / (i + 1)) * (m[k - 1] * x - m[k]);
        }
        double series = 0.0, factorial = 1.0;
        for (int k = 0; k <= n; ++k) {
            factorial *= std::max(k, 1);
            series += m[k] / (factorial * roulette.survival(k));
        }
        result[c] = weight * series;
    }
    return result;
}

}  // namespace kasumi
