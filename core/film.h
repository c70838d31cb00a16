#pragma once
/// Per-pixel accumulation of the beauty image and its AOVs (arbitrary output variables).
/// Samples are box-filtered: each pixel is the mean of the samples taken inside it.
#include "core/color.h"
#include "core/image.h"

#include <cstdint>
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

/// Which AOVs an image of the film carries besides the beauty R, G, B, A (a bit set).
enum FilmAov : uint32_t {
    kAovNone = 0,
    kAovAlbedo = 1u << 0,         ///< albedo.R/G/B
    kAovDepth = 1u << 1,          ///< depth.Z
    kAovSurface = 1u << 2,        ///< surface.R/G/B
    kAovVolume = 1u << 3,         ///< volume.R/G/B
    kAovTransmittance = 1u << 4,  ///< transmittance.R/G/B
    kAovAll = 31u,
};

/// Parses a comma-separated list of AOV names ("albedo", "depth", "surface", "volume",
/// "transmittance"), or "all" or "none"; returns false on an unknown name.
bool parse_film_aovs(const std::string& text, uint32_t& aovs);

class Film {
  public:
    /// All pixels start empty (black, transmittance 1, alpha 0). The pixel storage of a
    /// destroyed film is kept for the next film of the same size (a sequence renders one film
    /// per frame: a 1280x720 film is 63 MB whose fresh pages cost more to fault in than to
    /// clear); at most two films' storage is kept.
    Film(int width, int height);
    ~Film();
    Film(const Film&) = default;
    Film(Film&&) noexcept = default;
    Film& operator=(const Film&) = default;
    Film& operator=(Film&&) noexcept = default;

    int width() const { return m_width; }
    int height() const { return m_height; }

    /// Adds the mean of `n` samples already summed in `sum` for pixel (x, y); `hits` of them
    /// reached a surface and `depth_sum` is their summed depth.
    void set_pixel(int x, int y, const PixelSample& sum, int n, int hits, float depth_sum);

    /// The image with channels R,G,B,A, albedo.*, depth.Z, surface.*, volume.*, transmittance.*.
    /// Alpha is the fraction of samples that hit a surface, plus the opacity 1 - T of the media
    /// for the rest (luminance-weighted).
    Image to_image() const;

    /// The same into `image`, reusing its channel buffers when it already has this film's size
    /// and channels (no allocation: what a sequence does frame after frame); `aovs` (FilmAov
    /// bits) chooses the AOV channels, in the order above. Metadata is cleared.
    void to_image(Image& image, uint32_t aovs = kAovAll) const;

  private:
    struct Pixel {
        Rgb radiance{0.0f}, surface{0.0f}, volume{0.0f}, transmittance{1.0f}, albedo{0.0f};
        float depth = 0.0f;
        float alpha = 0.0f;
    };
    /// Pixel storage of destroyed films, kept for reuse (guarded by a mutex in film.cpp).
    static std::vector<std::vector<Pixel>>& kept_storage();

    int m_width, m_height;
    std::vector<Pixel> m_pixels;
};

}  // namespace kasumi
