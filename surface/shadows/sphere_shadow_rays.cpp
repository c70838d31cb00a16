#include "surface/shadows/sphere_shadow_rays.h"

namespace kasumi {

bool shadow_ray_blocked(const SurfaceScene& scene, const Vec3& origin, const LightCentre& light) {
    if (light.at_infinity)
        return scene.occluded(Ray{origin, light.direction, 0.0f, kInfinity});
    const Vec3 d = light.position - origin;
    const float distance = glm::length(d);
    // Stop just short of the light so that a light on a surface is not blocked by it.
    return distance > 0.0f &&
           scene.occluded(Ray{origin, d / distance, 0.0f, distance * (1.0f - 1e-5f)});
}

std::unique_ptr<SurfaceScene> sphere_scene(const std::vector<Shape>& shapes) {
    std::vector<Shape> spheres;
    for (const Shape& shape : shapes)
        if (std::holds_alternative<SphereShape>(shape.geometry))
            spheres.push_back(shape);
    return spheres.empty() ? nullptr : std::make_unique<SurfaceScene>(spheres);
}

}  // namespace kasumi
