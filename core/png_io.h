#pragma once
/// A small PNG encoder on zlib (ISO/IEC 15948, PNG 1.2): 8-bit RGB, non-interlaced.
#include <cstdint>
#include <string>
#include <vector>

namespace kasumi {

/// One tEXt chunk (PNG spec section 11.3.4.3): a keyword of 1 to 79 printable Latin-1
/// characters (no leading, trailing or double spaces) and its text (no NUL).
struct PngText {
    std::string keyword;
    std::string text;
};

/// Encodes an 8-bit RGB image (`rgb` holds width * height * 3 bytes, row-major, top row first)
/// as a PNG file in memory: signature, IHDR, a tEXt per `text` entry, one IDAT, IEND. Each row
/// takes the filter (None, Sub, Up, Average, Paeth) with the smallest sum of absolute filtered
/// bytes, the heuristic of PNG spec section 12.8. Throws ErrorKind::Runtime on bad sizes or a
/// keyword or text the spec forbids.
std::vector<uint8_t> encode_png_rgb8(int width, int height, const std::vector<uint8_t>& rgb,
                                     const std::vector<PngText>& text = {});

/// Writes encode_png_rgb8(...) to `path` atomically (temporary beside it, then rename).
/// Throws ErrorKind::Output naming `path` if it cannot be written; no file is left behind.
void write_png_rgb8(int width, int height, const std::vector<uint8_t>& rgb, const std::string& path,
                    const std::vector<PngText>& text = {});

}  // namespace kasumi
