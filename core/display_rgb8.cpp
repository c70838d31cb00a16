// display_rgb8 of color_management.h: compiled into the executable (calling the OpenColorIO
// module's apply_display_view through the loader) and into the module (for its
// write_preview_png), so previews and movie frames are quantised by the same code.
#include "core/color_management.h"
#include "core/error.h"

#include <cmath>

namespace kasumi {

namespace {

uint8_t quantise(float display_value) {
    // Clip to [0, 1] (NaN to 0), then round to nearest: 0.5/255 is the largest error.
    if (!(display_value > 0.0f))
        return 0;
    if (display_value >= 1.0f)
        return 255;
    return static_cast<uint8_t>(std::lround(display_value * 255.0f));
}

}  // namespace

std::vector<uint8_t> display_rgb8(const Image& image, const PreviewSettings& settings,
                                  const std::string& what) {
    const ImageChannel* r = image.find("R");
    const ImageChannel* g = image.find("G");
    const ImageChannel* b = image.find("B");
    if (!r || !g || !b)
        throw Error(ErrorKind::Runtime, what + ": the image needs R, G and B channels");
    const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
    std::vector<float> rgb(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) {
        rgb[3 * i + 0] = r->data[i];
        rgb[3 * i + 1] = g->data[i];
        rgb[3 * i + 2] = b->data[i];
    }
    apply_display_view(rgb, settings);
    std::vector<uint8_t> bytes(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i)
        bytes[i] = quantise(rgb[i]);
    return bytes;
}

}  // namespace kasumi
