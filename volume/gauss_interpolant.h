#pragma once
/// The polynomial through a function's values at the Gauss-Legendre nodes of an interval, and
/// its exact integral. An n-point Gauss-Legendre rule integrates polynomials of degree 2n - 1
/// exactly, so its sum over the node values IS the integral of the degree n - 1 interpolant:
/// a control variate whose integral is known exactly (in_scattering.cpp uses it for the
/// unshadowed airlight of a point light). Evaluated by the barycentric formula of the second
/// kind (Berrut & Trefethen 2004, "Barycentric Lagrange Interpolation", SIAM Review 46(3),
/// eq. 4.2), stable for these nodes.
#include "core/color.h"

#include <array>

namespace kasumi {

namespace gauss_legendre8 {
/// Nodes and weights on [-1, 1] (Abramowitz & Stegun 1964, table 25.4, n = 8).
inline constexpr std::array<double, 8> kX{-0.960289856497536231684, -0.796666477413626739592,
                                          -0.525532409916328985818, -0.183434642495649804939,
                                          0.183434642495649804939,  0.525532409916328985818,
                                          0.796666477413626739592,  0.960289856497536231684};
inline constexpr std::array<double, 8> kW{0.101228536290376259153, 0.222381034453374470544,
                                          0.313706645877887287338, 0.362683783378361982965,
                                          0.362683783378361982965, 0.313706645877887287338,
                                          0.222381034453374470544, 0.101228536290376259153};
/// Barycentric weights 1 / prod_{m != k} (x_k - x_m).
constexpr std::array<double, 8> barycentric_weights() {
    std::array<double, 8> lambda{};
    for (int k = 0; k < 8; ++k) {
        double p = 1.0;
        for (int m = 0; m < 8; ++m) {
            if (m != k)
                p *= kX[k] - kX[m];
        }
        lambda[k] = 1.0 / p;
    }
    return lambda;
}
inline constexpr std::array<double, 8> kLambda = barycentric_weights();

}  // namespace gauss_legendre8

class GaussLegendreInterpolant {
  public:
    static constexpr int kNodes = 8;

    /// Node k (ascending) of [a, b].
    static float node(int k, float a, float b) {
        return 0.5f * (a + b) + 0.5f * (b - a) * static_cast<float>(gauss_legendre8::kX[k]);
    }

    /// Sets the function's values at the nodes of [a, b] (a < b).
    void set(float a, float b, const std::array<Rgb, kNodes>& values) {
        a_ = a;
        b_ = b;
        values_ = values;
        integral_ = Rgb(0.0f);
        for (int k = 0; k < kNodes; ++k)
            integral_ += static_cast<float>(gauss_legendre8::kW[k]) * values[k];
        integral_ *= 0.5f * (b - a);
    }

    /// ∫ over [a, b] of the interpolant (= the Gauss-Legendre sum).
    const Rgb& integral() const { return integral_; }

    /// The interpolant at x in [a, b].
    Rgb operator()(float x) const {
        const float s = (2.0f * x - a_ - b_) / (b_ - a_);
        Rgb numerator(0.0f);
        float denominator = 0.0f;
        for (int k = 0; k < kNodes; ++k) {
            const float diff = s - static_cast<float>(gauss_legendre8::kX[k]);
            if (diff == 0.0f)
                return values_[k];
            const float c = static_cast<float>(gauss_legendre8::kLambda[k]) / diff;
            numerator += c * values_[k];
            denominator += c;
        }
        return numerator / denominator;
    }

  private:
    float a_ = 0.0f, b_ = 1.0f;
    std::array<Rgb, kNodes> values_{};
    Rgb integral_{0.0f};
};

}  // namespace kasumi
