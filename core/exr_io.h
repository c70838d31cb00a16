#pragma once
/// OpenEXR output and input of an Image (OpenEXR headers stay in exr_io.cpp).
///
/// Files are single-part scanline EXRs, ZIP-compressed unless told otherwise, one FLOAT channel per
/// image channel under the channel's own name ("R", "albedo.R", "depth.Z", ...), with the standard
/// `chromaticities` attribute. Each metadata pair (key, value) is a string attribute named
/// "kasumi/<key>" (the prefix keeps our keys apart from the standard attributes).
#include "core/image.h"

#include <string>
#include <vector>

namespace kasumi {

/// Prefix of the EXR attribute names that hold Image::metadata.
inline constexpr const char* kExrMetadataPrefix = "kasumi/";

/// Lossless compressions of the written EXR. Measured on a 1280x720 sunset frame with every AOV
/// (62.7 MB of floats), one thread, CPU time: zip (zlib level 1, the default) 0.75 s, 17.7 MB;
/// piz 0.97 s, 19.6 MB; rle 0.15 s, 45 MB; none 0.04 s, 62.7 MB (docs/sequences.md).
enum class ExrCompression { Zip, Piz, Rle, None };

/// Parses "zip", "piz", "rle" or "none"; returns false otherwise.
bool parse_exr_compression(const std::string& text, ExrCompression& compression);

/// Writes `image` to `path` atomically (a temporary beside it, then a rename): never a
/// half-written file. Throws ErrorKind::Runtime, before touching the disk, if a channel holds a
/// NaN or an infinity (naming channel and pixel) or has the wrong size; ErrorKind::Output naming
/// `path` if it cannot be written (no file is left behind).
void write_exr(const Image& image, const std::string& path,
               ExrCompression compression = ExrCompression::Zip);

/// A channel plane to write, borrowed: width * height floats, top row first.
struct ExrChannelView {
    std::string name;
    const float* data = nullptr;
};

/// write_exr from borrowed planes (no copy of the pixels: the renderer writes its film's planes
/// directly); `header` gives size, metadata and chromaticities, its own channels are ignored.
/// Same checks, errors and atomicity as write_exr(Image).
void write_exr(const Image& header, const std::vector<ExrChannelView>& channels,
               const std::string& path, ExrCompression compression = ExrCompression::Zip);

/// Reads every channel of `path` as float (top row first) and its string attributes: those named
/// "kasumi/<key>" become metadata <key>, other string attributes keep their full name. Missing
/// chromaticities read as Rec.709. Throws ErrorKind::Input naming `path` on failure.
Image read_exr(const std::string& path);

}  // namespace kasumi
