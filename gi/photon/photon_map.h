#pragma once
/// A photon map (Jensen 1996): photons in a balanced kd-tree with k-nearest-neighbour queries
/// bounded by a maximum radius.
#include "core/color.h"
#include "core/math.h"

#include <cstdint>
#include <vector>

namespace kasumi {

/// A stored photon. `wi` points back toward where it came from (the project's convention: away
/// from the point, toward the light), so a surface of normal n is lit by it when dot(n, wi) > 0.
struct Photon {
    Vec3 position{0.0f};  ///< world, metres
    Vec3 wi{0.0f, 0.0f, 1.0f};
    Rgb power{0.0f};  ///< flux, photometrically scaled RGB (luminance in lm); 0 in the shadow map
    /// Shadow map only (gi/photon/photon_shadow.h): the index of the light that emitted it, and
    /// whether it is a shadow photon (deposited behind the first surface its line from the light
    /// meets) rather than a direct-illumination photon (at that first surface).
    uint16_t light = 0;
    bool shadow = false;
};

/// One neighbour found by PhotonMap::nearest.
struct PhotonNeighbour {
    float distance2 = 0.0f;  ///< squared distance to the query point, m²
    uint32_t index = 0;      ///< into the map
};

/// Balanced kd-tree stored implicitly (Bentley 1975; Jensen 2001, §6.3): the photons of a subtree
/// occupy a contiguous range whose middle element is the node, split on the axis of largest
/// extent of the range, smaller coordinates on the left. Depth ⌈log2(N + 1)⌉ for any input.
/// Immutable after construction; queries are thread-safe.
class PhotonMap {
  public:
    PhotonMap() = default;
    explicit PhotonMap(std::vector<Photon> photons);

    size_t size() const { return m_photons.size(); }
    bool empty() const { return m_photons.empty(); }
    const Photon& operator[](size_t i) const { return m_photons[i]; }
    const std::vector<Photon>& photons() const { return m_photons; }

    /// The (at most) k photons nearest to p with distance < max_radius, into `out` (cleared
    /// first) as a max-heap on distance2: out.front() is the farthest found. Ties at equal
    /// distance are broken arbitrarily.
    void nearest(const Vec3& p, int k, float max_radius, std::vector<PhotonNeighbour>& out) const;

  private:
    void build(size_t lo, size_t hi);
    void search(size_t lo, size_t hi, const Vec3& p, size_t k, float& radius2,
                std::vector<PhotonNeighbour>& out) const;

    std::vector<Photon> m_photons;
    std::vector<uint8_t> m_axis;  ///< split axis of the node at each index
};

}  // namespace kasumi
