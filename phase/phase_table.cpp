#include "phase/phase_table.h"

#include "core/error.h"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace kasumi {

PhaseTable::PhaseTable(std::vector<double> mu, std::vector<double> value, const std::string& what)
    : m_mu(std::move(mu)), m_value(std::move(value)) {
    const size_t n = m_mu.size();
    if (n < 2 || m_value.size() != n)
        throw_input_error(what + ": a phase table needs at least two nodes with one value each");
    if (m_mu.front() != -1.0 || m_mu.back() != 1.0)
        throw_input_error(what + ": the table must cover the whole sphere (theta 0 to 180 deg)");
    for (size_t i = 0; i < n; ++i) {
        if (!std::isfinite(m_value[i]) || m_value[i] < 0.0)
            throw_input_error(what + ": value " + std::to_string(i) + " must be finite and >= 0");
        if (i > 0 && !(m_mu[i] > m_mu[i - 1]))
            throw_input_error(what + ": angles must be strictly increasing");
    }
    m_cdf.assign(n, 0.0);
    double mean = 0.0;
    for (size_t i = 1; i < n; ++i) {
        const double h = m_mu[i] - m_mu[i - 1];
        const double p0 = m_value[i - 1], p1 = m_value[i];
        m_cdf[i] = m_cdf[i - 1] + 0.5 * h * (p0 + p1);
        // ∫ mu (linear p) dmu over the segment, exact.
        mean += h * (p0 * (2.0 * m_mu[i - 1] + m_mu[i]) + p1 * (m_mu[i - 1] + 2.0 * m_mu[i])) / 6.0;
    }
    const double total = m_cdf.back();
    if (!(total > 0.0) || !std::isfinite(total))
        throw_input_error(what + ": the phase function integrates to zero");
    const double scale = 1.0 / (2.0 * kPiD * total);
    for (double& v : m_value)
        v *= scale;
    for (double& c : m_cdf)
        c /= total;
    m_cdf.back() = 1.0;
    m_mean_cosine = mean / total;
}

PhaseTable PhaseTable::from_theta_deg(const std::vector<double>& theta_deg,
                                      const std::vector<double>& value, const std::string& what) {
    if (theta_deg.size() != value.size())
        throw_input_error(what + ": angle and value counts differ");
    if (theta_deg.empty() || theta_deg.front() != 0.0 || theta_deg.back() != 180.0)
        throw_input_error(what + ": angles must run from 0 to 180 degrees");
    std::vector<double> mu(theta_deg.size()), v(value.size());
    // Reversed so mu increases; the end points are set exactly (cos(π) rounds to -1 anyway).
    for (size_t i = 0; i < theta_deg.size(); ++i) {
        const size_t j = theta_deg.size() - 1 - i;
        mu[j] = std::cos(theta_deg[i] * kPiD / 180.0);
        v[j] = value[i];
    }
    mu.front() = -1.0;
    mu.back() = 1.0;
    for (size_t i = 1; i < theta_deg.size(); ++i)
        if (!(theta_deg[i] > theta_deg[i - 1]))
            throw_input_error(what + ": angles must be strictly increasing");
    return PhaseTable(std::move(mu), std::move(v), what);
}

double PhaseTable::eval(double mu) const {
    if (!(mu >= -1.0))
        mu = -1.0;
    if (mu > 1.0)
        mu = 1.0;
    const auto it = std::upper_bound(m_mu.begin(), m_mu.end(), mu);
    const size_t i = std::clamp<size_t>(static_cast<size_t>(it - m_mu.begin()), 1, m_mu.size() - 1);
    const double t = (mu - m_mu[i - 1]) / (m_mu[i] - m_mu[i - 1]);
    return m_value[i - 1] + t * (m_value[i] - m_value[i - 1]);
}

double PhaseTable::sample_cosine(double u) const {
    u = std::clamp(u, 0.0, 1.0);
    const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), u);
    size_t i = std::clamp<size_t>(static_cast<size_t>(it - m_cdf.begin()), 1, m_cdf.size() - 1);
    // Skip zero-probability segments so the sample lands where the density is positive.
    while (i + 1 < m_cdf.size() && m_cdf[i] <= m_cdf[i - 1])
        ++i;
    const double h = m_mu[i] - m_mu[i - 1];
    const double p0 = m_value[i - 1] * 2.0 * kPiD, p1 = m_value[i] * 2.0 * kPiD;
    const double c = u - m_cdf[i - 1];
    const double slope = (p1 - p0) / h;
    // Solve p0 d + slope d²/2 = c for d in [0, h]; the form 2c / (p0 + sqrt(p0² + 2 slope c))
    // has no cancellation for either sign of the slope.
    const double disc = std::max(0.0, p0 * p0 + 2.0 * slope * c);
    const double denom = p0 + std::sqrt(disc);
    const double d = denom > 0.0 ? 2.0 * c / denom : 0.0;
    return std::clamp(m_mu[i - 1] + std::clamp(d, 0.0, h), -1.0, 1.0);
}

PhaseTable read_phase_table_csv(const std::string& path) {
    std::ifstream in(path);
    if (!in)
        throw_input_error(path + ": cannot open phase table");
    std::vector<double> theta, value;
    std::string line;
    int line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
            continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream fields(line);
        double t = 0.0, v = 0.0;
        std::string rest;
        if (!(fields >> t >> v) || (fields >> rest)) {
            if (theta.empty() && line_number == 1)
                continue;  // header
            throw_input_error(path + ":" + std::to_string(line_number) +
                              ": expected two numbers theta_deg,value");
        }
        theta.push_back(t);
        value.push_back(v);
    }
    return PhaseTable::from_theta_deg(theta, value, path);
}

PhaseSample sample_phase_table(const PhaseTable& table, const Vec3& wo, Vec2 u) {
    const double mu = table.sample_cosine(u.x);
    return phase_sample_about(wo, mu, kTwoPi * u.y, table.eval(mu));
}

double eval_precise(const TablePhase& p, double mu) {
    return p.table->eval(mu);
}

float eval(const TablePhase& p, float mu) {
    return static_cast<float>(eval_precise(p, mu));
}

float pdf(const TablePhase& p, float mu) {
    return eval(p, mu);
}

PhaseSample sample(const TablePhase& p, const Vec3& wo, Vec2 u) {
    return sample_phase_table(*p.table, wo, u);
}

float mean_cosine(const TablePhase& p) {
    return static_cast<float>(p.table->mean_cosine());
}

}  // namespace kasumi
