// The OpenEXR module (libkasumi_exr.so, see exr_module.h): reading EXRs, and writing them with
// piz, rle or none compression, through OpenEXR's C++ library Imf.
#include "core/error.h"
#include "core/exr_half.h"
#include "core/exr_module.h"

#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

namespace kasumi {
namespace {

/// Threads OpenEXR compresses with (its global pool, sized once): one per hardware thread (a
/// 1280x720 image with its AOVs took one thread longer to compress than the fast sky takes to
/// render it).
int exr_threads() {
    static std::once_flag once;
    static int threads = 1;
    std::call_once(once, [] {
        threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
        Imf::setGlobalThreadCount(threads);
    });
    return threads;
}

/// OpenEXR's thread count for a write asked to use `threads` (0: every hardware thread): 1
/// compresses on the calling thread (0 for OpenEXR, and its pool is never started: a render
/// with --threads 1 no longer starts two compression threads, which for a 320x240 image cost
/// more CPU in start-up and hand-offs than they saved).
int exr_write_threads(int threads) {
    if (threads == 1)
        return 0;
    const int pool = exr_threads();
    return threads <= 0 ? pool : std::min(threads, pool);
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

/// The HALF channels of a write: their indices and what the header reports of them.
struct HalfPlanes {
    std::vector<size_t> channels;  ///< indices of the HALF channels
    ExrWriteReport report;
    bool any() const { return !channels.empty(); }
};

/// Rows converted per block: a multiple of ZIP's 16 scanlines (and PIZ's 32), 4 blocks of ZIP
/// so OpenEXR's threads compress them together; R, G, B, A of a 1280-pixel row: 640 KB a block.
constexpr int kHalfBlockRows = 64;

Imf::Header make_header(const Image& image, const std::vector<ExrChannelView>& channels,
                        ExrCompression compression, bool any_half, const ExrWriteReport& half) {
    Imf::Header header(image.width, image.height);
    header.compression() = imf_compression(compression);  // not ZIP: exr_io.cpp writes it
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
    for (const auto& kv : exr_string_attributes(image, any_half, half))
        header.insert(kv.first, Imf::StringAttribute(kv.second));
    return header;
}

/// ExrModuleApi::write: HALF channels converted a block of rows at a time, just before OpenEXR
/// copies them (the whole image converted first was 9.8 MB of fresh pages at 1280x960 R, G, B,
/// A, written once and read once: page faults and cache misses; a block stays in the cache).
void write_imf_exr(const Image& header_image, const std::vector<ExrChannelView>& channels,
                   const std::string& path, ExrCompression compression, int threads,
                   ExrWriteReport& report) {
    HalfPlanes half;
    for (size_t c = 0; c < channels.size(); ++c)
        if (channels[c].type == ExrPixelType::Half)
            half.channels.push_back(c);
    half.report = report;
    const Imf::Header header =
        make_header(header_image, channels, compression, half.any(), half.report);
    const size_t width = static_cast<size_t>(header_image.width);
    const int height = header_image.height;
    const int block_rows = std::min(kHalfBlockRows, height);
    const size_t block_values = width * static_cast<size_t>(block_rows);
    // One block of rows of every HALF channel, plane after plane (not cleared: each value
    // is written before OpenEXR reads it).
    std::unique_ptr<Imath::half[]> block(
        half.any() ? new Imath::half[half.channels.size() * block_values] : nullptr);
    // The frame buffer of rows [y0, y0 + block_rows): FLOAT channels read from the planes
    // themselves, HALF channels from the block, addressed as if it held the whole image
    // (OpenEXR reads row y at base + y * yStride; the base is offset back by y0 rows, as
    // Imf::Slice::Make does for data windows).
    const auto frame_buffer_at = [&](int y0) {
        Imf::FrameBuffer frame_buffer;
        size_t k = 0;
        for (const ExrChannelView& channel : channels) {
            // OpenEXR only reads through the slice; the const_cast is its API's, not a write.
            if (channel.type == ExrPixelType::Half) {
                const Imath::half* rows = block.get() + (k++) * block_values;
                char* base = reinterpret_cast<char*>(const_cast<Imath::half*>(rows)) -
                             static_cast<ptrdiff_t>(y0) *
                                 static_cast<ptrdiff_t>(sizeof(Imath::half) * width);
                frame_buffer.insert(channel.name, Imf::Slice(Imf::HALF, base, sizeof(Imath::half),
                                                             sizeof(Imath::half) * width));
            } else {
                char* base = reinterpret_cast<char*>(const_cast<float*>(channel.data));
                frame_buffer.insert(channel.name, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                                             sizeof(float) * width));
            }
        }
        return frame_buffer;
    };
    Imf::OutputFile out(path.c_str(), header, exr_write_threads(threads));
    if (!half.any()) {
        out.setFrameBuffer(frame_buffer_at(0));
        out.writePixels(height);
    } else {
        for (int y0 = 0; y0 < height; y0 += block_rows) {
            const int rows = std::min(block_rows, height - y0);
            const size_t first = static_cast<size_t>(y0) * width;
            for (size_t k = 0; k < half.channels.size(); ++k)
                convert_to_half(channels[half.channels[k]].data + first,
                                static_cast<size_t>(rows) * width, block.get() + k * block_values,
                                half.report);
            out.setFrameBuffer(frame_buffer_at(y0));
            out.writePixels(rows);
        }
    }
    report = half.report;
}

Image read_exr_imf(const std::string& path) {
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
            // "type" is the part's storage ("scanlineimage", which the core library writing our
            // ZIP files states), no metadata.
            if (!text || std::strcmp(it.name(), "type") == 0)
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

}  // namespace
}  // namespace kasumi

extern "C" __attribute__((visibility("default"))) const kasumi::ExrModuleApi*
kasumi_exr_module_api() {
    static const kasumi::ExrModuleApi api{kasumi::kExrModuleAbi, &kasumi::write_imf_exr,
                                          &kasumi::read_exr_imf};
    return &api;
}
