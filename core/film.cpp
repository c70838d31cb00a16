#include "core/film.h"

#include <algorithm>
#include <mutex>
#include <sstream>

namespace kasumi {

namespace {

/// Films smaller than this (pixels) are not worth keeping: their storage is cheap to allocate.
constexpr size_t kKeepMinPixels = size_t{1} << 16;
/// Storage of at most this many destroyed films is kept (a sequence alternates between one
/// film being rendered and one being read out).
constexpr size_t kKeepFilms = 2;

std::mutex& kept_mutex() {
    static std::mutex mutex;
    return mutex;
}

}  // namespace

bool parse_film_aovs(const std::string& text, uint32_t& aovs) {
    aovs = kAovNone;
    std::istringstream in(text);
    std::string name;
    bool any = false;
    while (std::getline(in, name, ',')) {
        any = true;
        if (name == "all")
            aovs |= kAovAll;
        else if (name == "none")
            continue;
        else if (name == "albedo")
            aovs |= kAovAlbedo;
        else if (name == "depth")
            aovs |= kAovDepth;
        else if (name == "surface")
            aovs |= kAovSurface;
        else if (name == "volume")
            aovs |= kAovVolume;
        else if (name == "transmittance")
            aovs |= kAovTransmittance;
        else
            return false;
    }
    return any;
}

std::vector<std::vector<Film::Pixel>>& Film::kept_storage() {
    static std::vector<std::vector<Pixel>> kept;
    return kept;
}

Film::Film(int width, int height) : m_width(width), m_height(height) {
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (n >= kKeepMinPixels) {
        std::lock_guard<std::mutex> lock(kept_mutex());
        auto& kept = kept_storage();
        for (auto it = kept.begin(); it != kept.end(); ++it) {
            if (it->size() == n) {
                m_pixels = std::move(*it);
                kept.erase(it);
                break;
            }
        }
    }
    if (m_pixels.size() == n)
        std::fill(m_pixels.begin(), m_pixels.end(), Pixel{});
    else
        m_pixels.assign(n, Pixel{});
}

Film::~Film() {
    if (m_pixels.size() < kKeepMinPixels)
        return;
    try {
        std::lock_guard<std::mutex> lock(kept_mutex());
        auto& kept = kept_storage();
        if (kept.size() >= kKeepFilms)
            kept.erase(kept.begin());  // keep the newest sizes
        kept.push_back(std::move(m_pixels));
    } catch (...) {
        // Keeping is an optimisation: if it fails, the storage is simply freed.
    }
}

void Film::set_pixel(int x, int y, const PixelSample& sum, int n, int hits, float depth_sum) {
    Pixel& p = m_pixels[static_cast<size_t>(y) * m_width + x];
    const float inv = 1.0f / static_cast<float>(n);
    p.radiance = sum.radiance * inv;
    p.surface = sum.surface * inv;
    p.volume = sum.volume * inv;
    p.transmittance = sum.transmittance * inv;
    p.albedo = sum.albedo * inv;
    p.depth = hits > 0 ? depth_sum / static_cast<float>(hits) : 0.0f;
    // Samples that hit are opaque; the others are as opaque as the media in front of the sky.
    const float hit_fraction = static_cast<float>(hits) * inv;
    const float miss_opacity = (1.0f - hit_fraction) > 0.0f
                                   ? std::clamp(1.0f - luminance(p.transmittance), 0.0f, 1.0f)
                                   : 0.0f;
    p.alpha = hit_fraction + (1.0f - hit_fraction) * miss_opacity;
}

Image Film::to_image() const {
    Image image;
    to_image(image, kAovAll);
    return image;
}

void Film::to_image(Image& image, uint32_t aovs) const {
    const char* rgb[3] = {"R", "G", "B"};
    std::vector<std::string> names = {"R", "G", "B", "A"};
    const auto add3 = [&](uint32_t bit, const char* prefix) {
        if ((aovs & bit) != 0) {
            for (int c = 0; c < 3; ++c)
                names.push_back(std::string(prefix) + rgb[c]);
        }
    };
    add3(kAovAlbedo, "albedo.");
    if ((aovs & kAovDepth) != 0)
        names.push_back("depth.Z");
    add3(kAovSurface, "surface.");
    add3(kAovVolume, "volume.");
    add3(kAovTransmittance, "transmittance.");

    const size_t n = m_pixels.size();
    bool reusable =
        image.width == m_width && image.height == m_height && image.channels.size() == names.size();
    for (size_t i = 0; reusable && i < names.size(); ++i)
        reusable = image.channels[i].name == names[i] && image.channels[i].data.size() == n;
    if (!reusable) {
        image = Image(m_width, m_height);
        image.channels.resize(names.size());
        for (size_t i = 0; i < names.size(); ++i) {
            image.channels[i].name = names[i];
            image.channels[i].data.resize(n);  // every value is written below
        }
    }
    image.metadata.clear();
    image.chromaticities = Chromaticities{};

    // Channels in the order of `names`: R, G, B, A, then the chosen AOVs.
    float* out[17];
    for (size_t i = 0; i < names.size(); ++i)
        out[i] = image.channels[i].data.data();
    for (size_t i = 0; i < n; ++i) {
        const Pixel& p = m_pixels[i];
        size_t k = 0;
        for (int c = 0; c < 3; ++c)
            out[k++][i] = p.radiance[c];
        out[k++][i] = p.alpha;
        if ((aovs & kAovAlbedo) != 0) {
            for (int c = 0; c < 3; ++c)
                out[k++][i] = p.albedo[c];
        }
        if ((aovs & kAovDepth) != 0)
            out[k++][i] = p.depth;
        if ((aovs & kAovSurface) != 0) {
            for (int c = 0; c < 3; ++c)
                out[k++][i] = p.surface[c];
        }
        if ((aovs & kAovVolume) != 0) {
            for (int c = 0; c < 3; ++c)
                out[k++][i] = p.volume[c];
        }
        if ((aovs & kAovTransmittance) != 0) {
            for (int c = 0; c < 3; ++c)
                out[k++][i] = p.transmittance[c];
        }
    }
}

}  // namespace kasumi
