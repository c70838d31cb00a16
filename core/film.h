#pragma once
/// Per-pixel accumulation of the beauty image and its AOVs (arbitrary output variables).
/// Samples are box-filtered: each pixel is the mean of the samples taken inside it.
#include "core/color.h"
#include "core/image.h"
#include "core/zeroed_allocator.h"

#include <cstdint>
#include <string>
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

/// One channel plane of a film, borrowed: width * height floats, top row first.
struct FilmPlane {
    std::string name;  ///< EXR channel name: "R", "A", "albedo.R", "depth.Z", ...
    const float* data = nullptr;
};

/// Which AOVs an image of the film carries besides the beauty R, G, B, A (a bit set).
enum FilmAov : uint32_t {
    kAovNone = 0,
    kAovAlbedo = 1u << 0,         ///< albedo.R/G/B
    kAovDepth = 1u << 1,          ///< depth.Z
    kAovSurface = 1u << 2,        ///< surface.R/G/B
    kAovVolume = 1u << 3,         ///< volume.R/G/B
    kAovTransmittance = 1u << 4,  ///< transmittance.R/G/B
    kAovAll = 31u,                ///< the five above ("all" on the command line adds samples)
    /// samples.count: camera samples taken in the pixel (adaptive sampling stops pixels before
    /// film.spp; render/adaptive_sampling.h). Not in kAovAll: a uniform render's count is
    /// film.spp everywhere, in the metadata.
    kAovSamples = 1u << 5,
    /// noisy.R/G/B: the beauty before film.denoise (render/denoise/), stored only when the
    /// beauty is denoised. Not in kAovAll ("all" on the command line adds it).
    kAovNoisy = 1u << 6,
};

/// Parses a comma-separated list of AOV names ("albedo", "depth", "surface", "volume",
/// "transmittance", "samples", "noisy"), or "all" (every one) or "none"; returns false on an
/// unknown name.
bool parse_film_aovs(const std::string& text, uint32_t& aovs);

class Film {
  public:
    /// All pixels start empty (black, transmittance 1, alpha 0). The film stores R, G, B, A and
    /// only the AOVs in `aovs` (FilmAov bits), one plane per channel in the order of to_image:
    /// a render that writes no AOVs allocates, fills and reads out 4 floats per pixel, not 17.
    /// The storage of a destroyed film is kept for the next film of the same size and AOVs (a
    /// sequence renders one film per frame: a 1280x720 film with every AOV is 63 MB whose fresh
    /// pages cost more to fault in than to clear); at most two films' storage is kept.
    Film(int width, int height, uint32_t aovs = kAovAll);
    ~Film();
    Film(const Film&) = default;
    Film(Film&&) noexcept = default;
    Film& operator=(const Film&) = default;
    Film& operator=(Film&&) noexcept = default;

    int width() const { return m_width; }
    int height() const { return m_height; }
    uint32_t aovs() const { return m_aovs; }  ///< the AOVs stored (FilmAov bits)

    /// Adds the mean of `n` samples already summed in `sum` for pixel (x, y); `hits` of them
    /// reached a surface and `depth_sum` is their summed depth. The samples AOV records `n`.
    void set_pixel(int x, int y, const PixelSample& sum, int n, int hits, float depth_sum);

    /// The image with channels R,G,B,A, then the stored AOVs among albedo.*, depth.Z, surface.*,
    /// volume.*, transmittance.*, samples.count, noisy.*, in that order. Alpha is the fraction of
    /// samples that hit a surface, plus the opacity 1 - T of the media for the rest
    /// (luminance-weighted).
    Image to_image() const;

    /// The same into `image`, reusing its channel buffers when it already has this film's size
    /// and channels (no allocation: what a sequence does frame after frame); `aovs` (FilmAov
    /// bits) chooses the AOV channels among the stored ones (a uniform render stores no
    /// samples.count, so "all" writes it only for adaptive renders), in the order above. One
    /// copy per plane. Metadata is cleared.
    void to_image(Image& image, uint32_t aovs) const;
    void to_image(Image& image) const { to_image(image, m_aovs); }

    /// The planes to_image(image, aovs) would copy, in its channel order, without copying
    /// (valid while the film lives): what the EXR writer reads directly.
    std::vector<FilmPlane> planes(uint32_t aovs) const;

    /// Replaces the beauty R, G, B (cd/m², each `width * height` floats, top row first) with
    /// `rgb`, first copying the old beauty into noisy.R/G/B if that AOV is stored. Alpha and the
    /// other AOVs are unchanged (what film.denoise does).
    void replace_beauty(const float* const rgb[3]);

  private:
    /// Plane storage: a new film's planes are fresh zeroed pages (calloc), not a fill pass.
    using Storage = std::vector<float, ZeroedAllocator<float>>;
    /// Storage of destroyed films, kept for reuse (guarded by a mutex in film.cpp).
    static std::vector<Storage>& kept_storage();
    /// Plane `channel` (0..3: R, G, B, A, then the stored AOVs' channels in order).
    float* plane(int channel) { return m_planes.data() + static_cast<size_t>(channel) * m_pixels; }
    const float* plane(int channel) const {
        return m_planes.data() + static_cast<size_t>(channel) * m_pixels;
    }

    int m_width, m_height;
    uint32_t m_aovs;
    size_t m_pixels;
    /// First plane of each AOV (index by bit position: albedo, depth, surface, volume,
    /// transmittance, samples, noisy), -1 if not stored.
    int m_first[7];
    Storage m_planes;  ///< channel-major: plane c holds pixel i at c * m_pixels + i
};

}  // namespace kasumi
