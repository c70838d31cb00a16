#include "volume/medium_set.h"

#include "core/error.h"

#include <algorithm>

namespace kasumi {

namespace {

const HomogeneousMedium& homogeneous(const Medium& m) {
    return std::get<HomogeneousMedium>(m.model);
}

/// The part of [ray.t_min, ray.t_max] inside the medium's bounds.
std::optional<std::pair<float, float>> overlap(const HomogeneousMedium& m, const Ray& ray) {
    if (!m.bounds)
        return std::make_pair(ray.t_min, ray.t_max);
    return m.bounds->clip(ray);
}

}  // namespace

MediumSet::MediumSet(std::vector<Medium> media) : m_media(std::move(media)) {
    KASUMI_CHECK(m_media.size() <= kMaxMedia);
}

bool MediumSet::scatters() const {
    return std::any_of(m_media.begin(), m_media.end(), [](const Medium& m) {
        return max_component(homogeneous(m).sigma_s) > 0.0f;
    });
}

Rgb MediumSet::optical_depth(const Ray& ray) const {
    Rgb tau(0.0f);
    for (const Medium& medium : m_media) {
        const HomogeneousMedium& m = homogeneous(medium);
        const auto span = overlap(m, ray);
        if (!span)
            continue;
        const float length = span->second - span->first;
        // An unbounded medium along an infinite ray has infinite depth; exp(-inf) = 0 is right,
        // but 0 * inf would be NaN for a clear channel.
        const Rgb sigma_t = m.sigma_t();
        for (int c = 0; c < 3; ++c) {
            if (sigma_t[c] > 0.0f)
                tau[c] += sigma_t[c] * length;
        }
    }
    return tau;
}

void MediumSet::intervals(const Ray& ray, std::vector<MediumInterval>& out) const {
    out.clear();
    // Boundaries of all media overlaps, sorted; between consecutive ones coefficients are constant.
    float cuts[2 * kMaxMedia];
    size_t n_cuts = 0;
    for (const Medium& medium : m_media) {
        const auto span = overlap(homogeneous(medium), ray);
        if (!span)
            continue;
        cuts[n_cuts++] = span->first;
        cuts[n_cuts++] = span->second;
    }
    std::sort(cuts, cuts + n_cuts);
    for (size_t i = 0; i + 1 < n_cuts; ++i) {
        const float t0 = cuts[i], t1 = cuts[i + 1];
        if (!(t1 > t0))
            continue;
        const Vec3 mid = ray.at(0.5f * (t0 + t1));
        MediumInterval interval;
        interval.t0 = t0;
        interval.t1 = t1;
        bool inside_any = false;
        for (uint32_t k = 0; k < m_media.size(); ++k) {
            const HomogeneousMedium& m = homogeneous(m_media[k]);
            if (m.bounds && !m.bounds->contains(mid))
                continue;
            inside_any = true;
            interval.sigma_t += m.sigma_t();
            interval.sigma_s += m.sigma_s;
            if (max_component(m.sigma_s) > 0.0f)
                interval.scattering_mask |= 1u << k;
        }
        if (inside_any)
            out.push_back(interval);
    }
}

Rgb MediumSet::scattering(const MediumInterval& interval, float mu) const {
    Rgb result(0.0f);
    for (uint32_t mask = interval.scattering_mask; mask != 0; mask &= mask - 1) {
        const HomogeneousMedium& m = homogeneous(m_media[__builtin_ctz(mask)]);
        result += m.sigma_s * eval(m.phase, mu);
    }
    return result;
}

}  // namespace kasumi
