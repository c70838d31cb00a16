#pragma once
/// Lorenz-Mie phase function of a sphere or of a size distribution of spheres, tabulated finely
/// in angle (the forward diffraction peak, of width ~1/x radians, is resolved) and sampled by
/// the table's exact inverse CDF. One wavelength per model: an RGB scene uses the phase at
/// `wavelength_nm` (default 550 nm) for all three channels (see docs/phase.md).
#include "phase/lorenz_mie.h"
#include "phase/phase_table.h"
#include "phase/size_distribution.h"

#include <memory>
#include <optional>

namespace kasumi {

/// What a Mie model was built from, and its exact optical properties.
struct MieSummary {
    Complex m{1.33, 0.0};                 ///< particle refractive index (absolute)
    double medium_index = 1.0;            ///< real refractive index of the surrounding medium
    std::optional<double> wavelength_nm;  ///< vacuum wavelength, when radii are given
    std::optional<double> radius_um;      ///< monodisperse radius, when given
    std::optional<SizeDistribution> distribution;  ///< polydisperse
    double x = 0.0;                ///< size parameter (dominant one for a distribution)
    int n_terms = 0;               ///< terms of the largest sphere's series
    int n_radii = 1;               ///< quadrature nodes over the distribution
    MieEfficiencies efficiencies;  ///< monodisperse only
    double c_ext_um2 = 0.0;        ///< mean extinction cross section per particle, µm²
    double c_sca_um2 = 0.0;        ///< mean scattering cross section per particle, µm²
    double g = 0.0;                ///< exact mean cosine of the (averaged) phase function
};

/// eval, pdf, sample and mean_cosine are TablePhase's; the table's mean cosine is within its
/// resolution of summary->g.
struct Mie : TablePhase {
    std::shared_ptr<const MieSummary> summary;
};

/// Scattering angles (radians, ascending from 0 to π) at which the phase of size parameter x is
/// tabulated: 0.125° steps everywhere plus steps of 0.04/x out to 40/x, where the diffraction
/// peak lives.
std::vector<double> mie_theta_grid(double x, int uniform_steps = 1440);

/// Work bound of a single sphere's table: nodes × series terms.
inline constexpr double kMieTableWork = 3e7;

/// Uniform steps over [0, π] of a single sphere's table: a multiple of 1440 (every 0.125° is a
/// node) with steps of at most 0.05/x (the ripple and rings of S11 resolved) while the nodes
/// cost at most kMieTableWork series terms.
int mie_uniform_steps(double x, int n_terms);

/// A single sphere of size parameter x and relative index m, tabulated on
/// mie_theta_grid(x, mie_uniform_steps(x, n_terms)).
Mie make_mie(double x, Complex m_relative);
/// A single sphere of radius r (µm) at vacuum wavelength λ (nm) in a medium of real index
/// n_medium; x = 2π r n_medium / λ and m_relative = m / n_medium.
Mie make_mie_sphere(double radius_um, double wavelength_nm, Complex m, double medium_index);
/// A distribution of spheres; n_radii = 0 picks enough radii for steps of 0.25 in x
/// (64 .. 2000). Cross sections are per particle, averaged over the number distribution.
Mie make_mie_polydisperse(const SizeDistribution& sizes, double wavelength_nm, Complex m,
                          double medium_index, int n_radii = 0);

}  // namespace kasumi
