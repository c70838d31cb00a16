#pragma once
/// Each pixel's estimate from guiding's training passes, and the camera projection that finds
/// the pixel of a camera ray: the weight window's centre of render.volume.splitting "guided"
/// (Vorba & Křivánek 2016, "Adjoint-driven Russian roulette and splitting in light transport
/// simulation", sec. 4: the window is centred on the pixel's estimated measurement, so a path
/// whose expected contribution is far below the pixel's value is rouletted and one far above it
/// is split).
#include "core/camera.h"

#include <vector>

namespace kasumi {

class PixelEstimates {
  public:
    PixelEstimates() = default;
    /// The estimates of a `width` x `height` film seen by `camera` (generate_ray's film
    /// coordinates): `mean_luminance`, row-major, cd/m², each pixel's mean training estimate.
    /// Every pixel keeps the mean of its 3 x 3 neighbourhood (clipped at the film's edges): a
    /// few training samples per pixel are heavy-tailed, and the centre only steers the window.
    PixelEstimates(const Camera& camera, int width, int height,
                   const std::vector<float>& mean_luminance);

    bool empty() const { return m_values.empty(); }
    /// The estimate of the pixel ray `ray` passes through (cd/m²); negative when the ray does
    /// not start exactly at the camera's position (a reflected ray, a nested path) or leaves the
    /// film.
    float at(const Ray& ray) const;

  private:
    Vec3 m_origin{0.0f};
    Vec3 m_forward{0.0f};
    Vec3 m_right{0.0f};  ///< the film's half width on the plane at distance 1 along m_forward
    Vec3 m_up{0.0f};     ///< the film's half height there
    int m_width = 0;
    int m_height = 0;
    std::vector<float> m_values;
};

}  // namespace kasumi
