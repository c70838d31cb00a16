#pragma once
/// The centre of projection of the polygon shadow methods (shadow volumes, object-space
/// shadows): a point-like light's position, or for a directional light the point at infinity in
/// the direction toward it (homogeneous w = 0: projection along parallel lines).
#include "core/math.h"
#include "lights/light.h"

namespace kasumi {

/// World space, metres.
struct LightCentre {
    Vec3 position{0.0f};               ///< the light's position (w = 1); unused at infinity
    Vec3 direction{0.0f, 1.0f, 0.0f};  ///< unit, toward the light; used at infinity (w = 0)
    bool at_infinity = false;
};

/// The centre of a delta light: point, spot and goniometric lights at their position,
/// directional lights at infinity. Extended lights have none (callers refuse them at load time).
LightCentre light_centre(const Light& light);

/// A point light at `position`.
LightCentre point_centre(const Vec3& position);
/// A parallel light shining from `direction_to_light` (normalised here).
LightCentre parallel_centre(const Vec3& direction_to_light);

/// Unit direction from p toward the light.
Vec3 toward_light(const LightCentre& light, const Vec3& p);

/// Signed height of the light above the plane through `on_plane` with normal `normal`:
/// dot(normal, L − on_plane) for a point light, dot(normal, direction) for one at infinity
/// (its sign is all that a point at infinity has).
double light_height(const LightCentre& light, const DVec3& on_plane, const DVec3& normal);

}  // namespace kasumi
