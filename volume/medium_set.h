#pragma once
/// All media of a scene, queried together: overlapping media add their coefficients and mix
/// their phase functions in proportion to their scattering coefficients.
#include "core/color.h"
#include "volume/medium.h"

#include <vector>

namespace kasumi {

/// A stretch [t0, t1] of a ray over which every coefficient is constant.
struct MediumInterval {
    float t0 = 0.0f;
    float t1 = 0.0f;
    Rgb sigma_t{0.0f};
    Rgb sigma_s{0.0f};
    uint32_t scattering_mask = 0;  ///< bit k set: medium k scatters here
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

    /// Optical depth tau along the ray over [t_min, t_max] (exact for homogeneous media).
    Rgb optical_depth(const Ray& ray) const;
    /// Beer-Lambert transmittance exp(-tau) over [t_min, t_max].
    Rgb transmittance(const Ray& ray) const { return exp_neg(optical_depth(ray)); }

    /// Splits [t_min, t_max] at every medium boundary and returns the stretches inside at least
    /// one medium, in order. `out` is reused to avoid allocation in the hot loop.
    void intervals(const Ray& ray, std::vector<MediumInterval>& out) const;

    /// Phase-weighted scattering sum_m sigma_s,m p_m(mu) at a point of `interval`, in 1/(m sr).
    Rgb scattering(const MediumInterval& interval, float mu) const;

  private:
    std::vector<Medium> m_media;
};

}  // namespace kasumi
