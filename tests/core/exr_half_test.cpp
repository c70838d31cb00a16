// Half-float EXR output (core/exr_io.h, ExrPixelType::Half): the pixel type in the file as
// OpenEXR reads it, rounding to nearest within half's spacing, the overflow policy (saturate to
// 65504 and count, never infinity), non-finite values still refused, atomic writes.
#include "core/error.h"
#include "core/exr_io.h"
#include "tests/input_error.h"
#include "tests/scratch_dir.h"

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace kasumi {
namespace {

namespace fs = std::filesystem;

/// Channel name -> pixel type as OpenEXR itself reads the file's header.
std::map<std::string, Imf::PixelType> channel_types(const std::string& path) {
    Imf::InputFile in(path.c_str());
    std::map<std::string, Imf::PixelType> types;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
        types[it.name()] = it.channel().type;
    return types;
}

std::string string_attribute(const std::string& path, const std::string& name) {
    Imf::InputFile in(path.c_str());
    const auto* a = in.header().findTypedAttribute<Imf::StringAttribute>(name);
    return a ? a->value() : "<missing>";
}

/// Spacing of binary16 values around v (IEEE 754-2008: 10 stored significand bits, exponents
/// -14..15): 2^(e - 10) for 2^e <= |v| < 2^(e+1), e >= -14; 2^-24 in the subnormal range.
double half_spacing(double v) {
    const double a = std::fabs(v);
    if (a < std::ldexp(1.0, -14))
        return std::ldexp(1.0, -24);
    return std::ldexp(1.0, std::ilogb(a) - 10);
}

Image header_of(int width, int height) {
    return Image(width, height);
}

TEST(ExrHalf, ParsesPixelTypes) {
    ExrPixelType t = ExrPixelType::Float;
    EXPECT_TRUE(parse_exr_pixel_type("half", t));
    EXPECT_EQ(t, ExrPixelType::Half);
    EXPECT_TRUE(parse_exr_pixel_type("float", t));
    EXPECT_EQ(t, ExrPixelType::Float);
    EXPECT_FALSE(parse_exr_pixel_type("HALF", t));
    EXPECT_FALSE(parse_exr_pixel_type("double", t));
    EXPECT_FALSE(parse_exr_pixel_type("", t));
    EXPECT_STREQ(exr_pixel_type_name(ExrPixelType::Half), "half");
    EXPECT_STREQ(exr_pixel_type_name(ExrPixelType::Float), "float");
}

TEST(ExrHalf, RoundTripIsHalfInTheFileAndRoundsToNearest) {
    // Log-uniform magnitudes over the whole half range (subnormals 2^-24 .. normal 65504), both
    // signs, in a size that is not a multiple of ZIP's 16-line blocks; an AOV that stays float.
    ScratchDir dir("kasumi_exr_half_");
    const int width = 61, height = 37;
    const size_t n = static_cast<size_t>(width) * height;
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> exponent(-24.0, std::log2(65504.0));
    std::vector<std::vector<float>> rgba(4, std::vector<float>(n));
    for (auto& plane : rgba) {
        for (size_t i = 0; i < n; ++i)
            plane[i] = static_cast<float>((i % 2 ? -1.0 : 1.0) * std::exp2(exponent(rng)));
    }
    rgba[0][0] = 65504.0f;  // the largest half: exact, not saturated
    rgba[1][0] = 0.0f;
    rgba[2][0] = 1.0f;
    std::vector<float> depth(n, 1.0e6f);  // beyond half's range: must stay float, exact
    depth[5] = 123456.789f;

    const char* names[] = {"R", "G", "B", "A"};
    std::vector<ExrChannelView> channels;
    for (int c = 0; c < 4; ++c)
        channels.push_back({names[c], rgba[c].data(), ExrPixelType::Half});
    channels.push_back({"depth.Z", depth.data(), ExrPixelType::Float});
    const std::string path = dir.file("half.exr");
    const ExrWriteReport report =
        write_exr(header_of(width, height), channels, path, ExrCompression::Zip);
    EXPECT_EQ(report.half_saturated, 0u);
    EXPECT_EQ(report.half_flushed_to_zero, 0u);  // nothing below 2^-24 was given
    EXPECT_EQ(report.half_max_abs, 65504.0f);

    const auto types = channel_types(path);
    ASSERT_EQ(types.size(), 5u);
    for (const char* name : names)
        EXPECT_EQ(types.at(name), Imf::HALF) << name;
    EXPECT_EQ(types.at("depth.Z"), Imf::FLOAT);
    EXPECT_EQ(string_attribute(path, "kasumi/half/saturated"), "0");

    const Image back = read_exr(path);
    for (int c = 0; c < 4; ++c) {
        const ImageChannel* read = back.find(names[c]);
        ASSERT_NE(read, nullptr);
        for (size_t i = 0; i < n; ++i) {
            const double v = rgba[c][i];
            const double got = read->data[i];
            // Round to nearest: within half a spacing of the value given.
            ASSERT_LE(std::fabs(got - v), 0.5 * half_spacing(v))
                << names[c] << " pixel " << i << ": " << v << " -> " << got;
            // Relative: 2^-11 in the normal range.
            if (std::fabs(v) >= std::ldexp(1.0, -14)) {
                ASSERT_LE(std::fabs(got - v), std::ldexp(std::fabs(v), -11));
            }
        }
    }
    EXPECT_EQ(back.find("R")->data[0], 65504.0f);
    EXPECT_EQ(back.find("G")->data[0], 0.0f);
    EXPECT_EQ(back.find("B")->data[0], 1.0f);
    EXPECT_EQ(back.find("depth.Z")->data, depth);  // float: bit-exact
}

TEST(ExrHalf, BeyondTheHalfRangeSaturatesAndIsCountedNeverInfinite) {
    // The policy: |v| > 65504 is written as +-65504 (never inf, which plain float->half
    // conversion gives from 65520 on), counted in the report and in the file.
    ScratchDir dir("kasumi_exr_half_");
    const float big = std::numeric_limits<float>::max();
    std::vector<float> r = {65504.0f, 65505.0f, 65519.0f, 65520.0f, 1.0e9f, -3.0e5f, big, 2.0f};
    std::vector<float> g(r.size(), 0.5f), b(r.size(), 0.25f), a(r.size(), 1.0f);
    g[3] = 1.0e-9f;  // below 2^-25: flushed to zero, counted apart
    std::vector<ExrChannelView> channels = {{"R", r.data(), ExrPixelType::Half},
                                            {"G", g.data(), ExrPixelType::Half},
                                            {"B", b.data(), ExrPixelType::Half},
                                            {"A", a.data(), ExrPixelType::Half}};
    const std::string path = dir.file("bright.exr");
    const ExrWriteReport report =
        write_exr(header_of(static_cast<int>(r.size()), 1), channels, path, ExrCompression::None);
    EXPECT_EQ(report.half_saturated, 6u);  // all but 65504 and 2
    EXPECT_EQ(report.half_flushed_to_zero, 1u);
    EXPECT_EQ(report.half_max_abs, big);
    EXPECT_EQ(string_attribute(path, "kasumi/half/saturated"), "6");
    // Nine significant digits: the float comes back exactly.
    EXPECT_EQ(static_cast<float>(std::stod(string_attribute(path, "kasumi/half/max_abs"))), big);

    const Image back = read_exr(path);
    const std::vector<float> expected = {65504.0f, 65504.0f,  65504.0f, 65504.0f,
                                         65504.0f, -65504.0f, 65504.0f, 2.0f};
    EXPECT_EQ(back.find("R")->data, expected);
    EXPECT_EQ(back.find("G")->data[3], 0.0f);
    for (const ImageChannel& channel : back.channels) {
        for (float v : channel.data)
            EXPECT_TRUE(std::isfinite(v)) << channel.name;
    }
}

TEST(ExrHalf, ImageOverloadWritesOnlyTheBeautyChannelsAsHalf) {
    ScratchDir dir("kasumi_exr_half_");
    Image image(3, 2);
    for (const char* name : {"R", "G", "B", "A", "albedo.R", "depth.Z"}) {
        ImageChannel& channel = image.add_channel(name);
        for (size_t i = 0; i < channel.data.size(); ++i)
            channel.data[i] = 0.1f * static_cast<float>(i + 1);
    }
    image.find("depth.Z")->data[0] = 7.0e5f;
    const std::string path = dir.file("image.exr");
    const ExrWriteReport report = write_exr(image, path, ExrCompression::Zip, ExrPixelType::Half);
    EXPECT_EQ(report.half_saturated, 0u);  // depth is float: not counted, not saturated
    const auto types = channel_types(path);
    for (const char* name : {"R", "G", "B", "A"})
        EXPECT_EQ(types.at(name), Imf::HALF) << name;
    EXPECT_EQ(types.at("albedo.R"), Imf::FLOAT);
    EXPECT_EQ(types.at("depth.Z"), Imf::FLOAT);
    EXPECT_EQ(read_exr(path).find("depth.Z")->data[0], 7.0e5f);

    // Float output: no half attributes, every channel FLOAT.
    write_exr(image, path);
    for (const auto& kv : channel_types(path))
        EXPECT_EQ(kv.second, Imf::FLOAT) << kv.first;
    EXPECT_EQ(string_attribute(path, "kasumi/half/saturated"), "<missing>");
}

TEST(ExrHalf, WritesAtomicallyAndStillRefusesNonFiniteValues) {
    ScratchDir dir("kasumi_exr_half_");
    std::vector<float> r(6, 1.0f), g(6, 2.0f), b(6, 3.0f), a(6, 1.0f);
    std::vector<ExrChannelView> channels = {{"R", r.data(), ExrPixelType::Half},
                                            {"G", g.data(), ExrPixelType::Half},
                                            {"B", b.data(), ExrPixelType::Half},
                                            {"A", a.data(), ExrPixelType::Half}};
    // Replacing an old file leaves only the final name, with the new pixels.
    const std::string path = dir.file("frame.0001.exr");
    write_exr(header_of(3, 2), channels, path);
    r[4] = 42.0f;
    write_exr(header_of(3, 2), channels, path);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame.0001.exr"});
    EXPECT_EQ(read_exr(path).find("R")->data[4], 42.0f);

    // A NaN or an infinity is refused before the disk is touched: the old file stays as it was.
    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        g[5] = bad;
        std::string message;
        EXPECT_EQ(error_kind_of([&] { write_exr(header_of(3, 2), channels, path); }, &message),
                  ErrorKind::Runtime);
        EXPECT_NE(message.find("'G'"), std::string::npos) << message;
        EXPECT_NE(message.find("(2, 1)"), std::string::npos) << message;
    }
    g[5] = 2.0f;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame.0001.exr"});
    EXPECT_EQ(read_exr(path).find("R")->data[4], 42.0f);

    // An unwritable path: an output error naming it, nothing left behind.
    std::string message;
    const std::string missing = dir.file("missing_dir/out.exr");
    EXPECT_EQ(error_kind_of([&] { write_exr(header_of(3, 2), channels, missing); }, &message),
              ErrorKind::Output);
    EXPECT_NE(message.find(missing), std::string::npos) << message;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame.0001.exr"});
}

}  // namespace
}  // namespace kasumi
