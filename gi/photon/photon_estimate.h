#pragma once
/// Density estimates over a photon map (Jensen 2001, "Realistic Image Synthesis Using Photon
/// Mapping", ch. 7 and 10): radiance reflected by a surface and radiance in-scattered in a
/// medium from the k photons nearest to a point.
#include "gi/photon/photon_map.h"
#include "scene/photon_settings.h"

#include <optional>
#include <vector>

namespace kasumi {

/// The cone filter's constant k_cone (Jensen 2001, §7.2.2, eq. 7.9 uses k ≥ 1; 1.1 there).
inline constexpr float kConeFilterK = 1.1f;

/// Weight of a photon at distance d from the query in a disc (dims = 2) or ball (dims = 3) of
/// radius r, normalised so Σ w ΔΦ is a density per m² (per m³): ∫ w dA = 1 (∫ w dV = 1).
///   box:          1 / (π r²)                              ball: 3 / (4π r³)
///   cone:         (1 - d / (k r)) / ((1 - 2 / (3k)) π r²)  ball: / (4π r³ (1/3 - 1 / (4k)))
///   Epanechnikov: 2 (1 - d²/r²) / (π r²)                  ball: 15 (1 - d²/r²) / (8π r³)
float filter_weight(PhotonFilter filter, int dims, float d, float r);

/// Reusable storage for the neighbour search (one per thread).
struct PhotonQueryScratch {
    std::vector<PhotonNeighbour> neighbours;
};

/// The radius an estimate uses: the k-th neighbour's distance when k photons were found, else
/// max_radius (the whole search disc: fewer photons than k is a low density, not a small disc).
float estimate_radius(const std::vector<PhotonNeighbour>& found, int k, float max_radius);

/// Σ c_p w(d_p) over the k nearest photons within max_radius of x, with the filter's kernel in
/// `dims` dimensions (2: a disc on a surface, 3: a ball in a medium). `contribution(photon)`
/// returns the photon's c_p, or nothing to leave it out.
template <class Contribution>
Rgb kernel_estimate(const PhotonMap& map, const Vec3& x, int dims, int k, float max_radius,
                    PhotonFilter filter, PhotonQueryScratch& scratch, Contribution&& contribution) {
    if (map.empty())
        return Rgb(0.0f);
    map.nearest(x, k, max_radius, scratch.neighbours);
    if (scratch.neighbours.empty())
        return Rgb(0.0f);
    const float r = estimate_radius(scratch.neighbours, k, max_radius);
    Rgb sum(0.0f);
    for (const PhotonNeighbour& nb : scratch.neighbours) {
        if (const std::optional<Rgb> c = contribution(map[nb.index]))
            sum += *c * filter_weight(filter, dims, std::sqrt(nb.distance2), r);
    }
    return sum;
}

/// Reflected radiance L_r(x, wo) ≈ Σ f_r(x, wi_p, wo) ΔΦ_p w(d_p) (Jensen 2001, eq. 7.6) over the
/// k nearest photons within max_radius of x that arrived on the side n faces (dot(n, wi_p) > 0).
/// `brdf(wi)` returns f_r per steradian. With brdf ≡ 1 the result is the irradiance E (lux).
template <class Brdf>
Rgb surface_estimate(const PhotonMap& map, const Vec3& x, const Vec3& n, int k, float max_radius,
                     PhotonFilter filter, PhotonQueryScratch& scratch, Brdf&& brdf) {
    return kernel_estimate(map, x, 2, k, max_radius, filter, scratch,
                           [&](const Photon& p) -> std::optional<Rgb> {
                               if (!(glm::dot(n, p.wi) > 0.0f))
                                   return std::nullopt;
                               return brdf(p.wi) * p.power;
                           });
}

/// In-scattered radiance per unit length at x toward wo, σ_s ∫ p(wo, wi) L(wi) dwi ≈
/// Σ p(wo, wi_p) ΔΦ_p w(d_p) over the k nearest volume photons (Jensen & Christensen 1998,
/// eq. 11), in cd/m² per metre, for photons stored with the flux they scatter (σ_s folded in).
/// `phase(wi)` returns the phase function per steradian (per channel).
template <class Phase>
Rgb volume_estimate(const PhotonMap& map, const Vec3& x, int k, float max_radius,
                    PhotonFilter filter, PhotonQueryScratch& scratch, Phase&& phase) {
    return kernel_estimate(
        map, x, 3, k, max_radius, filter, scratch,
        [&](const Photon& p) -> std::optional<Rgb> { return phase(p.wi) * p.power; });
}

}  // namespace kasumi
