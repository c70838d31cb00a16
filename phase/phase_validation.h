#pragma once
/// Property checks every phase function must pass, shared by `kasumi phase validate` and the
/// test suite: normalisation, mean cosine, reciprocity, sample/pdf/eval agreement, and a
/// chi-square goodness-of-fit test of the sampler.
#include "phase/phase_function.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kasumi {

struct PhaseCheck {
    std::string name;
    bool passed = false;
    double value = 0.0;     ///< what was measured
    double expected = 0.0;  ///< what it should be
    double tolerance = 0.0;
    std::string detail;
    /// Statistical checks only: the p-value and the per-check significance it is compared with
    /// (the check passes when p_value > alpha).
    std::optional<double> p_value;
    std::optional<double> alpha;
};

/// The decision rule. Deterministic checks (normalisation, mean cosine, reciprocity, sample /
/// pdf / eval agreement) compare with a tolerance. Statistical checks (the chi-square test, one
/// per model) compare a p-value with alpha = 1 - (1 - significance)^{1/n_tests} (Šidák), so a
/// correct sampler fails anywhere in a run of n_tests independent checks with probability
/// `significance`. The default sample count gives power >= 0.99 at alpha = 1e-4 against a 1 %
/// error in 1 - g at g = 0.9999 (HG sampled with g = 0.999899) and against a sampler missing
/// the pdf's backward tail of mass 1e-3 (tests/phase/phase_validation_test.cpp plants both).
struct ValidationOptions {
    uint64_t seed = 1;
    int samples = 4000000;       ///< samples for the chi-square and agreement checks
    double significance = 1e-4;  ///< false-failure rate of the whole run (all n_tests checks)
    int n_tests = 1;  ///< statistical checks sharing `significance`: models × kStatisticalChecks
    double normalisation_tolerance = 1e-6;  ///< for the normalisation and the mean cosine
    int theta_cells = 32;  ///< chi-square cells in θ of equal probability, before tail cells
};

/// Statistical checks validate_phase runs per model (the chi-square test).
inline constexpr int kStatisticalChecks = 1;

/// Per-check significance: 1 - (1 - significance)^{1/n_tests} (Šidák).
double per_check_alpha(const ValidationOptions& options);

/// One line stating the decision rule, for reports: run false-failure rate, the number of
/// statistical checks and the per-check alpha.
std::string decision_rule(const ValidationOptions& options);

/// Closed-form mean cosine where one exists (not for tabulated or Mie, whose mean cosine is
/// computed from the table itself).
std::optional<double> closed_form_mean_cosine(const PhaseFunction& p);

/// 2π ∫ w(mu) p(mu) dmu by adaptive quadrature on eval_precise(), broken at a table's nodes.
double integrate_phase(const PhaseFunction& p, double (*weight)(double));

struct ChiSquareResult {
    double statistic = 0.0;
    int dof = 0;
    double p_value = 0.0;
    double threshold = 0.0;  ///< Šidák-corrected significance the p-value is compared with
    bool passed = false;
    int cells = 0;         ///< cells after pooling
    int pooled_cells = 0;  ///< cells with expectation < 5 merged into one
    std::string table;     ///< observed vs expected per θ row, for failure reports
};

/// Draws one scattered direction about wo; a model's own sampler, or a planted faulty one.
using PhaseSampler = std::function<PhaseSample(const Vec3& wo, Vec2 u)>;

/// Scattering-angle edges (radians, ascending from 0 to π) of the chi-square rows for p:
/// options.theta_cells rows of equal probability, plus rows splitting the first and last
/// 1e-2 of the probability at 1e-3, 1e-4 and 1e-5 (where a sampler's tail errors live), edges
/// no closer than 1e-6 rad to a pole (float directions hold θ to ~1e-7 rad).
std::vector<double> chi_square_theta_edges(const PhaseFunction& p,
                                           const ValidationOptions& options);

/// Mitsuba-style test: samples binned in (θ, φ) about wo, θ on chi_square_theta_edges and 8
/// φ sectors; expected counts from the pdf integrated over each cell; cells expecting < 5
/// pooled; p-value from χ² with cells - 1 dof, compared with per_check_alpha(options).
ChiSquareResult chi_square_test(const PhaseFunction& p, const Vec3& wo,
                                const ValidationOptions& options);
/// The same test of `sampler` against the density of `reference`.
ChiSquareResult chi_square_test(const PhaseFunction& reference, const PhaseSampler& sampler,
                                const Vec3& wo, const ValidationOptions& options);

/// Probability that chi_square_test rejects `reference` when the samples follow `alternative`
/// (noncentrality N Σ (q - p)² / p over the cells; normal approximation of the noncentral χ²).
double chi_square_power(const PhaseFunction& reference, const PhaseFunction& alternative,
                        const ValidationOptions& options);

/// Runs every check.
std::vector<PhaseCheck> validate_phase(const PhaseFunction& p, const ValidationOptions& options);

}  // namespace kasumi
