#pragma once
/// Per-pixel accumulation of the beauty image and its AOVs (arbitrary output variables).
/// Samples are box-filtered: each pixel is the mean of the samples taken inside it.
#include "core/color.h"
#include "core/image.h"

#include <vector>

namespace kasumi {

/// What one camera sample measured.
struct PixelSample {
    Rgb radiance{0.0f};       ///< beauty: L_volume + T * L_surface (or background), cd/m²
    Rgb surface{0.0f};        ///< L_surface (or background) before the media
    Rgb volume{0.0f};         ///< L_volume
    Rgb transmittance{1.0f};  ///< T along the camera ray up to the surface
    Rgb albedo{0.0f};         ///< diffuse reflectance of the first surface, 0 if none
    float depth = 0.0f;       ///< camera-space depth of the first surface, metres; 0 if none
    bool hit = false;         ///< the camera ray reached a surface
};

class Film {
  public:
    Film(int width, int height);

    int width() const { return m_width; }
    int height() const { return m_height; }

    /// Adds the mean of `n` samples already summed in `sum` for pixel (x, y); `hits` of them
    /// reached a surface and `depth_sum` is their summed depth.
    void set_pixel(int x, int y, const PixelSample& sum, int n, int hits, float depth_sum);

    /// The image with channels R,G,B,A, albedo.*, depth.Z, surface.*, volume.*, transmittance.*.
    /// Alpha is the fraction of samples that hit a surface, plus the opacity 1 - T of the media
    /// for the rest (luminance-weighted).
    Image to_image() const;

  private:
    struct Pixel {
        Rgb radiance{0.0f}, surface{0.0f}, volume{0.0f}, transmittance{1.0f}, albedo{0.0f};
        float depth = 0.0f;
        float alpha = 0.0f;
    };
    int m_width, m_height;
    std::vector<Pixel> m_pixels;
};

}  // namespace kasumi
