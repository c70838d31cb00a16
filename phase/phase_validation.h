#pragma once
/// Property checks every phase function must pass, shared by `kasumi phase validate` and the
/// test suite: normalisation, mean cosine, reciprocity, sample/pdf/eval agreement, and a
/// chi-square goodness-of-fit test of the sampler.
#include "phase/phase_function.h"

#include <cstdint>
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
};

struct ValidationOptions {
    uint64_t seed = 1;
    int samples = 1000000;       ///< samples for the chi-square and agreement checks
    double significance = 0.01;  ///< chi-square false-failure rate (before Šidák correction)
    int n_tests = 1;             ///< chi-square tests run together (Šidák correction)
    double normalisation_tolerance = 1e-6;  ///< for the normalisation and the mean cosine
};

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
    std::string table;     ///< observed vs expected per cos θ bin, for failure reports
};

/// Mitsuba-style test: samples binned in (cos θ, φ) about wo; expected counts from the pdf
/// integrated over each cell; cells expecting < 5 pooled; p-value from χ² with cells - 1 dof.
ChiSquareResult chi_square_test(const PhaseFunction& p, const Vec3& wo,
                                const ValidationOptions& options);

/// The χ² statistic of binned samples against expected counts (the same cell order), with
/// cells expecting < 5 pooled into one (failing outright when that pool is overfull), its
/// p-value with cells − 1 degrees of freedom, and the Šidák-corrected threshold for n_tests
/// tests of overall false-failure rate `significance`. Shared by every sampler's chi-square
/// test (phase functions here, the Phong BRDF and the lights in their test suites).
ChiSquareResult chi_square_statistic(const std::vector<double>& observed,
                                     const std::vector<double>& expected, double significance,
                                     int n_tests);

/// Runs every check.
std::vector<PhaseCheck> validate_phase(const PhaseFunction& p, const ValidationOptions& options);

}  // namespace kasumi
