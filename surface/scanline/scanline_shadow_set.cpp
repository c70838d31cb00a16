#include "surface/scanline/scanline_shadow_set.h"

#include "surface/shadows/sphere_shadow_rays.h"

#include <cmath>

namespace kasumi {

ScanlineCamera scanline_camera(const CameraDesc& camera, int width, int height) {
    // The axes and scale of Camera (core/camera.cpp): right = forward × up, up = right × forward,
    // horizontal half extent aspect · tan(fov/2).
    ScanlineCamera c;
    c.eye = camera.position;
    c.forward = glm::normalize(camera.look_at - camera.position);
    c.right = glm::normalize(glm::cross(c.forward, camera.up));
    c.up = glm::cross(c.right, c.forward);
    c.half_width = double(width) / double(height) * std::tan(0.5 * double(radians(camera.fov_deg)));
    c.width = width;
    c.height = height;
    return c;
}

ScanlineShadows::ScanlineShadows(const std::vector<Shape>& shapes, const LightCentre& light,
                                 const ScanlineCamera& camera, const SurfaceScene& scene)
    : m_image(render_scanline_shadows(shapes, light, camera)),
      m_camera(camera),
      m_light(light),
      m_scene(&scene),
      m_spheres(sphere_scene(shapes)) {}

ScanlineShadows::~ScanlineShadows() = default;

int64_t ScanlineShadows::pixel_at_centre(const Vec3& p) const {
    const ScanlineCamera& c = m_camera;
    const DVec3 d = DVec3(p) - DVec3(c.eye);
    const double z = glm::dot(d, DVec3(c.forward));
    if (!(z > 0.0))
        return -1;
    const double half_height = c.half_width * c.height / c.width;
    const double px = (glm::dot(d, DVec3(c.right)) / (z * c.half_width) + 1.0) * 0.5 * c.width;
    const double py = (1.0 - glm::dot(d, DVec3(c.up)) / (z * half_height)) * 0.5 * c.height;
    const double x = std::floor(px), y = std::floor(py);
    if (!(x >= 0.0 && x < c.width && y >= 0.0 && y < c.height))
        return -1;
    if (std::abs(px - (x + 0.5)) > kPixelCentreTolerance ||
        std::abs(py - (y + 0.5)) > kPixelCentreTolerance)
        return -1;
    return static_cast<int64_t>(y) * c.width + static_cast<int64_t>(x);
}

bool ScanlineShadows::in_shadow(const SurfaceHit& hit, const Vec3& origin, bool* by_pass) const {
    const int64_t pixel = pixel_at_centre(hit.position);
    const bool answered = pixel >= 0 && m_image.shape[pixel] == int32_t(hit.shape) &&
                          m_image.primitive[pixel] == int32_t(hit.primitive);
    if (by_pass != nullptr)
        *by_pass = answered;
    if (!answered)
        return shadow_ray_blocked(*m_scene, origin, m_light);
    if (m_image.shadowed[pixel] != 0)
        return true;
    return m_spheres != nullptr && shadow_ray_blocked(*m_spheres, origin, m_light);
}

ScanlineShadowSet::ScanlineShadowSet(const std::vector<Shape>& shapes,
                                     const std::vector<Light>& lights, const CameraDesc& camera,
                                     int width, int height, const SurfaceScene& scene) {
    const ScanlineCamera view = scanline_camera(camera, width, height);
    for (const Light& light : lights)
        m_shadows.push_back(
            light.shadows == ShadowMode::Scanline
                ? std::make_unique<ScanlineShadows>(shapes, light_centre(light), view, scene)
                : nullptr);
}

}  // namespace kasumi
