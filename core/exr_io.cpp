#include "core/exr_io.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/zeroed_allocator.h"

#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <half.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <mutex>
#include <set>
#include <thread>

namespace kasumi {
namespace {

void check_writable(const Image& header, const std::vector<ExrChannelView>& channels) {
    if (header.width <= 0 || header.height <= 0)
        throw Error(ErrorKind::Runtime, "write_exr: empty image " + std::to_string(header.width) +
                                            "x" + std::to_string(header.height));
    if (channels.empty())
        throw Error(ErrorKind::Runtime, "write_exr: image has no channels");
    const size_t pixels = static_cast<size_t>(header.width) * static_cast<size_t>(header.height);
    std::set<std::string> names;
    for (const ExrChannelView& channel : channels) {
        if (channel.name.empty() || !names.insert(channel.name).second)
            throw Error(ErrorKind::Runtime,
                        "write_exr: empty or repeated channel name '" + channel.name + "'");
        // The renderer guarantees finite pixels; this is the last guard before the file.
        for (size_t i = 0; i < pixels; ++i) {
            const float v = channel.data[i];
            if (!std::isfinite(v)) {
                const size_t x = i % static_cast<size_t>(header.width);
                const size_t y = i / static_cast<size_t>(header.width);
                throw Error(ErrorKind::Runtime, "write_exr: channel '" + channel.name +
                                                    "' pixel (" + std::to_string(x) + ", " +
                                                    std::to_string(y) + ") is " +
                                                    (std::isnan(v) ? "NaN" : "infinite") +
                                                    ": refusing to write a non-finite value");
            }
        }
    }
    for (const auto& kv : header.metadata) {
        if (kv.first.empty())
            throw Error(ErrorKind::Runtime, "write_exr: metadata with an empty key");
    }
}

/// Threads OpenEXR compresses with (its global pool, sized once): one per hardware thread. A
/// 1280x720 image with its AOVs is ~17 MB of ZIP-compressed scanlines; one thread takes longer
/// to compress it than the fast sky takes to render it.
int exr_threads() {
    static std::once_flag once;
    static int threads = 1;
    std::call_once(once, [] {
        threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
        Imf::setGlobalThreadCount(threads);
#if defined(__GLIBC__)
        // zlib allocates ~270 KB of deflate state for every compressed block and frees it
        // after; glibc's default trim threshold (128 KB) then returns the top of the arena to
        // the kernel each time (madvise, and in a VM a TLB shootdown on every core): 4% of the
        // CPU of a 640x480 soft-shadow render. Keep up to 64 MB of freed memory instead.
        mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
    });
    return threads;
}

Imf::Compression imf_compression(ExrCompression compression) {
    switch (compression) {
        case ExrCompression::Piz:
            return Imf::PIZ_COMPRESSION;
        case ExrCompression::Rle:
            return Imf::RLE_COMPRESSION;
        case ExrCompression::None:
            return Imf::NO_COMPRESSION;
        case ExrCompression::Zip:
            break;
    }
    return Imf::ZIP_COMPRESSION;
}

/// HALF channels converted before the file is opened: their values and what the conversion did.
struct HalfPlanes {
    /// Every HALF channel's plane, one after the other: fresh pages, not cleared first (each
    /// value is written once; a 1280x960 R, G, B, A is 9.8 MB, which a cleared std::vector
    /// wrote twice: 4% of a whole render's CPU).
    std::vector<Imath::half, ZeroedAllocator<Imath::half>> storage;
    std::vector<const Imath::half*> data;  ///< per channel; null for FLOAT channels
    ExrWriteReport report;
    bool any = false;
};

/// Rounds `n` floats to half (Imath: to nearest, ties to even), saturating |v| > 65504 to
/// +-65504 (Imath would give infinity from 65520 on) and counting what was saturated or
/// flushed to zero (see ExrPixelType).
void convert_to_half(const float* from, size_t n, Imath::half* to, ExrWriteReport& report) {
    for (size_t i = 0; i < n; ++i) {
        float v = from[i];
        const float magnitude = std::fabs(v);
        report.half_max_abs = std::max(report.half_max_abs, magnitude);
        if (magnitude > kHalfMax) {
            ++report.half_saturated;
            v = std::copysign(kHalfMax, v);
        }
        to[i] = Imath::half(v);
        if (v != 0.0f && (to[i].bits() & 0x7fffu) == 0)  // +-0 from a non-zero value
            ++report.half_flushed_to_zero;
    }
}

HalfPlanes convert_half_channels(const Image& header, const std::vector<ExrChannelView>& channels) {
    const size_t pixels = static_cast<size_t>(header.width) * static_cast<size_t>(header.height);
    HalfPlanes planes;
    planes.data.assign(channels.size(), nullptr);
    const size_t count = static_cast<size_t>(
        std::count_if(channels.begin(), channels.end(),
                      [](const ExrChannelView& c) { return c.type == ExrPixelType::Half; }));
    if (count == 0)
        return planes;
    planes.any = true;
    planes.storage.resize(count * pixels);
    Imath::half* next = planes.storage.data();
    for (size_t c = 0; c < channels.size(); ++c) {
        if (channels[c].type != ExrPixelType::Half)
            continue;
        convert_to_half(channels[c].data, pixels, next, planes.report);
        planes.data[c] = next;
        next += pixels;
    }
    return planes;
}

Imf::Header make_header(const Image& image, const std::vector<ExrChannelView>& channels,
                        ExrCompression compression, const HalfPlanes& half) {
    Imf::Header header(image.width, image.height);
    header.compression() = imf_compression(compression);
    // zlib level 1: on a 1280x720 render with its AOVs, 8% less write time than the default
    // level for a 3% larger file (float noise compresses little at any level).
    header.zipCompressionLevel() = 1;
    header.lineOrder() = Imf::INCREASING_Y;
    const Chromaticities& c = image.chromaticities;
    Imf::addChromaticities(
        header,
        Imf::Chromaticities(Imath::V2f(c.red_x, c.red_y), Imath::V2f(c.green_x, c.green_y),
                            Imath::V2f(c.blue_x, c.blue_y), Imath::V2f(c.white_x, c.white_y)));
    for (const ExrChannelView& channel : channels)
        header.channels().insert(
            channel.name,
            Imf::Channel(channel.type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT));
    for (const auto& kv : image.metadata)
        header.insert(kExrMetadataPrefix + kv.first, Imf::StringAttribute(kv.second));
    if (half.any) {
        // In the file itself: a reader sees whether values were saturated, and from what.
        char max_abs[32];
        std::snprintf(max_abs, sizeof max_abs, "%.9g",
                      static_cast<double>(half.report.half_max_abs));
        header.insert(std::string(kExrMetadataPrefix) + "half/saturated",
                      Imf::StringAttribute(std::to_string(half.report.half_saturated)));
        header.insert(std::string(kExrMetadataPrefix) + "half/max_abs",
                      Imf::StringAttribute(max_abs));
    }
    return header;
}

}  // namespace

bool parse_exr_compression(const std::string& text, ExrCompression& compression) {
    if (text == "zip")
        compression = ExrCompression::Zip;
    else if (text == "piz")
        compression = ExrCompression::Piz;
    else if (text == "rle")
        compression = ExrCompression::Rle;
    else if (text == "none")
        compression = ExrCompression::None;
    else
        return false;
    return true;
}

bool parse_exr_pixel_type(const std::string& text, ExrPixelType& type) {
    if (text == "float")
        type = ExrPixelType::Float;
    else if (text == "half")
        type = ExrPixelType::Half;
    else
        return false;
    return true;
}

const char* exr_pixel_type_name(ExrPixelType type) {
    return type == ExrPixelType::Half ? "half" : "float";
}

ExrWriteReport write_exr(const Image& image, const std::string& path, ExrCompression compression,
                         ExrPixelType beauty) {
    const size_t pixels = static_cast<size_t>(std::max(image.width, 0)) *
                          static_cast<size_t>(std::max(image.height, 0));
    std::vector<ExrChannelView> channels;
    channels.reserve(image.channels.size());
    for (const ImageChannel& channel : image.channels) {
        if (channel.data.size() != pixels)
            throw Error(ErrorKind::Runtime, "write_exr: channel '" + channel.name + "' has " +
                                                std::to_string(channel.data.size()) +
                                                " values for " + std::to_string(pixels) +
                                                " pixels");
        const bool is_beauty = channel.name == "R" || channel.name == "G" || channel.name == "B" ||
                               channel.name == "A";
        channels.push_back(
            {channel.name, channel.data.data(), is_beauty ? beauty : ExrPixelType::Float});
    }
    return write_exr(image, channels, path, compression);
}

ExrWriteReport write_exr(const Image& header_image, const std::vector<ExrChannelView>& channels,
                         const std::string& path, ExrCompression compression) {
    check_writable(header_image, channels);
    const HalfPlanes half = convert_half_channels(header_image, channels);
    AtomicFile file(path);
    try {
        const Imf::Header header = make_header(header_image, channels, compression, half);
        Imf::FrameBuffer frame_buffer;
        const size_t width = static_cast<size_t>(header_image.width);
        for (size_t c = 0; c < channels.size(); ++c) {
            const ExrChannelView& channel = channels[c];
            // OpenEXR only reads through the slice; the const_cast is its API's, not a write.
            if (channel.type == ExrPixelType::Half) {
                char* base = reinterpret_cast<char*>(const_cast<Imath::half*>(half.data[c]));
                frame_buffer.insert(channel.name, Imf::Slice(Imf::HALF, base, sizeof(Imath::half),
                                                             sizeof(Imath::half) * width));
            } else {
                char* base = reinterpret_cast<char*>(const_cast<float*>(channel.data));
                frame_buffer.insert(channel.name, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                                             sizeof(float) * width));
            }
        }
        Imf::OutputFile out(file.temp_path().c_str(), header, exr_threads());
        out.setFrameBuffer(frame_buffer);
        out.writePixels(header_image.height);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw_output_error(path + ": cannot write EXR: " + e.what());
    }
    file.commit();
    return half.report;
}

