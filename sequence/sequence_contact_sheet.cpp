#include "sequence/sequence_contact_sheet.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

constexpr int kGap = 2;
constexpr const char* kRgb[3] = {"R", "G", "B"};

}  // namespace

Image make_thumbnail(const Image& image, int width) {
    KASUMI_CHECK(image.width > 0 && image.height > 0 && width > 0);
    const int tw = std::min(width, image.width);
    const int th = std::max(
        1, static_cast<int>(std::lround(static_cast<double>(image.height) * tw / image.width)));
    Image thumb(tw, th);
    for (const char* name : kRgb)
        thumb.add_channel(name);
    for (int c = 0; c < 3; ++c) {
        const ImageChannel* source = image.find(kRgb[c]);
        if (source == nullptr)
            throw Error(ErrorKind::Runtime,
                        std::string("thumbnail: the frame has no ") + kRgb[c] + " channel");
        std::vector<double> sum(static_cast<size_t>(tw) * th, 0.0);
        std::vector<int> count(sum.size(), 0);
        // Pixel (x, y) has its centre at x + 0.5; it lands in thumbnail column
        // floor((x + 0.5) tw / W), so every frame pixel counts exactly once.
        for (int y = 0; y < image.height; ++y) {
            const int ty = std::min(th - 1, static_cast<int>((y + 0.5) * th / image.height));
            for (int x = 0; x < image.width; ++x) {
                const int tx = std::min(tw - 1, static_cast<int>((x + 0.5) * tw / image.width));
                const size_t t = static_cast<size_t>(ty) * tw + tx;
                sum[t] += source->data[static_cast<size_t>(y) * image.width + x];
                ++count[t];
            }
        }
        std::vector<float>& out = thumb.channels[static_cast<size_t>(c)].data;
        for (size_t t = 0; t < sum.size(); ++t)
            out[t] = count[t] > 0 ? static_cast<float>(sum[t] / count[t]) : 0.0f;
    }
    return thumb;
}

Image make_contact_sheet(const std::vector<const Image*>& thumbnails) {
    int cw = 0, ch = 0;
    for (const Image* t : thumbnails) {
        if (t != nullptr) {
            cw = t->width;
            ch = t->height;
            break;
        }
    }
    const int n = static_cast<int>(thumbnails.size());
    if (cw == 0 || n == 0) {
        Image empty(1, 1);
        for (const char* name : kRgb)
            empty.add_channel(name);
        return empty;
    }
    // columns / rows ≈ (16/9) * ch / cw makes the sheet's aspect about 16:9.
    const double ratio = 16.0 / 9.0 * ch / cw;
    const int columns = std::clamp(static_cast<int>(std::ceil(std::sqrt(n * ratio))), 1, n);
    const int rows = (n + columns - 1) / columns;
    Image sheet(columns * (cw + kGap) + kGap, rows * (ch + kGap) + kGap);
    for (const char* name : kRgb)
        sheet.add_channel(name);
    for (int i = 0; i < n; ++i) {
        const Image* t = thumbnails[static_cast<size_t>(i)];
        if (t == nullptr)
            continue;
        const int x0 = kGap + (i % columns) * (cw + kGap), y0 = kGap + (i / columns) * (ch + kGap);
        for (int c = 0; c < 3; ++c) {
            const ImageChannel* source = t->find(kRgb[c]);
            std::vector<float>& out = sheet.channels[static_cast<size_t>(c)].data;
            for (int y = 0; y < std::min(ch, t->height); ++y) {
                for (int x = 0; x < std::min(cw, t->width); ++x) {
                    out[static_cast<size_t>(y0 + y) * sheet.width + x0 + x] =
                        source->data[static_cast<size_t>(y) * t->width + x];
                }
            }
        }
    }
    return sheet;
}

}  // namespace kasumi
