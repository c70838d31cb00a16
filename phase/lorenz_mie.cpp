#include "phase/lorenz_mie.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

int wiscombe_n_terms(double x) {
    const double c = std::cbrt(x);
    double n;
    if (x <= 8.0)
        n = x + 4.0 * c + 1.0;
    else if (x < 4200.0)
        n = x + 4.05 * c + 2.0;
    else
        n = x + 4.0 * c + 2.0;
    return std::max(1, static_cast<int>(n));
}

namespace {

/// Logarithmic derivatives D_n(z) = ψ_n'(z) / ψ_n(z) for n = 0 .. n_max by downward
/// recurrence D_{n-1} = n/z - 1 / (D_n + n/z) (BH eq. 4.89), started at D = 0 well above
/// n_max. Upward recurrence is unstable whenever |Im z| is not small (Wiscombe 1980, §3); the
/// downward one is stable for every z, and the error of the arbitrary start shrinks by roughly
/// a factor |z| / n per step above |z|, so starting max(n_max, |z|) + 4|z|^{1/3} + 16 terms
/// up leaves it below double rounding by the time n_max is reached (Wiscombe uses a
/// continued fraction instead; BH use max(n_max, |z|) + 15).
template <typename T>
std::vector<T> log_derivatives(T z, int n_max) {
    const double az = std::abs(z);
    const int n_start = static_cast<int>(std::max<double>(n_max, az) + 4.0 * std::cbrt(az) + 16.0);
    std::vector<T> d(static_cast<size_t>(n_max) + 1);
    T dn = T(0.0);
    for (int n = n_start; n > 0; --n) {
        const T n_over_z = static_cast<double>(n) / z;
        dn = n_over_z - 1.0 / (dn + n_over_z);
        if (n - 1 <= n_max)
            d[static_cast<size_t>(n - 1)] = dn;
    }
    return d;
}

}  // namespace

LorenzMie::LorenzMie(double x, Complex m) : m_x(x), m_m(m) {
    KASUMI_CHECK(x > 0.0 && std::isfinite(x));
    KASUMI_CHECK(m.real() > 0.0 && m.imag() >= 0.0);
    const int n_max = wiscombe_n_terms(x);
    const std::vector<Complex> d = log_derivatives<Complex>(m * x, n_max);

    // Riccati-Bessel functions ψ_n = x j_n(x), χ_n = -x y_n(x), ξ_n = ψ_n - i χ_n.
    // χ_n grows with n, so its upward recurrence (BH eq. 4.89 form) is stable. ψ_n by upward
    // recurrence loses accuracy for n > x, which Wiscombe shows is harmless up to his n_max when
    // x is not small; for x < 1 every ψ_n is positive and decays like x^{n+1}, and we take
    // ψ_n = ψ_{n-1} / (D_n(x) + n/x) from the stable downward D_n(x) instead, which keeps full
    // relative precision down to the Rayleigh limit (x = 1e-3 and below).
    std::vector<double> psi(static_cast<size_t>(n_max) + 1);
    psi[0] = std::sin(x);
    if (x < 1.0) {
        const std::vector<double> dx = log_derivatives<double>(x, n_max);
        for (int n = 1; n <= n_max; ++n)
            psi[static_cast<size_t>(n)] =
                psi[static_cast<size_t>(n - 1)] / (dx[static_cast<size_t>(n)] + n / x);
    } else {
        double psi_prev = std::cos(x);  // ψ_{-1}
        for (int n = 1; n <= n_max; ++n) {
            const double next = (2.0 * n - 1.0) / x * psi[static_cast<size_t>(n - 1)] - psi_prev;
            psi_prev = psi[static_cast<size_t>(n - 1)];
            psi[static_cast<size_t>(n)] = next;
        }
    }

    m_a.resize(static_cast<size_t>(n_max));
    m_b.resize(static_cast<size_t>(n_max));
    double chi_prev = -std::sin(x), chi = std::cos(x);  // χ_{-1}, χ_0
    for (int n = 1; n <= n_max; ++n) {
        const double chi_next = (2.0 * n - 1.0) / x * chi - chi_prev;
        chi_prev = chi;
        chi = chi_next;
        const double psi_n = psi[static_cast<size_t>(n)];
        const double psi_n1 = psi[static_cast<size_t>(n - 1)];
        const Complex xi_n(psi_n, -chi), xi_n1(psi_n1, -chi_prev);
        const Complex dn = d[static_cast<size_t>(n)];
        const double n_over_x = n / x;
        // BH eq. 4.88.
        const Complex ta = dn / m + n_over_x;
        const Complex tb = m * dn + n_over_x;
        m_a[static_cast<size_t>(n - 1)] = (ta * psi_n - psi_n1) / (ta * xi_n - xi_n1);
        m_b[static_cast<size_t>(n - 1)] = (tb * psi_n - psi_n1) / (tb * xi_n - xi_n1);
    }
}

