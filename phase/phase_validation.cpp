#include "phase/phase_validation.h"

#include "core/rng.h"
#include "core/sampling.h"
#include "phase/phase_quadrature.h"

#include <algorithm>
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

/// Cell edges in cos θ: uniform steps plus geometric ones toward both poles, so forward and
/// backward peaks are split into several cells. The finest edge, 1 - |mu| = 2e-5, stays well
/// above the rounding of mu recomputed from float directions (~1e-7), which would otherwise
/// move samples across edges on the flanks of narrow peaks.
std::vector<double> cos_edges() {
    std::vector<double> edges = {-1.0, 1.0};
    for (int i = 1; i < 40; ++i)
        edges.push_back(-1.0 + 2.0 * i / 40.0);
    for (int k = 2; k <= 20; ++k) {
        const double d = 2.0 * std::pow(10.0, -0.25 * k);
        edges.push_back(-1.0 + d);
        edges.push_back(1.0 - d);
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end(),
                            [](double a, double b) { return std::abs(a - b) < 1e-12; }),
                edges.end());
    return edges;
}

}  // namespace

ChiSquareResult chi_square_test(const PhaseFunction& p, const Vec3& wo,
                                const ValidationOptions& options) {
    const std::vector<double> edges = cos_edges();
    const int n_cos = static_cast<int>(edges.size()) - 1;
    const int n_phi = 8;
    const int n_cells = n_cos * n_phi;
    std::vector<double> observed(static_cast<size_t>(n_cells), 0.0);
    const AngularFrame frame(wo);
    Pcg32 rng(options.seed, 0x9e3779b9u);
    for (int i = 0; i < options.samples; ++i) {
        const PhaseSample s = sample(p, wo, rng.next_vec2());
        if (!(s.pdf > 0.0f) || !is_finite(s.wi))
            continue;  // counts as missing mass: the cells then under-fill and the test fails
        // The scattered light propagates along -wi; θ is its angle to wo (mu = cos θ).
        const double mu = frame.cosine(s.wi);
        const double phi = frame.azimuth(s.wi);
        const int ci = std::clamp(
            static_cast<int>(std::upper_bound(edges.begin(), edges.end(), mu) - edges.begin()) - 1,
            0, n_cos - 1);
        const int pi = std::clamp(static_cast<int>(phi / (2.0 * kPiD) * n_phi), 0, n_phi - 1);
        observed[static_cast<size_t>(ci * n_phi + pi)] += 1.0;
    }
    std::vector<double> expected(static_cast<size_t>(n_cells));
    std::ostringstream table;
    table << "cos_lo,cos_hi,observed,expected\n";
    const std::vector<double> nodes = table_nodes(p);
    const auto f = [&](double mu) { return pdf_precise(p, mu); };
    for (int ci = 0; ci < n_cos; ++ci) {
        // pdf per steradian integrated over the cell: Δφ ∫ pdf dmu, Δφ = 2π / n_phi.
        const double mass = 2.0 * kPiD / n_phi *
                            integrate_mu(f, edges[static_cast<size_t>(ci)],
                                         edges[static_cast<size_t>(ci) + 1], 1e-12, 1e-9, nodes);
        double obs_row = 0.0;
        for (int pi = 0; pi < n_phi; ++pi) {
            expected[static_cast<size_t>(ci * n_phi + pi)] = mass * options.samples;
            obs_row += observed[static_cast<size_t>(ci * n_phi + pi)];
        }
        table << edges[static_cast<size_t>(ci)] << ',' << edges[static_cast<size_t>(ci) + 1] << ','
              << obs_row << ',' << mass * n_phi * options.samples << '\n';
    }
    ChiSquareResult result =
        chi_square_statistic(observed, expected, options.significance, options.n_tests);
    result.table = table.str();
    return result;
}

ChiSquareResult chi_square_statistic(const std::vector<double>& observed,
                                     const std::vector<double>& expected, double significance,
                                     int n_tests) {
    ChiSquareResult result;
    double pooled_obs = 0.0, pooled_exp = 0.0;
    for (size_t c = 0; c < observed.size(); ++c) {
        const double e = expected[c], o = observed[c];
        if (e < 5.0) {
            pooled_obs += o;
            pooled_exp += e;
            ++result.pooled_cells;
            continue;
        }
        result.statistic += (o - e) * (o - e) / e;
        ++result.cells;
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
    // Šidák: n independent tests each at 1 - (1 - α)^{1/n} fail together with probability α.
    result.threshold = 1.0 - std::pow(1.0 - significance, 1.0 / std::max(1, n_tests));
    result.passed = result.p_value > result.threshold;
    return result;
}

std::vector<PhaseCheck> validate_phase(const PhaseFunction& p, const ValidationOptions& options) {
    std::vector<PhaseCheck> checks;
    {
        PhaseCheck c{"normalisation",
                     false,
                     integrate_phase(p, one),
                     1.0,
                     options.normalisation_tolerance,
                     "2π ∫ p(mu) dmu, adaptive Simpson"};
        c.passed = std::abs(c.value - c.expected) <= c.tolerance;
        checks.push_back(c);
    }
    {
        const double measured = integrate_phase(p, identity);
        const std::optional<double> closed = closed_form_mean_cosine(p);
        PhaseCheck c{
            "mean_cosine",
            false,
            measured,
            closed ? *closed : mean_cosine(p),
            options.normalisation_tolerance,
            closed ? "quadrature vs closed form" : "quadrature vs the table's exact value"};
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
                     1e-6,          "max relative |p(wo,wi) - p(wi,wo)| over 10^4 random pairs"};
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
                         " disagreeing by > 2 % of " + std::to_string(n)};
        checks.push_back(c);
    }
    {
        const ChiSquareResult chi =
            chi_square_test(p, glm::normalize(Vec3(0.2f, 0.7f, -0.4f)), options);
        PhaseCheck c{"chi_square",
                     chi.passed,
                     chi.p_value,
                     1.0,
                     chi.threshold,
                     "chi2 = " + std::to_string(chi.statistic) + ", dof = " +
                         std::to_string(chi.dof) + ", " + std::to_string(chi.pooled_cells) +
                         " cells pooled; passes when p-value > " + std::to_string(chi.threshold)};
        checks.push_back(c);
    }
    return checks;
}

}  // namespace kasumi
