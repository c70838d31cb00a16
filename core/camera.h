#pragma once
/// A pinhole camera. Image y runs down (row 0 is the top of the image); film coordinates are in
/// pixels with the pixel (x, y) covering [x, x+1) × [y, y+1).
#include "core/math.h"

namespace kasumi {

struct CameraDesc {
    Vec3 position{0.0f, 1.0f, 5.0f};
    Vec3 look_at{0.0f, 1.0f, 0.0f};
    Vec3 up{0.0f, 1.0f, 0.0f};
    float fov_deg = 45.0f;  ///< vertical field of view, degrees, in (0, 180)
};

class Camera {
  public:
    Camera(const CameraDesc& desc, int width, int height);

    /// The primary ray through film position (px, py) in pixels.
    Ray generate_ray(float px, float py) const;

    const Vec3& position() const { return m_position; }
    const Vec3& forward() const { return m_forward; }

  private:
    Vec3 m_position;
    Vec3 m_forward, m_right, m_up;
    float m_tan_half_fov;
    float m_aspect;
    int m_width, m_height;
};

}  // namespace kasumi