Image read_exr(const std::string& path) {
    try {
        Imf::InputFile in(path.c_str());
        const Imf::Header& header = in.header();
        const Imath::Box2i data_window = header.dataWindow();
        Image image(data_window.max.x - data_window.min.x + 1,
                    data_window.max.y - data_window.min.y + 1);
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
                throw_input_error(path + ": channel '" + it.name() +
                                  "' is subsampled, which is not supported");
            image.add_channel(it.name());
        }
        Imf::FrameBuffer frame_buffer;
        for (ImageChannel& channel : image.channels) {
            // Slice::Make offsets the base pointer by the data window's origin.
            frame_buffer.insert(channel.name,
                                Imf::Slice::Make(Imf::FLOAT, channel.data.data(), data_window));
        }
        in.setFrameBuffer(frame_buffer);
        in.readPixels(data_window.min.y, data_window.max.y);

        if (Imf::hasChromaticities(header)) {
            const Imf::Chromaticities& c = Imf::chromaticities(header);
            image.chromaticities = Chromaticities{c.red.x,  c.red.y,  c.green.x, c.green.y,
                                                  c.blue.x, c.blue.y, c.white.x, c.white.y};
        }
        const size_t prefix_length = std::strlen(kExrMetadataPrefix);
        for (auto it = header.begin(); it != header.end(); ++it) {
            const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute());
            if (!text)
                continue;
            std::string key = it.name();
            if (key.compare(0, prefix_length, kExrMetadataPrefix) == 0)
                key = key.substr(prefix_length);
            image.metadata.emplace_back(key, text->value());
        }
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw_input_error(path + ": cannot read EXR: " + e.what());
    }
}

}  // namespace kasumi
