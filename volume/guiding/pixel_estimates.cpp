#include "volume/guiding/pixel_estimates.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

/// Ray direction d scaled to the plane at distance 1 along `forward`.
Vec3 on_unit_plane(const Vec3& d, const Vec3& forward) {
    return d / glm::dot(d, forward);
}

}  // namespace

PixelEstimates::PixelEstimates(const Camera& camera, int width, int height,
                               const std::vector<float>& mean_luminance)
    : m_origin(camera.position()), m_forward(camera.forward()), m_width(width), m_height(height) {
    const float w = static_cast<float>(width), h = static_cast<float>(height);
    // The rays through the film's right edge and top edge centres give its half extents.
    m_right = on_unit_plane(camera.generate_ray(w, 0.5f * h).direction, m_forward) - m_forward;
    m_up = on_unit_plane(camera.generate_ray(0.5f * w, 0.0f).direction, m_forward) - m_forward;
    m_values.assign(mean_luminance.size(), 0.0f);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            double sum = 0.0;
            int count = 0;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= width || yy >= height)
                        continue;
                    sum += mean_luminance[static_cast<size_t>(yy * width + xx)];
                    ++count;
                }
            }
            m_values[static_cast<size_t>(y * width + x)] = static_cast<float>(sum / count);
        }
    }
}

float PixelEstimates::at(const Ray& ray) const {
    if (m_values.empty() || ray.origin != m_origin)
        return -1.0f;
    const float along = glm::dot(ray.direction, m_forward);
    if (!(along > 0.0f))
        return -1.0f;
    const Vec3 v = on_unit_plane(ray.direction, m_forward) - m_forward;
    const float ndc_x = glm::dot(v, m_right) / glm::dot(m_right, m_right);
    const float ndc_y = glm::dot(v, m_up) / glm::dot(m_up, m_up);
    const float px = 0.5f * (ndc_x + 1.0f) * static_cast<float>(m_width);
    const float py = 0.5f * (1.0f - ndc_y) * static_cast<float>(m_height);
    if (!(px >= 0.0f && py >= 0.0f && px < static_cast<float>(m_width) &&
          py < static_cast<float>(m_height)))
        return -1.0f;
    const int x = std::min(m_width - 1, static_cast<int>(px));
    const int y = std::min(m_height - 1, static_cast<int>(py));
    return m_values[static_cast<size_t>(y * m_width + x)];
}

}  // namespace kasumi
