#include "core/exr_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

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
#include <cmath>
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

Imf::Header make_header(const Image& image, const std::vector<ExrChannelView>& channels,
                        ExrCompression compression) {
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
        header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
    for (const auto& kv : image.metadata)
        header.insert(kExrMetadataPrefix + kv.first, Imf::StringAttribute(kv.second));
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

void write_exr(const Image& image, const std::string& path, ExrCompression compression) {
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
        channels.push_back({channel.name, channel.data.data()});
    }
    write_exr(image, channels, path, compression);
}

void write_exr(const Image& header_image, const std::vector<ExrChannelView>& channels,
               const std::string& path, ExrCompression compression) {
    check_writable(header_image, channels);
    AtomicFile file(path);
    try {
        const Imf::Header header = make_header(header_image, channels, compression);
        Imf::FrameBuffer frame_buffer;
        const size_t x_stride = sizeof(float);
        const size_t y_stride = sizeof(float) * static_cast<size_t>(header_image.width);
        for (const ExrChannelView& channel : channels) {
            // OpenEXR only reads through the slice; the const_cast is its API's, not a write.
            char* base = reinterpret_cast<char*>(const_cast<float*>(channel.data));
            frame_buffer.insert(channel.name, Imf::Slice(Imf::FLOAT, base, x_stride, y_stride));
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
