#pragma once
/// The polynomial through a function's values at the Gauss-Legendre nodes of an interval, and
/// its exact integral. An n-point Gauss-Legendre rule integrates polynomials of degree 2n - 1
/// exactly, so its sum over the node values IS the integral of the degree n - 1 interpolant:
/// a control variate whose integral is known exactly (in_scattering.cpp uses it for the
/// unshadowed airlight of a point light). Evaluated by the barycentric formula of the second
/// kind (Berrut & Trefethen 2004, "Barycentric Lagrange Interpolation", SIAM Review 46(3),
/// eq. 4.2), stable for these nodes. Its integral over a part [a, x] of the interval comes from
/// its Legendre coefficients c_k = (2k + 1) / 2 sum_j w_j f_j P_k(x_j) (exact by the rule, as
/// P_k times the interpolant has degree <= 2n - 2) and ∫_{-1}^{s} P_k = (P_{k+1}(s) -
/// P_{k-1}(s)) / (2k + 1) for k >= 1 (Abramowitz & Stegun 1964, 22.8.5 and 22.7.10).
#include "core/color.h"

#include <algorithm>
#include <array>

namespace kasumi {

/// Nodes (ascending) and weights of the n-point rule on [-1, 1] (Abramowitz & Stegun 1964,
/// table 25.4).
template <int N>
struct GaussLegendreRule;

template <>
struct GaussLegendreRule<4> {
    static constexpr std::array<double, 4> kX{-0.861136311594052575224, -0.339981043584856264803,
                                              0.339981043584856264803, 0.861136311594052575224};
    static constexpr std::array<double, 4> kW{0.347854845137453857373, 0.652145154862546142627,
                                              0.652145154862546142627, 0.347854845137453857373};
};

template <>
struct GaussLegendreRule<6> {
    static constexpr std::array<double, 6> kX{-0.932469514203152027812, -0.661209386466264513661,
                                              -0.238619186083196908631, 0.238619186083196908631,
                                              0.661209386466264513661,  0.932469514203152027812};
    static constexpr std::array<double, 6> kW{0.171324492379170345040, 0.360761573048138607570,
                                              0.467913934572691047390, 0.467913934572691047390,
                                              0.360761573048138607570, 0.171324492379170345040};
};

template <>
struct GaussLegendreRule<8> {
    static constexpr std::array<double, 8> kX{-0.960289856497536231684, -0.796666477413626739592,
                                              -0.525532409916328985818, -0.183434642495649804939,
                                              0.183434642495649804939,  0.525532409916328985818,
                                              0.796666477413626739592,  0.960289856497536231684};
    static constexpr std::array<double, 8> kW{0.101228536290376259153, 0.222381034453374470544,
                                              0.313706645877887287338, 0.362683783378361982965,
                                              0.362683783378361982965, 0.313706645877887287338,
                                              0.222381034453374470544, 0.101228536290376259153};
};

namespace gauss_legendre_detail {

/// P_0 .. P_{M-1} at x by the three-term recurrence (A&S 22.7.10).
template <int M, typename T>
constexpr std::array<T, M> legendre(T x) {
    std::array<T, M> p{};
    p[0] = T(1);
    if (M > 1)
        p[1] = x;
    for (int k = 1; k + 1 < M; ++k)
        p[k + 1] = (T(2 * k + 1) * x * p[k] - T(k) * p[k - 1]) / T(k + 1);
    return p;
}

/// Barycentric weights 1 / prod_{m != k} (x_k - x_m).
template <int N>
constexpr std::array<double, N> barycentric_weights() {
    std::array<double, N> lambda{};
    for (int k = 0; k < N; ++k) {
        double p = 1.0;
        for (int m = 0; m < N; ++m) {
            if (m != k)
                p *= GaussLegendreRule<N>::kX[k] - GaussLegendreRule<N>::kX[m];
        }
        lambda[k] = 1.0 / p;
    }
    return lambda;
}

/// M[k][j] = (2k + 1) / 2 w_j P_k(x_j): node values to Legendre coefficients.
template <int N>
constexpr std::array<std::array<double, N>, N> legendre_transform() {
    std::array<std::array<double, N>, N> m{};
    for (int j = 0; j < N; ++j) {
        const std::array<double, N> p = legendre<N>(GaussLegendreRule<N>::kX[j]);
        for (int k = 0; k < N; ++k)
            m[k][j] = 0.5 * (2 * k + 1) * GaussLegendreRule<N>::kW[j] * p[k];
    }
    return m;
}

}  // namespace gauss_legendre_detail

template <int N>
class GaussLegendreInterpolantN {
  public:
    static constexpr int kNodes = N;

    /// Node k (ascending) of [a, b].
    static float node(int k, float a, float b) {
        return 0.5f * (a + b) + 0.5f * (b - a) * static_cast<float>(GaussLegendreRule<N>::kX[k]);
    }

    /// Sets the function's values at the nodes of [a, b] (a < b).
    void set(float a, float b, const std::array<Rgb, N>& values) {
        a_ = a;
        b_ = b;
        values_ = values;
        integral_ = Rgb(0.0f);
        for (int k = 0; k < N; ++k)
            integral_ += static_cast<float>(GaussLegendreRule<N>::kW[k]) * values[k];
        integral_ *= 0.5f * (b - a);
        coefficients_ready_ = false;
    }

    /// ∫ over [a, b] of the interpolant (= the Gauss-Legendre sum).
    const Rgb& integral() const { return integral_; }

    /// ∫ over [a, x] of the interpolant, x in [a, b].
    Rgb integral_to(float x) {
        if (!coefficients_ready_)
            prepare_coefficients();
        const float s = std::clamp((2.0f * x - a_ - b_) / (b_ - a_), -1.0f, 1.0f);
        const std::array<float, N + 1> p = gauss_legendre_detail::legendre<N + 1>(s);
        Rgb sum = coefficients_[0] * (s + 1.0f);
        for (int k = 1; k < N; ++k)
            sum += coefficients_[k] * ((p[k + 1] - p[k - 1]) / static_cast<float>(2 * k + 1));
        return 0.5f * (b_ - a_) * sum;
    }

    /// The interpolant at x in [a, b].
    Rgb operator()(float x) const {
        const float s = (2.0f * x - a_ - b_) / (b_ - a_);
        Rgb numerator(0.0f);
        float denominator = 0.0f;
        for (int k = 0; k < N; ++k) {
            const float diff = s - static_cast<float>(GaussLegendreRule<N>::kX[k]);
            if (diff == 0.0f)
                return values_[k];
            const float c = static_cast<float>(kLambda[k]) / diff;
            numerator += c * values_[k];
            denominator += c;
        }
        return numerator / denominator;
    }

  private:
    static constexpr std::array<double, N> kLambda =
        gauss_legendre_detail::barycentric_weights<N>();
    static constexpr std::array<std::array<double, N>, N> kToLegendre =
        gauss_legendre_detail::legendre_transform<N>();

    void prepare_coefficients() {
        for (int k = 0; k < N; ++k) {
            coefficients_[k] = Rgb(0.0f);
            for (int j = 0; j < N; ++j)
                coefficients_[k] += static_cast<float>(kToLegendre[k][j]) * values_[j];
        }
        coefficients_ready_ = true;
    }

    float a_ = 0.0f, b_ = 1.0f;
    std::array<Rgb, N> values_{};
    Rgb integral_{0.0f};
    std::array<Rgb, N> coefficients_{};
    bool coefficients_ready_ = false;
};

using GaussLegendreInterpolant = GaussLegendreInterpolantN<8>;

}  // namespace kasumi
