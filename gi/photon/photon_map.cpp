#include "gi/photon/photon_map.h"

#include <algorithm>

namespace kasumi {

namespace {

bool farther(const PhotonNeighbour& a, const PhotonNeighbour& b) {
    return a.distance2 < b.distance2;  // std heap functions keep the largest at the front
}

}  // namespace

PhotonMap::PhotonMap(std::vector<Photon> photons)
    : m_photons(std::move(photons)), m_axis(m_photons.size(), 0) {
    build(0, m_photons.size());
}

void PhotonMap::build(size_t lo, size_t hi) {
    while (hi - lo > 1) {
        Vec3 lower(kInfinity), upper(-kInfinity);
        for (size_t i = lo; i < hi; ++i) {
            lower = glm::min(lower, m_photons[i].position);
            upper = glm::max(upper, m_photons[i].position);
        }
        const Vec3 extent = upper - lower;
        const uint8_t axis =
            extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
        const size_t mid = lo + (hi - lo) / 2;
        std::nth_element(m_photons.begin() + static_cast<std::ptrdiff_t>(lo),
                         m_photons.begin() + static_cast<std::ptrdiff_t>(mid),
                         m_photons.begin() + static_cast<std::ptrdiff_t>(hi),
                         [axis](const Photon& a, const Photon& b) {
                             return a.position[axis] < b.position[axis];
                         });
        m_axis[mid] = axis;
        build(lo, mid);
        lo = mid + 1;  // the right subtree iteratively: recursion depth is log2(N)
    }
}

void PhotonMap::nearest(const Vec3& p, int k, float max_radius,
                        std::vector<PhotonNeighbour>& out) const {
    out.clear();
    if (k <= 0 || m_photons.empty() || !(max_radius > 0.0f))
        return;
    float radius2 = max_radius * max_radius;
    search(0, m_photons.size(), p, static_cast<size_t>(k), radius2, out);
}

void PhotonMap::search(size_t lo, size_t hi, const Vec3& p, size_t k, float& radius2,
                       std::vector<PhotonNeighbour>& out) const {
    while (hi > lo) {
        const size_t mid = lo + (hi - lo) / 2;
        const Photon& node = m_photons[mid];
        const int axis = m_axis[mid];
        const float delta = p[axis] - node.position[axis];
        // The near side first: it shrinks the radius before the far side is considered.
        const bool left_first = delta < 0.0f;
        if (left_first)
            search(lo, mid, p, k, radius2, out);
        else
            search(mid + 1, hi, p, k, radius2, out);
        const Vec3 d = node.position - p;
        const float d2 = glm::dot(d, d);
        if (d2 < radius2) {
            if (out.size() < k) {
                out.push_back({d2, static_cast<uint32_t>(mid)});
                std::push_heap(out.begin(), out.end(), farther);
            } else {
                std::pop_heap(out.begin(), out.end(), farther);
                out.back() = {d2, static_cast<uint32_t>(mid)};
                std::push_heap(out.begin(), out.end(), farther);
            }
            if (out.size() == k)
                radius2 = out.front().distance2;
        }
        if (!(delta * delta < radius2))
            return;
        if (left_first)
            lo = mid + 1;
        else
            hi = mid;
    }
}

}  // namespace kasumi
