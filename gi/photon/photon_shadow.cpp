#include "gi/photon/photon_shadow.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

void classify_shadow_photons(const PhotonMap& shadow_map, const Vec3& x, const Vec3& n, int k,
                             float max_radius, size_t lights, PhotonQueryScratch& scratch,
                             KnownVisibility* known) {
    std::fill(known, known + lights, KnownVisibility::Unknown);
    if (shadow_map.empty() || lights == 0)
        return;
    shadow_map.nearest(x, k, max_radius, scratch.neighbours);
    if (scratch.neighbours.empty())
        return;
    float r2 = 0.0f;
    for (const PhotonNeighbour& nb : scratch.neighbours)
        r2 = std::max(r2, nb.distance2);
    const float thickness = kShadowDiscThickness * std::sqrt(r2);
    thread_local std::vector<uint32_t> direct, shadow;
    direct.assign(lights, 0);
    shadow.assign(lights, 0);
    for (const PhotonNeighbour& nb : scratch.neighbours) {
        const Photon& p = shadow_map[nb.index];
        if (p.light >= lights || !(glm::dot(n, p.wi) > 0.0f) ||
            std::abs(glm::dot(n, p.position - x)) > thickness)
            continue;
        ++(p.shadow ? shadow : direct)[p.light];
    }
    const uint32_t min_photons = static_cast<uint32_t>(shadow_min_photons(k));
    for (size_t l = 0; l < lights; ++l) {
        if (direct[l] + shadow[l] < min_photons)
            continue;
        if (shadow[l] == 0)
            known[l] = KnownVisibility::Lit;
        else if (direct[l] == 0)
            known[l] = KnownVisibility::Shadowed;
    }
}

}  // namespace kasumi
