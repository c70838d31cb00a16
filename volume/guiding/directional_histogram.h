#pragma once
/// A distribution of directions on the unit sphere as a histogram over equal-area bins: kZBands
/// bands of equal width in z = cos(theta) (world z axis) times kPhiBins sectors in phi, so every
/// bin spans 4 pi / kBins sr (Archimedes' hat-box theorem; the cylindrical equal-area map of
/// Müller, Gross & Novák 2017, "Practical path guiding", sec. 5.3, without their quadtree).
/// Density per steradian; sampling is exact (the pdf is piecewise constant over the bins).
#include "core/math.h"

#include <array>

namespace kasumi {

class DirectionalHistogram {
  public:
    static constexpr int kZBands = 8;
    static constexpr int kPhiBins = 16;
    static constexpr int kBins = kZBands * kPhiBins;

    /// Solid angle of every bin, sr.
    static constexpr float kBinSolidAngle = 4.0f * kPi / static_cast<float>(kBins);

    /// The bin holding unit direction `w`.
    static int bin_of(const Vec3& w);
    /// The direction at (z, phi) fractions `u` in [0, 1)² of bin `bin`: uniform over the bin's
    /// solid angle when u is uniform (equal-area map); u = (0.5, 0.5) is the bin's centre.
    static Vec3 in_bin(int bin, Vec2 u);

    /// Adds `weight` (>= 0, finite; anything else is ignored) to the bin of unit direction `w`.
    void add(const Vec3& w, double weight);
    /// Turns the added weights into a pdf in which a share `uniform` in [0, 1] is spread evenly
    /// (so no direction's density is below uniform / (4 pi)); false, and no pdf, when no weight
    /// was added.
    bool normalise(float uniform);

    /// Probability of bin `bin` (0 before normalise()).
    float mass(int bin) const { return m_mass[static_cast<size_t>(bin)]; }
    /// Density of direction `w` (unit), per steradian; 0 before normalise().
    float pdf(const Vec3& w) const;
    /// A direction drawn in proportion to pdf() from `u` in [0, 1)², and its pdf per steradian.
    Vec3 sample(Vec2 u, float& pdf_sr) const;

  private:
    std::array<double, kBins> m_weight{};  ///< summed weights while training
    std::array<float, kBins> m_mass{};     ///< probability of each bin after normalise()
    std::array<float, kBins> m_cdf{};      ///< running sum of m_mass, the last one 1
};

}  // namespace kasumi
