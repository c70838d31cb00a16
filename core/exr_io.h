#pragma once
/// OpenEXR output and input of an Image (OpenEXR headers stay in exr_io.cpp).
///
/// Files are single-part scanline EXRs, ZIP-compressed unless told otherwise, one FLOAT (or, on
/// request, HALF: ExrPixelType) channel per image channel under the channel's own name ("R",
/// "albedo.R", "depth.Z", ...), with the standard `chromaticities` attribute. Each metadata pair
/// (key, value) is a string attribute named "kasumi/<key>" (the prefix keeps our keys apart from
/// the standard attributes).
#include "core/image.h"

#include <cstdint>
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

/// Pixel type of a written channel. HALF (IEEE 754 binary16, OpenEXR's `half`) keeps 11
/// significant bits: a value v in the normal range [2^-14, 65504] is stored within
/// 2^-11 |v| (0.049%); below 2^-14 (6.1e-5) the step is a fixed 2^-24 (6e-8), and values under
/// 2^-25 become 0. Values beyond the half range, |v| > 65504 (e.g. the sun's disc, ~1.6e9 cd/m²),
/// are SATURATED to +-65504, never written as infinity: write_exr counts them and records the
/// count and the largest |value| of the half channels in the file (attributes
/// "kasumi/half/saturated", "kasumi/half/max_abs"); callers warn (kasumi render prints a
/// warning and the count in -v). Use FLOAT to keep them.
enum class ExrPixelType { Float, Half };

/// The largest finite half, 65504 = (2 - 2^-10) 2^15.
inline constexpr float kHalfMax = 65504.0f;

/// Parses "float" or "half"; returns false otherwise.
bool parse_exr_pixel_type(const std::string& text, ExrPixelType& type);

/// "float" or "half".
const char* exr_pixel_type_name(ExrPixelType type);

/// What write_exr did to the HALF channels (all zero when every channel is FLOAT).
struct ExrWriteReport {
    uint64_t half_saturated = 0;        ///< values with |v| > 65504, written as +-65504
    uint64_t half_flushed_to_zero = 0;  ///< non-zero values with |v| < 2^-25, written as 0
    float half_max_abs = 0.0f;          ///< the largest |v| given for the HALF channels
};

/// Writes `image` to `path` atomically (a temporary beside it, then a rename): never a
/// half-written file. Throws ErrorKind::Runtime, before touching the disk, if a channel holds a
/// NaN or an infinity (naming channel and pixel) or has the wrong size; ErrorKind::Output naming
/// `path` if it cannot be written (no file is left behind). The beauty channels "R", "G", "B"
/// and "A" are written as `beauty`, every other channel (AOVs: depth in metres exceeds the half
/// range) as FLOAT.
ExrWriteReport write_exr(const Image& image, const std::string& path,
                         ExrCompression compression = ExrCompression::Zip,
                         ExrPixelType beauty = ExrPixelType::Float);

/// A channel plane to write, borrowed: width * height floats, top row first, written as `type`.
struct ExrChannelView {
    std::string name;
    const float* data = nullptr;
    ExrPixelType type = ExrPixelType::Float;
};

/// write_exr from borrowed planes (no copy of the pixels: the renderer writes its film's planes
/// directly; HALF channels are converted a block of rows at a time); `header` gives size,
/// metadata and chromaticities, its own channels are ignored. Same checks, errors and
/// atomicity as write_exr(Image). `threads`: how many threads compress (0: one per hardware
/// thread; 1: the calling thread alone, no pool started), the renderer passes its own count.
ExrWriteReport write_exr(const Image& header, const std::vector<ExrChannelView>& channels,
                         const std::string& path, ExrCompression compression = ExrCompression::Zip,
                         int threads = 0);

/// Reads every channel of `path` as float (HALF channels converted exactly) (top row first) and its
/// string attributes: those named "kasumi/<key>" become metadata <key>, other string attributes
/// keep their full name, except the part's "type" (its storage, not metadata). Missing
/// chromaticities read as Rec.709. Throws ErrorKind::Input naming `path` on failure.
Image read_exr(const std::string& path);

}  // namespace kasumi
