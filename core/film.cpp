#include "core/film.h"

#include "core/error.h"

namespace kasumi {

Film::Film(int width, int height)
    : m_width(width), m_height(height), m_pixels(static_cast<size_t>(width) * height) {}

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
    Image image(m_width, m_height);
    // Pointers into image.channels are taken below: no reallocation may move them.
    image.channels.reserve(17);
    const char* rgb[3] = {"R", "G", "B"};
    ImageChannel* beauty[3];
    ImageChannel* surface[3];
    ImageChannel* volume[3];
    ImageChannel* transmittance[3];
    ImageChannel* albedo[3];
    for (int c = 0; c < 3; ++c)
        beauty[c] = &image.add_channel(rgb[c]);
    ImageChannel& alpha = image.add_channel("A");
    for (int c = 0; c < 3; ++c)
        albedo[c] = &image.add_channel(std::string("albedo.") + rgb[c]);
    ImageChannel& depth = image.add_channel("depth.Z");
    for (int c = 0; c < 3; ++c)
        surface[c] = &image.add_channel(std::string("surface.") + rgb[c]);
    for (int c = 0; c < 3; ++c)
        volume[c] = &image.add_channel(std::string("volume.") + rgb[c]);
    for (int c = 0; c < 3; ++c) {
        transmittance[c] = &image.add_channel(std::string("transmittance.") + rgb[c]);
    }
    KASUMI_CHECK(image.channels.size() == 17);  // the reserve above held
    for (size_t i = 0; i < m_pixels.size(); ++i) {
        const Pixel& p = m_pixels[i];
        for (int c = 0; c < 3; ++c) {
            beauty[c]->data[i] = p.radiance[c];
            surface[c]->data[i] = p.surface[c];
            volume[c]->data[i] = p.volume[c];
            transmittance[c]->data[i] = p.transmittance[c];
            albedo[c]->data[i] = p.albedo[c];
        }
        alpha.data[i] = p.alpha;
        depth.data[i] = p.depth;
    }
    return image;
}

}  // namespace kasumi
