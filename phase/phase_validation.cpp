#include "phase/phase_validation.h"

#include "core/rng.h"
#include "core/sampling.h"
#include "phase/phase_quadrature.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace kasumi {

std::optional<double> closed_form_mean_cosine(const PhaseFunction& p) {
    if (std::holds_alternative<Tabulated>(p) || std::holds_alternative<Mie>(p))
        return std::nullopt;
    return mean_cosine(p);
}

namespace {

/// The nodes of a tabulated model (its kinks), empty for the smooth analytic models.
std::vector<double> table_nodes(const PhaseFunction& p) {
    if (const auto* t = std::get_if<Tabulated>(&p))
        return t->table->mu();
    if (const auto* m = std::get_if<Mie>(&p))
        return m->table->mu();
    return {};
}

}  // namespace

double integrate_phase(const PhaseFunction& p, double (*weight)(double)) {
    const auto f = [&](double mu) { return weight(mu) * eval_precise(p, mu); };
    // The double-precision path is smooth to rounding (~1e-16), so the panels can be asked for
    // 1e-12 relative; breaking at the table nodes makes Simpson exact on the piecewise-linear
    // tables (and on mu times them).
    return 2.0 * kPiD * integrate_mu(f, -1.0, 1.0, 1e-12, 1e-12, table_nodes(p));
}

