#include "volume/blackbody.h"

#include "core/cie_1931.h"
#include "core/spectrum.h"

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
    m_last = blackbody_rec709(kMaxK);
}

Rgb BlackbodyTable::operator()(float temperature_k) const {
    if (!(temperature_k > 0.0f))
        return Rgb(0.0f);
    const double x = temperature_k / kStepK;
    const size_t last = m_log_y.size() - 1;
    if (x >= static_cast<double>(last)) {
        const float ratio = static_cast<float>(temperature_k / kMaxK);
        return m_last * (ratio * ratio * ratio * ratio);
    }
    const size_t i = static_cast<size_t>(x);
    const float f = static_cast<float>(x - static_cast<double>(i));
    if (m_log_y[i] < -1e29f || m_log_y[i + 1] < -1e29f)
        return Rgb(0.0f);
    const float y = std::exp(m_log_y[i] + f * (m_log_y[i + 1] - m_log_y[i]));
    return y * (m_colour[i] + f * (m_colour[i + 1] - m_colour[i]));
}

}  // namespace kasumi
