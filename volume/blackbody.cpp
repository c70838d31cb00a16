#include "volume/blackbody.h"

#include "core/cie_1931.h"
#include "core/spectrum.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

Rgb blackbody_rec709(double temperature_k) {
    if (!(temperature_k > 0.0))
        return Rgb(0.0f);
    // Midpoint rule on 1 nm bins over [360, 830] nm: B is smooth and the CMFs are piecewise
    // linear between their 5 nm samples.
    glm::dvec3 xyz(0.0);
    for (double lambda = 360.5; lambda < 830.0; lambda += 1.0)
        xyz += planck_radiance(lambda, temperature_k) * cie_1931_cmf(lambda);
    xyz *= kLuminousEfficacy;
    const glm::dvec3 rgb = glm::max(xyz_to_rec709(xyz), glm::dvec3(0.0));
    return Rgb(rgb);
}

BlackbodyTable::BlackbodyTable() {
    const int n = static_cast<int>(kMaxK / kStepK) + 1;
    m_log_y.resize(static_cast<size_t>(n));
    m_colour.resize(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        const Rgb b = blackbody_rec709(i * kStepK);
        const float y = luminance(b);
        // Below ~300 K the luminance underflows float: those entries stay black.
        m_log_y[static_cast<size_t>(i)] = y > 0.0f ? std::log(y) : -1e30f;
        m_colour[static_cast<size_t>(i)] = y > 0.0f ? b / y : Rgb(0.0f);
    }
    // Above kMaxK: nodes uniform in u = kMaxK / T in [0, 1]. In the visible, c2 / (lambda T) is
    // below 0.9 there and falls with u, so B(lambda, T) / T = (2 h c² / lambda⁵) / (T expm1(x))
    // tends to the Rayleigh-Jeans 2 c k / lambda⁴ as u -> 0 and is smooth in u: Y / T and the
    // colour interpolate linearly to ~1e-6. u = 0 (T -> infinity) is taken at u = 1e-7.
    m_hot_y_over_t.resize(kHotNodes);
    m_hot_colour.resize(kHotNodes);
    for (int j = 0; j < kHotNodes; ++j) {
        const double u = std::max(1e-7, static_cast<double>(j) / (kHotNodes - 1));
        const double t = kMaxK / u;
        const Rgb b = blackbody_rec709(t);
        const double y = luminance(b);
        m_hot_y_over_t[static_cast<size_t>(j)] = static_cast<float>(y / t);
        m_hot_colour[static_cast<size_t>(j)] = b / static_cast<float>(y);
    }
}

Rgb BlackbodyTable::operator()(float temperature_k) const {
    if (!(temperature_k > 0.0f))
        return Rgb(0.0f);
    const double x = temperature_k / kStepK;
    const size_t last = m_log_y.size() - 1;
    if (x >= static_cast<double>(last)) {
        // Not Stefan-Boltzmann's T⁴: that is the total over all wavelengths, whereas the visible
        // part of a very hot body grows only like T (Rayleigh-Jeans).
        const double u = kMaxK / static_cast<double>(temperature_k) * (kHotNodes - 1);
        const size_t j = std::min(static_cast<size_t>(u), static_cast<size_t>(kHotNodes - 2));
        const float f = static_cast<float>(u - static_cast<double>(j));
        const float y_over_t = m_hot_y_over_t[j] + f * (m_hot_y_over_t[j + 1] - m_hot_y_over_t[j]);
        const Rgb colour = m_hot_colour[j] + f * (m_hot_colour[j + 1] - m_hot_colour[j]);
        return (y_over_t * temperature_k) * colour;
    }
    const size_t i = static_cast<size_t>(x);
    const float f = static_cast<float>(x - static_cast<double>(i));
    if (m_log_y[i] < -1e29f || m_log_y[i + 1] < -1e29f)
        return Rgb(0.0f);
    const float y = std::exp(m_log_y[i] + f * (m_log_y[i + 1] - m_log_y[i]));
    return y * (m_colour[i] + f * (m_colour[i + 1] - m_colour[i]));
}

}  // namespace kasumi
