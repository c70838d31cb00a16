#pragma once
/// A phase function tabulated at nodes in mu and interpolated linearly in mu between them.
/// Because the interpolant is piecewise linear, its integral, mean cosine and CDF are exact, so
/// eval, pdf and sample agree to rounding and the table integrates to 1 over the sphere.
#include "phase/phase_sample.h"

#include <memory>
#include <string>
#include <vector>

namespace kasumi {

class PhaseTable {
  public:
    /// Nodes mu in [-1, 1], strictly increasing, starting at -1 and ending at 1, with
    /// non-negative values (any scale: the table normalises to 1 over the sphere). Throws an
    /// input error naming `what` when the nodes are invalid.
    PhaseTable(std::vector<double> mu, std::vector<double> value, const std::string& what);

    /// Builds from scattering angles in degrees (0 = forward), strictly increasing from 0 to 180.
    static PhaseTable from_theta_deg(const std::vector<double>& theta_deg,
                                     const std::vector<double>& value, const std::string& what);

    /// p(mu) per steradian.
    double eval(double mu) const;
    /// Exact inverse of the piecewise-quadratic CDF in mu, for u in [0, 1].
    double sample_cosine(double u) const;
    double mean_cosine() const { return m_mean_cosine; }

    const std::vector<double>& mu() const { return m_mu; }
    const std::vector<double>& value() const { return m_value; }

  private:
    std::vector<double> m_mu;
    std::vector<double> m_value;  ///< normalised: 2π ∫ p dmu = 1
    std::vector<double> m_cdf;    ///< 2π ∫_{-1}^{mu_i} p dmu
    double m_mean_cosine = 0.0;
};

/// Reads a CSV file of `theta_deg,value` rows (a header line is allowed, `#` comments skipped).
PhaseTable read_phase_table_csv(const std::string& path);

/// Samples a direction from a table: wi from the exact CDF inverse in mu, azimuth uniform.
/// value == pdf == table.eval(mu) per steradian.
PhaseSample sample_phase_table(const PhaseTable& table, const Vec3& wo, Vec2 u);

/// A phase model whose density is a shared PhaseTable; Tabulated and Mie derive from it, and
/// the functions below are their phase-function interface. Copies never copy the table.
struct TablePhase {
    std::shared_ptr<const PhaseTable> table;
};

float eval(const TablePhase& p, float mu);
/// The table's p(mu) in double precision; eval() is this value rounded to float.
double eval_precise(const TablePhase& p, double mu);
float pdf(const TablePhase& p, float mu);
PhaseSample sample(const TablePhase& p, const Vec3& wo, Vec2 u);
/// The mean cosine of the interpolant (exact for the piecewise-linear table).
float mean_cosine(const TablePhase& p);

}  // namespace kasumi
