#pragma once
/// An unbiased estimate of exp(-tau) from independent unbiased estimates tau^_0..tau^_N of an
/// optical depth tau (Kettunen, d'Eon, Pantaleoni & Novák 2021, "An unbiased ray-marching
/// transmittance estimator", ACM TOG 40(4)): the power series of exp around a pivot,
///   exp(-tau) = exp(-tau_p) sum_k (tau_p - tau)^k / k!,
/// with the order truncated at a random N (Russian roulette on the order, each term k divided by
/// P(N >= k)) and (tau_p - tau)^k estimated by the mean of the products of k distinct
/// differences tau_p - tau^_i (the elementary symmetric mean, a U-statistic: unbiased because
/// the estimates are independent). Every estimate serves as the pivot in turn and the N + 1
/// results are averaged. When all estimates agree (a constant medium, a deterministic depth)
/// every correction is exactly 0 and the result is exp(-tau^): zero variance.
#include "core/math.h"

#include <vector>

namespace kasumi {

/// The roulette never continues past this order. P(N >= 64) is below 1e-80 (the continuation
/// probability is 2/k), so the truncation's bias is far below float resolution.
constexpr int kMaxSeriesOrder = 64;

/// P(N >= k) of the order roulette: Kettunen et al.'s "aggressive" Bhanot-Kennedy roulette,
/// which stops at order 0 with probability p_z = 0.9, else takes orders 1 and 2 (K = 2) and
/// continues past order k - 1 with probability min(1, c / k), c = 2. 0 past kMaxSeriesOrder.
double series_order_survival(int k);

/// E[N] of the roulette (about 0.319): an unbiased-march transmittance costs E[N] + 1 optical
/// depth estimates on average.
double expected_series_order();

/// N, drawn by inversion from u in [0, 1): the largest k with P(N >= k) > u.
int sample_series_order(float u);

/// The debiased exp(-tau) per channel from tau_hat (size N + 1, N drawn by sample_series_order):
/// its expectation is exp(-tau) when the estimates are independent, unbiased estimates of tau.
/// The estimate is signed and unbounded above (a correction can be negative or push it past 1);
/// its mean lies in [0, 1]. A channel where an estimate is +inf (an endless opaque stretch)
/// is 0. Never throws, never NaN for finite or +inf input.
DVec3 debiased_exp(const std::vector<DVec3>& tau_hat);

/// A Russian roulette on the series order for debiased_exp_about: P(N >= 1) = first, then order
/// k follows order k - 1 with probability min(1, continuation / k). {0.1, 2} is the law above.
struct SeriesRoulette {
    double first = 0.1;
    double continuation = 2.0;
    /// P(N >= k); 0 past kMaxSeriesOrder.
    double survival(int k) const;
    /// N, by inversion from u in [0, 1): the largest k with P(N >= k) > u.
    int sample(float u) const;
};

/// The debiased exp(-tau) per channel about a pivot that is not one of the estimates:
///   exp(-pivot) sum_{k=0..N} m_k / (k! P(N >= k)),
/// m_k the elementary symmetric mean of the k-fold products of the differences pivot - tau^_i
/// over the N = `count` estimates at tau_hat (N drawn by roulette.sample). Unbiased for
/// exp(-tau) when the pivot is fixed or independent of the estimates and the estimates are
/// independent and unbiased: E[m_k] = (pivot - tau)^k, and the series of exp about the pivot
/// (Kettunen et al. 2021, eq. 8) converges for any pivot, so any control (a biased march, a
/// cached depth) serves; only the variance depends on how close it is. N = 0 costs no estimate:
/// exp(-pivot). A channel whose pivot or an estimate is +inf is 0. Never NaN for finite or +inf
/// input.
DVec3 debiased_exp_about(const DVec3& pivot, const DVec3* tau_hat, int count,
                         const SeriesRoulette& roulette);

}  // namespace kasumi
