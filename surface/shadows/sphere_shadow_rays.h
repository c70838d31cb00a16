#pragma once
/// The polygon shadow methods' fallback for analytic spheres (no polygons to clip or extrude):
/// a shadow ray toward the light's centre of projection against the spheres alone, or against
/// a whole scene for a point on a sphere.
#include "surface/shadows/light_centre.h"
#include "surface/shape.h"
#include "surface/surface_scene.h"

#include <memory>
#include <vector>

namespace kasumi {

/// True when `scene` blocks the ray from `origin` (already offset off its surface) to the
/// light: up to just short of a point light, to infinity along a parallel light's direction.
bool shadow_ray_blocked(const SurfaceScene& scene, const Vec3& origin, const LightCentre& light);

/// The spheres of `shapes` as their own Embree scene; null when there are none.
std::unique_ptr<SurfaceScene> sphere_scene(const std::vector<Shape>& shapes);

}  // namespace kasumi
