#include "phase/mie.h"

#include "core/error.h"

#include <algorithm>

namespace kasumi {

std::vector<double> mie_theta_grid(double x, int uniform_steps) {
    std::vector<double> theta;
    for (int i = 0; i <= uniform_steps; ++i)
        theta.push_back(kPiD * i / uniform_steps);
    // The diffraction peak has its first zero near θ = 3.83 / x; 40/x covers the peak and its
    // first rings, 0.04/x resolves them (about 100 nodes per ring).
    const double peak_end = std::min(kPiD, 40.0 / x);
    const double step = 0.04 / x;
    if (step < kPiD / uniform_steps)
        for (double t = step; t < peak_end; t += step)
            theta.push_back(t);
    std::sort(theta.begin(), theta.end());
    // Nodes closer than this would map to equal or nearly equal mu = cos θ.
    std::vector<double> unique;
    for (const double t : theta)
        if (unique.empty() || t - unique.back() > 1e-7 * std::max(1.0, t) + 1e-9)
            unique.push_back(t);
    unique.back() = kPiD;
    return unique;
}

namespace {

/// Converts per-angle unpolarised intensities on a θ grid into a normalised table in mu.
std::shared_ptr<const PhaseTable> table_from_theta(const std::vector<double>& theta,
                                                   const std::vector<double>& s11) {
    const size_t n = theta.size();
    std::vector<double> mu(n), value(n);
    for (size_t i = 0; i < n; ++i) {
        mu[n - 1 - i] = std::cos(theta[i]);
        value[n - 1 - i] = s11[i];
    }
    mu.front() = -1.0;
    mu.back() = 1.0;
    return std::make_shared<const PhaseTable>(std::move(mu), std::move(value), "mie phase table");
}

void check_index(Complex m) {
    if (!(m.real() > 0.0) || !std::isfinite(m.real()))
        throw_input_error("mie: refractive index real part must be > 0");
    if (!(m.imag() >= 0.0) || !std::isfinite(m.imag()))
        throw_input_error(
            "mie: refractive index imaginary part must be >= 0 (m = n + ik, Bohren & Huffman)");
}

}  // namespace

int mie_uniform_steps(double x, int n_terms) {
    // Away from the forward peak a single sphere's S11 still oscillates on angular scales of
    // ~1/x (the diffraction rings, then the ripple of interfering rays); steps of 0.05/x keep
    // linear interpolation between nodes within a few per cent of the series except right at
    // the deep minima. Each node costs n_terms terms, so the grid is capped at kMieTableWork
    // term evaluations (~0.2 s CPU): fully resolved up to x ≈ 650, 0.125° steps above x ≈ 1e4.
    // A multiple of 1440 keeps every multiple of 0.125° a node (exact there).
    const double wanted = std::ceil(kPiD * x / 0.05 / 1440.0);
    const double affordable = std::floor(kMieTableWork / std::max(1, n_terms) / 1440.0);
    return 1440 * static_cast<int>(std::clamp(std::min(wanted, affordable), 1.0, 500.0));
}

Mie make_mie(double x, Complex m_relative) {
    if (!(x > 0.0) || !std::isfinite(x))
        throw_input_error("mie: size parameter x must be > 0");
    if (x > 1e5)
        throw_input_error("mie: size parameter x must be <= 1e5");
    check_index(m_relative);
    const LorenzMie sphere(x, m_relative);
    const std::vector<double> theta = mie_theta_grid(x, mie_uniform_steps(x, sphere.n_terms()));
    std::vector<double> s11(theta.size());
    for (size_t i = 0; i < theta.size(); ++i)
        s11[i] = sphere.s11(std::cos(theta[i]));
    auto summary = std::make_shared<MieSummary>();
    summary->m = m_relative;
    summary->x = x;
    summary->n_terms = sphere.n_terms();
    summary->efficiencies = sphere.efficiencies();
    summary->g = summary->efficiencies.g;
    return Mie{{table_from_theta(theta, s11)}, summary};
}

Mie make_mie_sphere(double radius_um, double wavelength_nm, Complex m, double medium_index) {
    if (!(radius_um > 0.0))
        throw_input_error("mie: radius_um must be > 0");
    if (!(wavelength_nm > 0.0))
        throw_input_error("mie: wavelength_nm must be > 0");
    if (!(medium_index > 0.0))
        throw_input_error("mie: medium_index must be > 0");
    check_index(m);
    const double x = 2.0 * kPiD * radius_um * medium_index / (wavelength_nm * 1e-3);
    Mie result = make_mie(x, m / medium_index);
    auto summary = std::make_shared<MieSummary>(*result.summary);
    summary->m = m;
    summary->medium_index = medium_index;
    summary->wavelength_nm = wavelength_nm;
    summary->radius_um = radius_um;
    const double area = kPiD * radius_um * radius_um;
    summary->c_ext_um2 = summary->efficiencies.qext * area;
    summary->c_sca_um2 = summary->efficiencies.qsca * area;
    result.summary = summary;
    return result;
}

Mie make_mie_polydisperse(const SizeDistribution& sizes, double wavelength_nm, Complex m,
                          double medium_index, int n_radii) {
    if (!(wavelength_nm > 0.0))
        throw_input_error("mie: wavelength_nm must be > 0");
    if (!(medium_index > 0.0))
        throw_input_error("mie: medium_index must be > 0");
    check_index(m);
    const Complex m_rel = m / medium_index;
    const double k = 2.0 * kPiD * medium_index / (wavelength_nm * 1e-3);  // 1/µm
    double r_min = 0.0, r_max = 0.0;
    scattering_radius_range(sizes, r_min, r_max);
    if (k * r_max > 1e5)
        throw_input_error("mie: the size distribution reaches x > 1e5");
    if (n_radii <= 0)
        n_radii = std::clamp(static_cast<int>(std::ceil(k * (r_max - r_min) / 0.25)), 64, 2000);
    // Trapezoid rule in ln r: n(r) dr = n(r) r d(ln r).
    const double log_min = std::log(r_min), log_step = std::log(r_max / r_min) / (n_radii - 1);
    const double x_dominant = k * dominant_radius_um(sizes);
    // Half the uniform resolution of a single sphere: the average is smoother than any member.
    const std::vector<double> theta = mie_theta_grid(x_dominant, 720);
    std::vector<double> mu(theta.size());
    for (size_t j = 0; j < theta.size(); ++j)
        mu[j] = std::cos(theta[j]);
    std::vector<double> s11(theta.size(), 0.0);
    double weight_sum = 0.0, c_ext = 0.0, c_sca = 0.0, g_c_sca = 0.0;
    int n_terms = 0;
    for (int i = 0; i < n_radii; ++i) {
        const double r = std::exp(log_min + log_step * i);
        const double w =
            number_density(sizes, r) * r * log_step * ((i == 0 || i == n_radii - 1) ? 0.5 : 1.0);
        if (!(w > 0.0))
            continue;
        const LorenzMie sphere(k * r, m_rel);
        n_terms = std::max(n_terms, sphere.n_terms());
        const MieEfficiencies q = sphere.efficiencies();
        const double area = kPiD * r * r;
        weight_sum += w;
        c_ext += w * q.qext * area;
        c_sca += w * q.qsca * area;
        g_c_sca += w * q.qsca * area * q.g;
        // Σ w C_sca p(θ) = Σ w S11 / k²: the per-sphere normalisations cancel.
        for (size_t j = 0; j < theta.size(); ++j)
            s11[j] += w * sphere.s11(mu[j]);
    }
    if (!(c_sca > 0.0))
        throw_input_error("mie: the size distribution scatters nothing");
    auto summary = std::make_shared<MieSummary>();
    summary->m = m;
    summary->medium_index = medium_index;
    summary->wavelength_nm = wavelength_nm;
    summary->distribution = sizes;
    summary->x = x_dominant;
    summary->n_terms = n_terms;
    summary->n_radii = n_radii;
    summary->c_ext_um2 = c_ext / weight_sum;
    summary->c_sca_um2 = c_sca / weight_sum;
    summary->g = g_c_sca / c_sca;
    return Mie{{table_from_theta(theta, s11)}, summary};
}

}  // namespace kasumi
