#include "core/film.h"

#include "core/error.h"

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
            aovs |= kAovAll | kAovSamples | kAovNoisy;
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
        else if (name == "samples")
            aovs |= kAovSamples;
        else if (name == "noisy")
            aovs |= kAovNoisy;
        else
            return false;
    }
    return any;
}

std::vector<Film::Storage>& Film::kept_storage() {
    static std::vector<Storage> kept;
    return kept;
}

namespace {

/// The AOVs in channel order: bit, channels, name prefix, name of a single channel.
struct AovLayout {
    uint32_t bit;
    int channels;
    const char* prefix;
    const char* single;
};
constexpr int kAovKinds = 7;
constexpr AovLayout kAovLayout[kAovKinds] = {{kAovAlbedo, 3, "albedo.", ""},
                                             {kAovDepth, 1, "depth.", "Z"},
                                             {kAovSurface, 3, "surface.", ""},
                                             {kAovVolume, 3, "volume.", ""},
                                             {kAovTransmittance, 3, "transmittance.", ""},
                                             {kAovSamples, 1, "samples.", "count"},
                                             {kAovNoisy, 3, "noisy.", ""}};

int channel_count(uint32_t aovs) {
    int n = 4;
    for (const AovLayout& a : kAovLayout)
        n += (aovs & a.bit) != 0 ? a.channels : 0;
    return n;
}

}  // namespace

Film::Film(int width, int height, uint32_t aovs)
    : m_width(width),
      m_height(height),
      m_aovs(aovs & (kAovAll | kAovSamples | kAovNoisy)),
      m_pixels(static_cast<size_t>(width) * static_cast<size_t>(height)) {
    int next = 4;
    for (int k = 0; k < kAovKinds; ++k) {
        m_first[k] = (m_aovs & kAovLayout[k].bit) != 0 ? next : -1;
        next += m_first[k] >= 0 ? kAovLayout[k].channels : 0;
    }
    const size_t size = static_cast<size_t>(next) * m_pixels;
    if (m_pixels >= kKeepMinPixels) {
        std::lock_guard<std::mutex> lock(kept_mutex());
        auto& kept = kept_storage();
        for (auto it = kept.begin(); it != kept.end(); ++it) {
            if (it->size() == size) {
                m_planes = std::move(*it);
                kept.erase(it);
                break;
            }
        }
    }
    if (m_planes.size() == size)
        std::fill(m_planes.begin(), m_planes.end(), 0.0f);  // recycled: written by the last film
    else
        m_planes.resize(size);  // new: zeros from calloc, no fill (ZeroedAllocator)
    if (m_first[4] >= 0)        // empty pixels: transmittance 1
        std::fill(plane(m_first[4]), plane(m_first[4] + 3), 1.0f);
}

Film::~Film() {
    if (m_pixels < kKeepMinPixels)
        return;
    try {
        std::lock_guard<std::mutex> lock(kept_mutex());
        auto& kept = kept_storage();
        if (kept.size() >= kKeepFilms)
            kept.erase(kept.begin());  // keep the newest sizes
        kept.push_back(std::move(m_planes));
    } catch (...) {
        // Keeping is an optimisation: if it fails, the storage is simply freed.
    }
}

void Film::set_pixel(int x, int y, const PixelSample& sum, int n, int hits, float depth_sum) {
    const size_t i = static_cast<size_t>(y) * static_cast<size_t>(m_width) + static_cast<size_t>(x);
    const float inv = 1.0f / static_cast<float>(n);
    const Rgb transmittance = sum.transmittance * inv;
    const auto put3 = [&](int first, const Rgb& v) {
        for (int c = 0; c < 3; ++c)
            plane(first + c)[i] = v[c] * inv;
    };
    put3(0, sum.radiance);
    // Samples that hit are opaque; the others are as opaque as the media in front of the sky.
    const float hit_fraction = static_cast<float>(hits) * inv;
    const float miss_opacity = (1.0f - hit_fraction) > 0.0f
                                   ? std::clamp(1.0f - luminance(transmittance), 0.0f, 1.0f)
                                   : 0.0f;
    plane(3)[i] = hit_fraction + (1.0f - hit_fraction) * miss_opacity;
    if (m_first[0] >= 0)
        put3(m_first[0], sum.albedo);
    if (m_first[1] >= 0)
        plane(m_first[1])[i] = hits > 0 ? depth_sum / static_cast<float>(hits) : 0.0f;
    if (m_first[2] >= 0)
        put3(m_first[2], sum.surface);
    if (m_first[3] >= 0)
        put3(m_first[3], sum.volume);
    if (m_first[4] >= 0)
        put3(m_first[4], sum.transmittance);
    if (m_first[5] >= 0)
        plane(m_first[5])[i] = static_cast<float>(n);
}

void Film::replace_beauty(const float* const rgb[3]) {
    for (int c = 0; c < 3; ++c) {
        if (m_first[6] >= 0)
            std::copy(plane(c), plane(c) + m_pixels, plane(m_first[6] + c));
        std::copy(rgb[c], rgb[c] + m_pixels, plane(c));
    }
}

Image Film::to_image() const {
    Image image;
    to_image(image, m_aovs);
    return image;
}

std::vector<FilmPlane> Film::planes(uint32_t aovs) const {
    aovs &= m_aovs;  // only stored AOVs can be read out
    const char* rgba[4] = {"R", "G", "B", "A"};
    std::vector<FilmPlane> planes;
    planes.reserve(static_cast<size_t>(channel_count(aovs)));
    for (int c = 0; c < 4; ++c)
        planes.push_back({rgba[c], plane(c)});
    for (int k = 0; k < kAovKinds; ++k) {
        if ((aovs & kAovLayout[k].bit) == 0)
            continue;
        for (int c = 0; c < kAovLayout[k].channels; ++c) {
            planes.push_back({std::string(kAovLayout[k].prefix) +
                                  (kAovLayout[k].channels == 1 ? kAovLayout[k].single : rgba[c]),
                              plane(m_first[k] + c)});
        }
    }
    return planes;
}

void Film::to_image(Image& image, uint32_t aovs) const {
    const std::vector<FilmPlane> from = planes(aovs);
    bool reusable =
        image.width == m_width && image.height == m_height && image.channels.size() == from.size();
    for (size_t i = 0; reusable && i < from.size(); ++i)
        reusable =
            image.channels[i].name == from[i].name && image.channels[i].data.size() == m_pixels;
    if (!reusable) {
        image = Image(m_width, m_height);
        image.channels.resize(from.size());
        for (size_t i = 0; i < from.size(); ++i)
            image.channels[i].name = from[i].name;
    }
    for (size_t i = 0; i < from.size(); ++i)  // no reallocation when reused
        image.channels[i].data.assign(from[i].data, from[i].data + m_pixels);
    image.metadata.clear();
    image.chromaticities = Chromaticities{};
}

}  // namespace kasumi
