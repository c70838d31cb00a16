#pragma once
/// The query media ask of surfaces (god rays, cloud shadows on the ground): render/ implements it
/// over the Embree scene (SurfaceOcclusion), so volume/ never includes surface/. Surfaces get the
/// media's transmittance toward a light from render/ calling volume/ directly.
#include "core/math.h"

namespace kasumi {

/// Does any surface block the open segment from `from` to `to` (world space, metres)?
class OcclusionQuery {
  public:
    virtual ~OcclusionQuery() = default;
    /// True when a surface blocks the segment; the end point itself does not count.
    virtual bool occluded(const Vec3& from, const Vec3& to) const = 0;
    /// Same along a unit direction to infinity (directional lights).
    virtual bool occluded_direction(const Vec3& from, const Vec3& direction) const = 0;
};

}  // namespace kasumi