namespace {

/// The scattering angle θ between wo and the propagation direction -wi, in double from float
/// directions: θ = 2 atan2(|wo + wi|, |wo - wi|) on the renormalised vectors has no cancellation
/// at the poles, where acos of a float mu cannot tell 1 - mu = 1e-9 from 0.
double scattering_angle(const Vec3& wo, const Vec3& wi) {
    const DVec3 a = glm::normalize(DVec3(wo)), b = glm::normalize(DVec3(wi));
    return 2.0 * std::atan2(glm::length(a + b), glm::length(a - b));
}

/// Local coordinates about wo in double precision: (cos θ, φ) of the propagation -wi.
struct AngularFrame {
    DVec3 tangent, bitangent;
    Vec3 wo;
    explicit AngularFrame(const Vec3& w) : wo(w) {
        const DVec3 n = glm::normalize(DVec3(w));
        const DVec3 helper = std::abs(n.x) < 0.9 ? DVec3(1.0, 0.0, 0.0) : DVec3(0.0, 1.0, 0.0);
        tangent = glm::normalize(glm::cross(helper, n));
        bitangent = glm::cross(n, tangent);
    }
    double cosine(const Vec3& wi) const { return std::cos(scattering_angle(wo, wi)); }
    double azimuth(const Vec3& wi) const {
        const DVec3 v = -DVec3(wi);
        const double phi = std::atan2(glm::dot(v, bitangent), glm::dot(v, tangent));
        return phi < 0.0 ? phi + 2.0 * kPiD : phi;
    }
};

double one(double) {
    return 1.0;
}
double identity(double mu) {
    return mu;
}

constexpr int kPhiSectors = 8;

/// Mass of p between scattering angles lo < hi (radians): 2π ∫ pdf dmu over [cos hi, cos lo].
double theta_mass(const PhaseFunction& p, const std::vector<double>& nodes, double lo, double hi) {
    const auto f = [&](double mu) { return pdf_precise(p, mu); };
    return 2.0 * kPiD * integrate_mu(f, std::cos(hi), std::cos(lo), 1e-13, 1e-10, nodes);
}

std::vector<double> row_masses(const PhaseFunction& p, const std::vector<double>& edges) {
    const std::vector<double> nodes = table_nodes(p);
    std::vector<double> mass;
    for (size_t i = 1; i < edges.size(); ++i)
        mass.push_back(theta_mass(p, nodes, edges[i - 1], edges[i]));
    return mass;
}

/// Candidate edges the rows are chosen from: 40 a decade from 1e-6 rad to 0.05 rad from each
/// pole (narrow peaks), 0.25° steps between.
std::vector<double> candidate_edges() {
    std::vector<double> edges = {0.0, kPiD};
    for (double t = 1e-6; t < 0.05; t *= std::pow(10.0, 1.0 / 40.0)) {
        edges.push_back(t);
        edges.push_back(kPiD - t);
    }
    for (int i = 1; i < 720; ++i) {
        const double t = kPiD * i / 720.0;
        if (t > 0.05 && t < kPiD - 0.05)
            edges.push_back(t);
    }
    std::sort(edges.begin(), edges.end());
    return edges;
}

/// The cells shared by the test and its power: per θ row the probability, and whether the
/// row's φ cells (expecting < 5 samples each) are pooled.
struct Cells {
    std::vector<double> mass;
    std::vector<bool> pooled;
};

Cells make_cells(std::vector<double> mass, int samples) {
    Cells c;
    for (const double m : mass)
        c.pooled.push_back(m * samples / kPhiSectors < 5.0);
    c.mass = std::move(mass);
    return c;
}

double chi_square_critical(int dof, double alpha) {
    // Q(dof/2, x/2) falls monotonically in x: bisect for Q = alpha.
    double lo = 0.0, hi = dof + 100.0 * std::sqrt(double(dof)) + 1000.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (upper_incomplete_gamma_q(0.5 * dof, 0.5 * mid) > alpha ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

double per_check_alpha(const ValidationOptions& options) {
    // Šidák: n independent tests each at 1 - (1 - α)^{1/n} fail together with probability α.
    // log1p/expm1 keep the digits: 1 - (1 - 1e-4)^{1/33} is 3.03e-6, near 1 - 1 in double.
    return -std::expm1(std::log1p(-options.significance) / std::max(1, options.n_tests));
}

std::string decision_rule(const ValidationOptions& options) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "false-failure rate %.3g for the run, Sidak over %d statistical check(s): a "
                  "check fails when its p-value <= %.3g; %d samples",
                  options.significance, std::max(1, options.n_tests), per_check_alpha(options),
                  options.samples);
    return line;
}

std::vector<double> chi_square_theta_edges(const PhaseFunction& p,
                                           const ValidationOptions& options) {
    const std::vector<double> candidates = candidate_edges();
    const std::vector<double> mass = row_masses(p, candidates);
    std::vector<double> cdf = {0.0};
    for (const double m : mass)
        cdf.push_back(cdf.back() + m);
    const double total = cdf.back();
    std::vector<double> targets;
    const int k = std::max(2, options.theta_cells);
    for (int i = 1; i < k; ++i)
        targets.push_back(double(i) / k);
    for (const double tail : {1e-5, 1e-4, 1e-3, 1e-2}) {
        targets.push_back(tail);
        targets.push_back(1.0 - tail);
    }
    std::vector<double> edges = {0.0, kPiD};
    for (const double q : targets) {
        // The first candidate whose cumulative probability reaches q (never a pole).
        const auto it = std::lower_bound(cdf.begin(), cdf.end(), q * total);
        const size_t j = std::clamp<size_t>(size_t(it - cdf.begin()), 1, candidates.size() - 2);
        edges.push_back(candidates[j]);
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

ChiSquareResult chi_square_test(const PhaseFunction& p, const Vec3& wo,
                                const ValidationOptions& options) {
    return chi_square_test(
        p, [&p](const Vec3& w, Vec2 u) { return sample(p, w, u); }, wo, options);
}

ChiSquareResult chi_square_test(const PhaseFunction& reference, const PhaseSampler& sampler,
                                const Vec3& wo, const ValidationOptions& options) {
    const std::vector<double> edges = chi_square_theta_edges(reference, options);
    const int n_theta = static_cast<int>(edges.size()) - 1;
    const int n_cells = n_theta * kPhiSectors;
    std::vector<double> observed(static_cast<size_t>(n_cells), 0.0);
    const AngularFrame frame(wo);
    Pcg32 rng(options.seed, 0x9e3779b9u);
    for (int i = 0; i < options.samples; ++i) {
        const PhaseSample s = sampler(wo, rng.next_vec2());
        if (!(s.pdf > 0.0f) || !is_finite(s.wi))
            continue;  // counts as missing mass: the cells then under-fill and the test fails
        // The scattered light propagates along -wi; θ is its angle to wo (mu = cos θ), binned
        // in θ itself: near the poles cos θ in double from a float direction loses digits.
        const double theta = scattering_angle(wo, s.wi);
        const double phi = frame.azimuth(s.wi);
        const int ti = std::clamp(
            static_cast<int>(std::upper_bound(edges.begin(), edges.end(), theta) - edges.begin()) -
                1,
            0, n_theta - 1);
        const int pi =
            std::clamp(static_cast<int>(phi / (2.0 * kPiD) * kPhiSectors), 0, kPhiSectors - 1);
        observed[static_cast<size_t>(ti * kPhiSectors + pi)] += 1.0;
    }
    const Cells cells = make_cells(row_masses(reference, edges), options.samples);
    std::ostringstream table;
    table << "theta_lo,theta_hi,observed,expected\n";
    ChiSquareResult result;
    double pooled_obs = 0.0, pooled_exp = 0.0;
    for (int ti = 0; ti < n_theta; ++ti) {
        const double e = cells.mass[size_t(ti)] * options.samples / kPhiSectors;
        double obs_row = 0.0;
        for (int pi = 0; pi < kPhiSectors; ++pi) {
            const double o = observed[static_cast<size_t>(ti * kPhiSectors + pi)];
            obs_row += o;
            if (cells.pooled[size_t(ti)]) {
                pooled_obs += o;
                pooled_exp += e;
                ++result.pooled_cells;
                continue;
            }
            result.statistic += (o - e) * (o - e) / e;
            ++result.cells;
        }
        table << edges[size_t(ti)] << ',' << edges[size_t(ti) + 1] << ',' << obs_row << ','
              << e * kPhiSectors << '\n';
    }
    if (pooled_exp >= 5.0) {
        result.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        ++result.cells;
    } else if (pooled_obs > pooled_exp + 10.0) {
        // Too few expected samples for a χ² term, yet many arrived: a sampler putting mass
        // where the pdf has (almost) none. Fail outright.
        result.statistic = INFINITY;
    }
    result.dof = std::max(1, result.cells - 1);
    result.p_value = upper_incomplete_gamma_q(0.5 * result.dof, 0.5 * result.statistic);
    result.threshold = per_check_alpha(options);
    result.passed = result.p_value > result.threshold;
    result.table = table.str();
    return result;
}

double chi_square_power(const PhaseFunction& reference, const PhaseFunction& alternative,
                        const ValidationOptions& options) {
    const std::vector<double> edges = chi_square_theta_edges(reference, options);
    const Cells cells = make_cells(row_masses(reference, edges), options.samples);
    const std::vector<double> alt = row_masses(alternative, edges);
    // Per φ cell p/8 and q/8: N Σ (q - p)² / p summed over a row's 8 cells is N (Q - P)² / P.
    double lambda = 0.0, pooled_p = 0.0, pooled_q = 0.0;
    int n_cells = 0;
    for (size_t i = 0; i < cells.mass.size(); ++i) {
        if (cells.pooled[i]) {
            pooled_p += cells.mass[i];
            pooled_q += alt[i];
            continue;
        }
        lambda +=
            options.samples * (alt[i] - cells.mass[i]) * (alt[i] - cells.mass[i]) / cells.mass[i];
        n_cells += kPhiSectors;
    }
    if (pooled_p * options.samples >= 5.0) {
        lambda += options.samples * (pooled_q - pooled_p) * (pooled_q - pooled_p) / pooled_p;
        ++n_cells;
    }
    const int dof = std::max(1, n_cells - 1);
    const double critical = chi_square_critical(dof, per_check_alpha(options));
    // Noncentral χ²(dof, λ) has mean dof + λ and variance 2 (dof + 2 λ).
    const double z = (critical - (dof + lambda)) / std::sqrt(2.0 * (dof + 2.0 * lambda));
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

std::vector<PhaseCheck> validate_phase(const PhaseFunction& p, const ValidationOptions& options) {
    std::vector<PhaseCheck> checks;
    {
        PhaseCheck c{"normalisation",
                     false,
                     integrate_phase(p, one),
                     1.0,
                     options.normalisation_tolerance,
                     "2π ∫ p(mu) dmu, adaptive Simpson",
                     std::nullopt,
                     std::nullopt};
        c.passed = std::abs(c.value - c.expected) <= c.tolerance;
        checks.push_back(c);
    }
    {
        const double measured = integrate_phase(p, identity);
        const std::optional<double> closed = closed_form_mean_cosine(p);
        PhaseCheck c{"mean_cosine",
                     false,
                     measured,
                     closed ? *closed : mean_cosine(p),
                     options.normalisation_tolerance,
                     closed ? "quadrature vs closed form" : "quadrature vs the table's exact value",
                     std::nullopt,
                     std::nullopt};
        c.passed = std::abs(c.value - c.expected) <= c.tolerance;
        checks.push_back(c);
    }
    Pcg32 rng(options.seed, 17u);
    {
        // p(wo, wi) must equal p(wi, wo) (and be unchanged when both directions flip).
        double worst = 0.0;
        for (int i = 0; i < 10000; ++i) {
            const Vec3 a = sample_uniform_sphere(rng.next_vec2());
            const Vec3 b = sample_uniform_sphere(rng.next_vec2());
            const double ab = eval(p, a, b), ba = eval(p, b, a), flipped = eval(p, -b, -a);
            const double scale = std::max(1e-30, std::abs(ab));
            worst = std::max({worst, std::abs(ab - ba) / scale, std::abs(ab - flipped) / scale});
        }
        PhaseCheck c{"reciprocity", worst <= 1e-6,
                     worst,         0.0,
                     1e-6,          "max relative |p(wo,wi) - p(wi,wo)| over 10^4 random pairs",
                     std::nullopt,  std::nullopt};
        checks.push_back(c);
    }
    {
        // Sampled value and pdf agree with each other exactly, and with the density at the
        // angle recomputed (in double) from the returned float direction, whose components
        // round by ~1e-7: the density anywhere within 2e-7 rad of that angle is acceptable,
        // plus 2 %, and at most 0.1 % of the samples may disagree. Float eval and pdf agree.
        const Vec3 wo = glm::normalize(Vec3(0.3f, -0.5f, 0.81f));
        const int n = std::min(options.samples, 200000);
        int bad = 0, invalid = 0;
        for (int i = 0; i < n; ++i) {
            const PhaseSample s = sample(p, wo, rng.next_vec2());
            if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf) || !is_finite(s.wi) ||
                std::abs(glm::length(s.wi) - 1.0f) > 1e-4f || s.value != s.pdf) {
                ++invalid;
                continue;
            }
            const double theta = scattering_angle(wo, s.wi);
            double lo = pdf_precise(p, std::cos(theta)), hi = lo;
            for (const double d : {-2e-7, 2e-7}) {
                const double v = pdf_precise(p, std::cos(std::clamp(theta + d, 0.0, kPiD)));
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
            const float mu = scattering_cosine(wo, s.wi);
            if (s.pdf < 0.98 * lo || s.pdf > 1.02 * hi || eval(p, mu) != pdf(p, mu))
                ++bad;
        }
        PhaseCheck c{"sample_pdf_eval",
                     invalid == 0 && bad <= n / 1000,
                     double(bad + invalid),
                     0.0,
                     n / 1000.0,
                     std::to_string(invalid) + " invalid samples, " + std::to_string(bad) +
                         " disagreeing by > 2 % of " + std::to_string(n),
                     std::nullopt,
                     std::nullopt};
        checks.push_back(c);
    }
    {
        const ChiSquareResult chi =
            chi_square_test(p, glm::normalize(Vec3(0.2f, 0.7f, -0.4f)), options);
        char detail[200];
        std::snprintf(detail, sizeof detail,
                      "chi2 = %.6g, dof = %d, %d cells pooled; passes when p-value > %.3g",
                      chi.statistic, chi.dof, chi.pooled_cells, chi.threshold);
        PhaseCheck c{"chi_square",  chi.passed, chi.p_value, 1.0,
                     chi.threshold, detail,     chi.p_value, chi.threshold};
        checks.push_back(c);
    }
    return checks;
}

}  // namespace kasumi
