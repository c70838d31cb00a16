#include "core/camera.h"

#include "core/error.h"

namespace kasumi {

Camera::Camera(const CameraDesc& desc, int width, int height)
    : m_position(desc.position),
      m_tan_half_fov(std::tan(0.5f * radians(desc.fov_deg))),
      m_aspect(static_cast<float>(width) / static_cast<float>(height)),
      m_width(width),
      m_height(height) {
    m_forward = glm::normalize(desc.look_at - desc.position);
    m_right = glm::normalize(glm::cross(m_forward, desc.up));
    m_up = glm::cross(m_right, m_forward);
    KASUMI_CHECK(is_finite(m_forward) && is_finite(m_right));
}

Ray Camera::generate_ray(float px, float py) const {
    // Normalised device coordinates in [-1, 1], y up.
    const float ndc_x = 2.0f * px / static_cast<float>(m_width) - 1.0f;
    const float ndc_y = 1.0f - 2.0f * py / static_cast<float>(m_height);
    const Vec3 d =
        m_forward + (ndc_x * m_aspect * m_tan_half_fov) * m_right + (ndc_y * m_tan_half_fov) * m_up;
    return Ray{m_position, glm::normalize(d), 0.0f, kInfinity};
}

}  // namespace kasumi