MieEfficiencies LorenzMie::efficiencies() const {
    double ext = 0.0, sca = 0.0, asym = 0.0;
    Complex back(0.0);
    const size_t n_max = m_a.size();
    for (size_t i = 0; i < n_max; ++i) {
        const double n = static_cast<double>(i + 1);
        const Complex an = m_a[i], bn = m_b[i];
        ext += (2.0 * n + 1.0) * (an.real() + bn.real());
        sca += (2.0 * n + 1.0) * (std::norm(an) + std::norm(bn));
        // BH eq. 4.86 / Wiscombe 1979 eq. 2: g Qsca in terms of adjacent coefficients.
        asym += (2.0 * n + 1.0) / (n * (n + 1.0)) * (an * std::conj(bn)).real();
        if (i + 1 < n_max)
            asym += n * (n + 2.0) / (n + 1.0) *
                    (an * std::conj(m_a[i + 1]) + bn * std::conj(m_b[i + 1])).real();
        back += (2.0 * n + 1.0) * ((i % 2 == 0) ? -1.0 : 1.0) * (an - bn);
    }
    const double x2 = m_x * m_x;
    MieEfficiencies q;
    q.qext = 2.0 / x2 * ext;
    q.qsca = 2.0 / x2 * sca;
    // For a non-absorbing sphere Qabs is zero exactly; the difference would only be rounding.
    q.qabs = m_m.imag() == 0.0 ? 0.0 : std::max(0.0, q.qext - q.qsca);
    q.qback = std::norm(back) / x2;
    q.g = q.qsca > 0.0 ? 4.0 / x2 * asym / q.qsca : 0.0;
    return q;
}

void LorenzMie::amplitudes(double mu, Complex& s1, Complex& s2) const {
    // Angular functions π_n, τ_n by upward recurrence (BH eq. 4.47), stable for all mu.
    double pi_prev = 0.0, pi_n = 1.0;
    s1 = Complex(0.0);
    s2 = Complex(0.0);
    const size_t n_max = m_a.size();
    for (size_t i = 0; i < n_max; ++i) {
        const double n = static_cast<double>(i + 1);
        const double tau_n = n * mu * pi_n - (n + 1.0) * pi_prev;
        const double c = (2.0 * n + 1.0) / (n * (n + 1.0));
        s1 += c * (m_a[i] * pi_n + m_b[i] * tau_n);
        s2 += c * (m_a[i] * tau_n + m_b[i] * pi_n);
        const double pi_next = ((2.0 * n + 1.0) * mu * pi_n - (n + 1.0) * pi_prev) / n;
        pi_prev = pi_n;
        pi_n = pi_next;
    }
}

double LorenzMie::s11(double mu) const {
    Complex s1, s2;
    amplitudes(mu, s1, s2);
    return 0.5 * (std::norm(s1) + std::norm(s2));
}

}  // namespace kasumi
