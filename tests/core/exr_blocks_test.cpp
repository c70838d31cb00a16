// Half-float EXR output written block by block (core/exr_io.cpp converts 64 rows at a time just
// before OpenEXR copies them, after the header): every value must still land in its own pixel,
// across block boundaries, a partial last block, every compression and float channels written
// beside the half ones; the header's saturation count must cover values in the last block,
// which are converted only after the header is written.
#include "core/exr_io.h"
#include "tests/scratch_dir.h"

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace kasumi {
namespace {

std::string string_attribute(const std::string& path, const std::string& name) {
    Imf::InputFile in(path.c_str());
    const auto* a = in.header().findTypedAttribute<Imf::StringAttribute>(name);
    return a ? a->value() : "<missing>";
}

TEST(ExrHalfBlocks, EveryPixelInItsPlaceAcrossBlocksForEveryCompression) {
    ScratchDir dir("kasumi_exr_blocks_");
    // 150 rows: blocks of 64, 64 and 22 rows; 29 columns (odd, no multiple of anything).
    const int width = 29, height = 150;
    const size_t n = static_cast<size_t>(width) * height;
    const char* names[] = {"R", "G", "B", "A"};
    std::vector<std::vector<float>> rgba(4, std::vector<float>(n));
    std::vector<float> depth(n);
    for (size_t i = 0; i < n; ++i) {
        // A distinct value per pixel and channel, exact in half (integers below 2048): a pixel
        // written to the wrong row or channel cannot match.
        for (int c = 0; c < 4; ++c)
            rgba[c][i] = static_cast<float>((i * 4 + static_cast<size_t>(c)) % 2039);
        depth[i] = 1000.0f + static_cast<float>(i) * 0.001f;  // float only
    }
    // In the last (partial) block: saturated, and counted in the header written before it.
    const size_t last = n - 3;
    rgba[1][last] = -1.0e6f;
    for (const ExrCompression compression :
         {ExrCompression::Zip, ExrCompression::Piz, ExrCompression::Rle, ExrCompression::None}) {
        SCOPED_TRACE(static_cast<int>(compression));
        std::vector<ExrChannelView> channels;
        for (int c = 0; c < 4; ++c)
            channels.push_back({names[c], rgba[c].data(), ExrPixelType::Half});
        channels.push_back({"depth.Z", depth.data(), ExrPixelType::Float});
        const std::string path = dir.file("blocks.exr");
        const ExrWriteReport report = write_exr(Image(width, height), channels, path, compression);
        EXPECT_EQ(report.half_saturated, 1u);
        EXPECT_EQ(report.half_max_abs, 1.0e6f);
        EXPECT_EQ(string_attribute(path, "kasumi/half/saturated"), "1");
        const Image back = read_exr(path);
        for (int c = 0; c < 4; ++c) {
            const ImageChannel* read = back.find(names[c]);
            ASSERT_NE(read, nullptr);
            for (size_t i = 0; i < n; ++i) {
                const float expected = i == last && c == 1 ? -kHalfMax : rgba[c][i];
                ASSERT_EQ(read->data[i], expected) << names[c] << " pixel " << i;
            }
        }
        ASSERT_NE(back.find("depth.Z"), nullptr);
        EXPECT_EQ(back.find("depth.Z")->data, depth);
    }
}

TEST(ExrHalfBlocks, RoundsEachValueAsImathDoesAtBlockEdges) {
    // Values that are not exact in half, on the rows around the block edges (63/64, 127/128)
    // and the last row: the file holds Imath's round-to-nearest of each.
    ScratchDir dir("kasumi_exr_blocks_");
    const int width = 5, height = 129;
    const size_t n = static_cast<size_t>(width) * height;
    std::vector<float> plane(n);
    for (size_t i = 0; i < n; ++i)
        plane[i] = 1.0f + static_cast<float>(i) * 1.2345e-4f;
    const std::string path = dir.file("edges.exr");
    write_exr(Image(width, height), {{"R", plane.data(), ExrPixelType::Half}}, path,
              ExrCompression::Zip);
    const Image back = read_exr(path);
    ASSERT_NE(back.find("R"), nullptr);
    for (const int row : {0, 63, 64, 127, 128})
        for (int x = 0; x < width; ++x) {
            const size_t i = static_cast<size_t>(row) * width + static_cast<size_t>(x);
            EXPECT_EQ(back.find("R")->data[i], static_cast<float>(Imath::half(plane[i])))
                << "row " << row << " x " << x;
        }
}

TEST(ExrHalfBlocks, SameFileWhateverTheCompressionThreads) {
    // threads 1 compresses on the calling thread (no OpenEXR pool), 0 and 2 in the pool: the
    // pixels read back must be the same, half and float channels, every block.
    ScratchDir dir("kasumi_exr_blocks_");
    const int width = 33, height = 200;
    const size_t n = static_cast<size_t>(width) * height;
    std::vector<float> r(n), z(n);
    for (size_t i = 0; i < n; ++i) {
        r[i] = std::sin(0.01f * static_cast<float>(i)) * 100.0f;
        z[i] = 1.0f + static_cast<float>(i) * 1e-3f;
    }
    std::vector<Image> back;
    for (const int threads : {1, 0, 2}) {
        const std::string path = dir.file("threads" + std::to_string(threads) + ".exr");
        write_exr(Image(width, height),
                  {{"R", r.data(), ExrPixelType::Half}, {"depth.Z", z.data(), ExrPixelType::Float}},
                  path, ExrCompression::Zip, threads);
        back.push_back(read_exr(path));
    }
    for (size_t k = 1; k < back.size(); ++k) {
        EXPECT_EQ(back[k].find("R")->data, back[0].find("R")->data);
        EXPECT_EQ(back[k].find("depth.Z")->data, z);
    }
    EXPECT_EQ(back[0].find("depth.Z")->data, z);
    EXPECT_NE(back[0].find("R")->data[150], 0.0f);
}

TEST(ExrHalfBlocks, EveryFloatBitPatternRoundsAsImathDoes) {
    // The writer converts with the F16C instruction where the CPU has it (8 at a time, the rest
    // one by one) and with Imath otherwise; this test's own Imath::half is Imath's software
    // rounding (the tests are not built for F16C). Random bit patterns over every exponent and
    // sign, plus the half range's edges, ties between two halves (odd and even) and values that
    // flush to zero: each must come back as Imath's half of the value (saturated past 65504).
    ScratchDir dir("kasumi_exr_blocks_");
    std::vector<float> values;
    std::mt19937 rng(2026);
    while (values.size() < 200000) {
        const uint32_t bits = rng();
        float v;
        std::memcpy(&v, &bits, sizeof v);
        if (std::isfinite(v))
            values.push_back(v);
    }
    for (const float v : {0.0f, -0.0f, 65504.0f, -65504.0f, 65519.0f, 65520.0f, 1.0e9f, 0x1p-24f,
                          0x1p-25f, 0x1.8p-25f, -0x1p-26f, 0x1p-14f, 0x1.ffcp-15f,
                          1.0f + 0x1p-11f,                     // tie: rounds to even (1)
                          1.0f + 3.0f * 0x1p-11f,              // tie: rounds to even (1 + 2^-9)
                          std::numeric_limits<float>::min()})  // normal float, flushed
        values.push_back(v);
    const int width = 7;  // 8-wide blocks straddle rows
    while (values.size() % width != 0)
        values.push_back(0.5f);
    const int height = static_cast<int>(values.size() / width);
    const std::string path = dir.file("bits.exr");
    const ExrWriteReport report =
        write_exr(Image(width, height), {{"R", values.data(), ExrPixelType::Half}}, path,
                  ExrCompression::Rle);
    const Image back = read_exr(path);
    ASSERT_NE(back.find("R"), nullptr);
    uint64_t saturated = 0, flushed = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        const float v = std::clamp(values[i], -kHalfMax, kHalfMax);
        saturated += v != values[i] ? 1u : 0u;
        const Imath::half expected(v);
        flushed += v != 0.0f && (expected.bits() & 0x7fffu) == 0 ? 1u : 0u;
        ASSERT_EQ(Imath::half(back.find("R")->data[i]).bits(), expected.bits())
            << "value " << values[i] << " (index " << i << ")";
    }
    EXPECT_GT(saturated, 1000u);  // random exponents: most are beyond the half range
    EXPECT_GT(flushed, 1000u);    // ... or below it
    EXPECT_EQ(report.half_saturated, saturated);
    EXPECT_EQ(report.half_flushed_to_zero, flushed);
}

}  // namespace
}  // namespace kasumi
