#pragma once
/// The two queries surfaces and media ask of each other. render/ implements them over the
/// Embree scene and the media, so surface/ and volume/ never include one another.
#include "core/color.h"
#include "core/math.h"
#include "core/rng.h"

namespace kasumi {

/// Does any surface block the open segment from `from` to `to`?
class OcclusionQuery {
  public:
    virtual ~OcclusionQuery() = default;
    virtual bool occluded(const Vec3& from, const Vec3& to) const = 0;
    /// Same along a direction to infinity (directional lights).
    virtual bool occluded_direction(const Vec3& from, const Vec3& direction) const = 0;
};

/// Transmittance of all media along a segment (surfaces ignored). May be stochastic for
/// heterogeneous media, so it takes the sample's generator.
class TransmittanceQuery {
  public:
    virtual ~TransmittanceQuery() = default;
    virtual Rgb transmittance(const Vec3& from, const Vec3& to, Pcg32& rng) const = 0;
    virtual Rgb transmittance_direction(const Vec3& from, const Vec3& direction,
                                        Pcg32& rng) const = 0;
};

}  // namespace kasumi
