#include "core/png_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <zlib.h>

#include <cstdlib>
#include <limits>

namespace kasumi {
namespace {

constexpr int kBytesPerPixel = 3;

void append_u32_be(std::vector<uint8_t>& out, uint32_t v) {
    out.push_back(static_cast<uint8_t>(v >> 24));
    out.push_back(static_cast<uint8_t>(v >> 16));
    out.push_back(static_cast<uint8_t>(v >> 8));
    out.push_back(static_cast<uint8_t>(v));
}

/// Appends one chunk: length, type, data, CRC-32 of type and data (PNG spec section 5.3).
void append_chunk(std::vector<uint8_t>& out, const char type[4], const uint8_t* data, size_t size) {
    append_u32_be(out, static_cast<uint32_t>(size));
    const size_t type_at = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + size);
    const uLong crc = crc32_z(crc32(0L, Z_NULL, 0), out.data() + type_at, size + 4);
    append_u32_be(out, static_cast<uint32_t>(crc));
}

/// Paeth predictor (PNG spec section 9.4).
uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc)
        return static_cast<uint8_t>(a);
    return static_cast<uint8_t>(pb <= pc ? b : c);
}

/// Filters one row with filter `type` into `out` (without the filter byte). `prior` is the row
/// above, all zeros for the first row.
void filter_row(int type, const uint8_t* row, const uint8_t* prior, size_t n, uint8_t* out) {
    for (size_t i = 0; i < n; ++i) {
        const int a = i >= kBytesPerPixel ? row[i - kBytesPerPixel] : 0;
        const int b = prior[i];
        const int c = i >= kBytesPerPixel ? prior[i - kBytesPerPixel] : 0;
        int predictor = 0;
        switch (type) {
            case 1:
                predictor = a;
                break;
            case 2:
                predictor = b;
                break;
            case 3:
                predictor = (a + b) / 2;
                break;
            case 4:
                predictor = paeth(a, b, c);
                break;
            default:
                predictor = 0;
                break;
        }
        out[i] = static_cast<uint8_t>(row[i] - predictor);
    }
}

/// The filtered scanlines: per row one filter-type byte and the filtered bytes.
std::vector<uint8_t> filter_image(int width, int height, const std::vector<uint8_t>& rgb) {
    const size_t stride = static_cast<size_t>(width) * kBytesPerPixel;
    std::vector<uint8_t> filtered;
    filtered.reserve((stride + 1) * static_cast<size_t>(height));
    const std::vector<uint8_t> zero_row(stride, 0);
    std::vector<uint8_t> candidate(stride), best(stride);
    for (int y = 0; y < height; ++y) {
        const uint8_t* row = rgb.data() + static_cast<size_t>(y) * stride;
        const uint8_t* prior = y > 0 ? row - stride : zero_row.data();
        uint64_t best_cost = std::numeric_limits<uint64_t>::max();
        int best_type = 0;
        for (int type = 0; type <= 4; ++type) {
            filter_row(type, row, prior, stride, candidate.data());
            // Bytes read as signed: small residuals of either sign cost little.
            uint64_t cost = 0;
            for (uint8_t v : candidate)
                cost += static_cast<uint64_t>(std::abs(static_cast<int>(static_cast<int8_t>(v))));
            if (cost < best_cost) {
                best_cost = cost;
                best_type = type;
                best.swap(candidate);
            }
        }
        filtered.push_back(static_cast<uint8_t>(best_type));
        filtered.insert(filtered.end(), best.begin(), best.end());
    }
    return filtered;
}

/// The tEXt keyword rule of PNG spec section 11.3.4.3.
void check_text(const PngText& entry) {
    const std::string& k = entry.keyword;
    bool ok = !k.empty() && k.size() <= 79 && k.front() != ' ' && k.back() != ' ' &&
              k.find("  ") == std::string::npos;
    for (const char c : k) {
        const auto byte = static_cast<unsigned char>(c);
        ok = ok && ((byte >= 32 && byte <= 126) || byte >= 161);
    }
    if (!ok)
        throw Error(ErrorKind::Runtime, "encode_png_rgb8: \"" + k +
                                            "\" is not a PNG tEXt keyword (1 to 79 printable "
                                            "Latin-1 characters, no leading, trailing or double "
                                            "spaces)");
    if (entry.text.find('\0') != std::string::npos)
        throw Error(ErrorKind::Runtime,
                    "encode_png_rgb8: the text of \"" + k + "\" holds a NUL character");
}

}  // namespace

std::vector<uint8_t> encode_png_rgb8(int width, int height, const std::vector<uint8_t>& rgb,
                                     const std::vector<PngText>& text) {
    // PNG limits dimensions to 2^31 - 1; zlib's one-shot compress2 takes a uLong size.
    if (width <= 0 || height <= 0)
        throw Error(ErrorKind::Runtime, "encode_png_rgb8: empty image " + std::to_string(width) +
                                            "x" + std::to_string(height));
    const size_t expected = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
    if (rgb.size() != expected)
        throw Error(ErrorKind::Runtime, "encode_png_rgb8: " + std::to_string(rgb.size()) +
                                            " bytes for a " + std::to_string(width) + "x" +
                                            std::to_string(height) + " RGB image (expected " +
                                            std::to_string(expected) + ")");
    for (const PngText& entry : text)
        check_text(entry);

    const std::vector<uint8_t> filtered = filter_image(width, height, rgb);
    uLongf compressed_size = compressBound(static_cast<uLong>(filtered.size()));
    std::vector<uint8_t> compressed(compressed_size);
    const int status = compress2(compressed.data(), &compressed_size, filtered.data(),
                                 static_cast<uLong>(filtered.size()), Z_DEFAULT_COMPRESSION);
    if (status != Z_OK)
        throw Error(ErrorKind::Runtime,
                    "encode_png_rgb8: zlib compress2 failed with status " + std::to_string(status));

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<uint8_t> ihdr;
    append_u32_be(ihdr, static_cast<uint32_t>(width));
    append_u32_be(ihdr, static_cast<uint32_t>(height));
    // Bit depth 8, colour type 2 (truecolour), deflate, adaptive filtering, no interlace.
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
    append_chunk(png, "IHDR", ihdr.data(), ihdr.size());
    for (const PngText& entry : text) {
        std::vector<uint8_t> data(entry.keyword.begin(), entry.keyword.end());
        data.push_back(0);
        data.insert(data.end(), entry.text.begin(), entry.text.end());
        append_chunk(png, "tEXt", data.data(), data.size());
    }
    append_chunk(png, "IDAT", compressed.data(), compressed_size);
    append_chunk(png, "IEND", nullptr, 0);
    return png;
}

void write_png_rgb8(int width, int height, const std::vector<uint8_t>& rgb, const std::string& path,
                    const std::vector<PngText>& text) {
    const std::vector<uint8_t> png = encode_png_rgb8(width, height, rgb, text);
    write_file_atomic(path, png.data(), png.size());
}

}  // namespace kasumi
