// ZIP EXRs are written by core/exr_io.cpp itself (packing, OpenEXR's byte pre-pass, zlib level
// 1) through OpenEXR's core C library, not by Imf::OutputFile. Each chunk must hold exactly the
// bytes Imf::OutputFile writes at that level (any EXR reader decodes them the same way), an
// incompressible chunk must be stored raw, and every pixel must read back bit-identical, half and
// float channels alike, whatever the thread count.
#include "core/exr_io.h"
#include "tests/scratch_dir.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <half.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace kasumi {
namespace {

/// The raw chunk (as stored: compressed or not) starting at scanline `y`.
std::vector<char> raw_chunk(Imf::InputFile& in, int y) {
    const char* data = nullptr;
    int size = 0;
    in.rawPixelData(y, data, size);
    return std::vector<char>(data, data + size);
}

/// A test image: a smooth half channel R, an incompressible float channel (random bits of
/// finite floats) on the rows from `noise_from` on, a constant (zero) float channel.
struct Planes {
    std::vector<float> r, noise, zero;
};

Planes make_planes(int width, int height, int noise_from) {
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    Planes p{std::vector<float>(n), std::vector<float>(n, 0.5f), std::vector<float>(n, 0.0f)};
    std::mt19937 rng(19);
    for (size_t i = 0; i < n; ++i) {
        p.r[i] = 3.0f * std::sin(0.002f * static_cast<float>(i));
        if (i >= static_cast<size_t>(noise_from) * static_cast<size_t>(width)) {
            const uint32_t bits = (rng() & 0x3fffffffu) | 0x3f000000u;  // finite, in [0.5, 2)
            std::memcpy(&p.noise[i], &bits, sizeof bits);
        }
    }
    return p;
}

std::vector<ExrChannelView> views(const Planes& p) {
    return {{"R", p.r.data(), ExrPixelType::Half},
            {"noise.Y", p.noise.data(), ExrPixelType::Float},
            {"zero.Y", p.zero.data(), ExrPixelType::Float}};
}

/// The same channels written by Imf::OutputFile, ZIP at zlib level 1.
void write_with_imf(const std::vector<ExrChannelView>& channels, int width, int height,
                    const std::string& path) {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = 1;
    const size_t w = static_cast<size_t>(width), n = w * static_cast<size_t>(height);
    std::vector<std::vector<Imath::half>> halves;
    halves.reserve(channels.size());
    Imf::FrameBuffer frame;
    for (const ExrChannelView& c : channels) {
        if (c.type == ExrPixelType::Half) {
            halves.emplace_back(c.data, c.data + n);
            header.channels().insert(c.name, Imf::Channel(Imf::HALF));
            frame.insert(
                c.name,
                Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.back().data()), 2, 2 * w));
        } else {
            // OpenEXR only reads through the slice.
            header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
            frame.insert(c.name,
                         Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(c.data)),
                                    4, 4 * w));
        }
    }
    Imf::OutputFile out(path.c_str(), header, 0);
    out.setFrameBuffer(frame);
    out.writePixels(height);
}

TEST(ExrZip, ChunksAreTheBytesOpenExrWrites) {
    ScratchDir dir("kasumi_exr_zip_");
    // 75 rows: four full chunks of 16 and a partial one of 11. The noise from row 40 on makes
    // the chunks from the third on less compressible; alone it makes them incompressible, which
    // the format stores raw.
    const int width = 37, height = 75;
    const Planes planes = make_planes(width, height, 40);
    const std::vector<ExrChannelView> noise_alone = {
        {"noise.Y", planes.noise.data(), ExrPixelType::Float}};
    for (const std::vector<ExrChannelView>& channels : {views(planes), noise_alone}) {
        SCOPED_TRACE(channels.size());
        const std::string ours = dir.file("ours.exr"), theirs = dir.file("theirs.exr");
        write_exr(Image(width, height), channels, ours, ExrCompression::Zip, 1);
        write_with_imf(channels, width, height, theirs);
        Imf::InputFile a(ours.c_str()), b(theirs.c_str());
        EXPECT_EQ(a.header().compression(), Imf::ZIP_COMPRESSION);
        size_t row_bytes = 0;
        for (const ExrChannelView& c : channels)
            row_bytes += static_cast<size_t>(width) * (c.type == ExrPixelType::Half ? 2 : 4);
        for (int y = 0; y < height; y += 16) {
            SCOPED_TRACE(y);
            const std::vector<char> chunk = raw_chunk(a, y);
            EXPECT_EQ(chunk, raw_chunk(b, y));
            if (y == 0) {
                EXPECT_LT(chunk.size(), row_bytes * 16 / 4);  // smooth and constant: compressed
            }
            if (y == 48) {
                if (channels.size() == 1) {
                    EXPECT_EQ(chunk.size(), row_bytes * 16);  // noise alone: stored raw
                } else {
                    EXPECT_LT(chunk.size(), row_bytes * 16);
                }
            }
        }
    }
}

TEST(ExrZip, PixelsReadBackBitIdenticalForAnyThreadCount) {
    ScratchDir dir("kasumi_exr_zip_");
    // Over 2 MiB of raw data, so 2 threads compress it (at least 1 MiB each).
    const int width = 301, height = 1000;
    const Planes planes = make_planes(width, height, 500);
    for (const int threads : {1, 2, 0}) {
        SCOPED_TRACE(threads);
        const std::string path = dir.file("t" + std::to_string(threads) + ".exr");
        write_exr(Image(width, height), views(planes), path, ExrCompression::Zip, threads);
        const Image back = read_exr(path);
        ASSERT_NE(back.find("R"), nullptr);
        ASSERT_NE(back.find("noise.Y"), nullptr);
        ASSERT_NE(back.find("zero.Y"), nullptr);
        EXPECT_EQ(back.find("noise.Y")->data, planes.noise);
        EXPECT_EQ(back.find("zero.Y")->data, planes.zero);
        for (size_t i = 0; i < planes.r.size(); ++i)
            ASSERT_EQ(back.find("R")->data[i], static_cast<float>(Imath::half(planes.r[i])))
                << "pixel " << i;
    }
}

}  // namespace
}  // namespace kasumi
