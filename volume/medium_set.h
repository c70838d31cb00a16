#pragma once
/// All media of a scene, queried together: overlapping media add their coefficients and mix
/// their phase functions in proportion to their scattering coefficients.
#include "core/color.h"
#include "phase/phase_sample.h"
#include "volume/medium.h"

#include <vector>

namespace kasumi {

/// A stretch [t0, t1] of a ray over which every coefficient is constant (homogeneous media).
struct MediumInterval {
    float t0 = 0.0f;
    float t1 = 0.0f;
    Rgb sigma_t{0.0f};
    Rgb sigma_s{0.0f};
    uint32_t scattering_mask = 0;  ///< bit k set: medium k scatters here
};

/// A stretch [t0, t1] of a ray with bounds on the extinction of all media over it (1/m):
/// sigma_min <= sigma_t(x) <= sigma_max per channel. Stretches not listed hold no medium.
struct MajorantSegment {
    float t0 = 0.0f;
    float t1 = 0.0f;
    Rgb sigma_max{0.0f};
    Rgb sigma_min{0.0f};
    uint32_t media_mask = 0;  ///< bit k set: medium k may be non-zero here
};

/// Coefficients of all media at one point, 1/m.
struct PointCoefficients {
    Rgb sigma_t{0.0f};
    Rgb sigma_s{0.0f};
};

/// A direction drawn from the scattering-weighted mixture of phase functions at a point.
struct MixtureSample {
    Vec3 wi{0.0f};
    Rgb scattering{0.0f};  ///< sum_m sigma_s,m p_m(mu) at wi, 1/(m sr)
    float pdf = 0.0f;      ///< per steradian; 0 when nothing scatters
};

/// Media beyond this count are rejected at load time (interval bookkeeping uses a 32-bit mask).
inline constexpr size_t kMaxMedia = 32;

class MediumSet {
  public:
    MediumSet() = default;
    explicit MediumSet(std::vector<Medium> media);

    bool empty() const { return m_media.empty(); }
    const std::vector<Medium>& media() const { return m_media; }
    /// True if any medium scatters light (sigma_s > 0 in some channel).
    bool scatters() const;
    /// True if every medium is homogeneous (then `intervals` and `optical_depth` are exact).
    bool all_homogeneous() const { return m_all_homogeneous; }
    /// True if every medium's extinction is the same in all channels (trackers run once).
    bool grey_extinction() const { return m_grey_extinction; }
    /// Shortest voxel edge of the grid media, metres (kInfinity without grids).
    float smallest_voxel_m() const;

    /// Optical depth tau along the ray over [t_min, t_max], exact; homogeneous media only
    /// (grids are left out: use the transmittance estimators for them).
    Rgb optical_depth(const Ray& ray) const;
    /// Beer-Lambert transmittance exp(-tau) over [t_min, t_max]; homogeneous media only.
    Rgb transmittance(const Ray& ray) const { return exp_neg(optical_depth(ray)); }

    /// Splits [t_min, t_max] at every homogeneous medium's boundary and returns the stretches
    /// inside at least one, in order. `out` is reused to avoid allocation in the hot loop.
    void intervals(const Ray& ray, std::vector<MediumInterval>& out) const;

    /// Phase-weighted scattering sum_m sigma_s,m p_m(mu) at a point of `interval`, in 1/(m sr).
    Rgb scattering(const MediumInterval& interval, float mu) const;

    /// Majorant/minorant stretches of [t_min, t_max] in order, skipping empty space: one per
    /// homogeneous box and one per non-empty grid brick (bricks found by a DDA), overlapping
    /// media summed. `out` is reused.
    void majorants(const Ray& ray, std::vector<MajorantSegment>& out) const;

    /// Coefficients at world point p, summing the media in `mask` (a segment's media_mask).
    /// Homogeneous media in the mask count without a bounds test (the segment is inside them).
    PointCoefficients coefficients(const Vec3& p, uint32_t mask) const;
    /// sum_m sigma_s,m(p) p_m(mu) over the media in `mask`, in 1/(m sr).
    Rgb scattering(const Vec3& p, uint32_t mask, float mu) const;
    /// Picks a medium in proportion to the luminance of its sigma_s at p (with `u_pick`), samples
    /// its phase function with `u`, and returns the mixture's value and pdf for that direction.
    MixtureSample sample_scattering(const Vec3& p, uint32_t mask, const Vec3& wo, float u_pick,
                                    Vec2 u) const;

  private:
    std::vector<Medium> m_media;
    bool m_all_homogeneous = true;
    bool m_grey_extinction = true;
};

}  // namespace kasumi
