#include "volume/guiding/directional_histogram.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

int DirectionalHistogram::bin_of(const Vec3& w) {
    const float z = std::clamp(w.z, -1.0f, 1.0f);
    const int band = std::min(kZBands - 1, static_cast<int>((z + 1.0f) * 0.5f * kZBands));
    float phi = std::atan2(w.y, w.x);
    if (phi < 0.0f)
        phi += kTwoPi;
    const int sector = std::min(kPhiBins - 1, static_cast<int>(phi * (kPhiBins / kTwoPi)));
    return band * kPhiBins + sector;
}

Vec3 DirectionalHistogram::in_bin(int bin, Vec2 u) {
    const int band = bin / kPhiBins, sector = bin % kPhiBins;
    const float z =
        std::clamp(-1.0f + 2.0f * (static_cast<float>(band) + u.x) / kZBands, -1.0f, 1.0f);
    const float phi = kTwoPi * (static_cast<float>(sector) + u.y) / kPhiBins;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

void DirectionalHistogram::add(const Vec3& w, double weight) {
    if (!(weight > 0.0) || !std::isfinite(weight))
        return;
    m_weight[static_cast<size_t>(bin_of(w))] += weight;
}

bool DirectionalHistogram::normalise(float uniform) {
    double total = 0.0;
    for (double w : m_weight)
        total += w;
    if (!(total > 0.0) || !std::isfinite(total))
        return false;
    float running = 0.0f;
    for (int i = 0; i < kBins; ++i) {
        m_mass[i] = static_cast<float>((1.0 - uniform) * m_weight[i] / total +
                                       static_cast<double>(uniform) / kBins);
        running += m_mass[i];
        m_cdf[i] = running;
    }
    // Rounding may leave the sum a few ulps off 1: rescale so pdf() and sample() agree exactly.
    for (int i = 0; i < kBins; ++i) {
        m_mass[i] /= running;
        m_cdf[i] /= running;
    }
    m_cdf[kBins - 1] = 1.0f;
    return true;
}

float DirectionalHistogram::pdf(const Vec3& w) const {
    return m_mass[static_cast<size_t>(bin_of(w))] / kBinSolidAngle;
}

Vec3 DirectionalHistogram::sample(Vec2 u, float& pdf_sr) const {
    const int bin =
        static_cast<int>(std::upper_bound(m_cdf.begin(), m_cdf.end(), u.x) - m_cdf.begin());
    const int i = std::min(bin, kBins - 1);
    const float below = i > 0 ? m_cdf[i - 1] : 0.0f;
    // The offset of u.x inside the bin's share is itself uniform: it places z in the band.
    const float t = m_mass[i] > 0.0f ? std::clamp((u.x - below) / m_mass[i], 0.0f, 1.0f) : 0.5f;
    const Vec3 w = in_bin(i, Vec2(t, u.y));
    // The density of the bin the direction landed in (rounding at a bin edge may cross it).
    pdf_sr = pdf(w);
    return w;
}

}  // namespace kasumi
