#include "core/color_management.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/png_io.h"
#include "tests/input_error.h"
#include "tests/scratch_dir.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace kasumi {
namespace {

namespace fs = std::filesystem;

const std::string kConfig = std::string(KASUMI_SOURCE_DIR) + "/data/ocio/config.ocio";

/// The channels the renderer writes, filled with distinct values (some negative, tiny, large).
Image make_render_like_image(int width, int height) {
    Image image(width, height);
    const char* names[] = {"R",
                           "G",
                           "B",
                           "A",
                           "albedo.R",
                           "albedo.G",
                           "albedo.B",
                           "depth.Z",
                           "surface.R",
                           "surface.G",
                           "surface.B",
                           "volume.R",
                           "volume.G",
                           "volume.B",
                           "transmittance.R",
                           "transmittance.G",
                           "transmittance.B"};
    int c = 0;
    for (const char* name : names) {
        ImageChannel& channel = image.add_channel(name);
        for (size_t i = 0; i < channel.data.size(); ++i)
            channel.data[i] = static_cast<float>(c * 1000 + static_cast<int>(i)) * 0.37f - 5.0f;
        ++c;
    }
    image.find("R")->data[0] = 1.0e-30f;
    image.find("G")->data[0] = 3.0e37f;
    image.metadata = {{"spp", "64"},
                      {"seed", "7"},
                      {"time_seconds", "1.25"},
                      {"version", "kasumi 0.1.0"},
                      {"scene", "fog: \"a b\"\nline 2"}};
    image.chromaticities =
        Chromaticities{0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f};
    return image;
}

TEST(ExrIo, RoundTripsEveryChannelMetadataAndChromaticities) {
    ScratchDir dir("kasumi_image_io_");
    const Image image = make_render_like_image(7, 5);
    const std::string path = dir.file("out.exr");
    write_exr(image, path);
    const Image back = read_exr(path);

    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 5);
    ASSERT_EQ(back.channels.size(), image.channels.size());
    for (const ImageChannel& channel : image.channels) {
        const ImageChannel* read = back.find(channel.name);
        ASSERT_NE(read, nullptr) << channel.name;
        // FLOAT channels: bit-exact.
        EXPECT_EQ(read->data, channel.data) << channel.name;
    }
    for (const auto& kv : image.metadata) {
        const std::string* value = back.find_metadata(kv.first);
        ASSERT_NE(value, nullptr) << kv.first;
        EXPECT_EQ(*value, kv.second);
    }
    EXPECT_EQ(back.metadata.size(), image.metadata.size());
    const Chromaticities& a = image.chromaticities;
    const Chromaticities& b = back.chromaticities;
    EXPECT_EQ(b.red_x, a.red_x);
    EXPECT_EQ(b.red_y, a.red_y);
    EXPECT_EQ(b.green_x, a.green_x);
    EXPECT_EQ(b.green_y, a.green_y);
    EXPECT_EQ(b.blue_x, a.blue_x);
    EXPECT_EQ(b.blue_y, a.blue_y);
    EXPECT_EQ(b.white_x, a.white_x);
    EXPECT_EQ(b.white_y, a.white_y);
}

TEST(ExrIo, EveryCompressionIsLossless) {
    // Random bit patterns of finite floats (all exponents, signs, denormals) in a size that is
    // not a multiple of any compression's block (PIZ: 32 scanlines, ZIP: 16): every
    // compression must give back the same bits.
    ScratchDir dir("kasumi_image_io_");
    Image image = make_render_like_image(37, 45);
    uint32_t state = 12345u;
    for (ImageChannel& channel : image.channels) {
        for (float& v : channel.data) {
            state = state * 1664525u + 1013904223u;  // LCG (Numerical Recipes)
            uint32_t bits = state;
            if (((bits >> 23) & 0xffu) == 0xffu)
                bits &= ~(1u << 23);  // not inf/NaN: the writer refuses those
            std::memcpy(&v, &bits, sizeof v);
        }
    }
    for (const char* name : {"zip", "piz", "rle", "none"}) {
        ExrCompression compression = ExrCompression::Zip;
        ASSERT_TRUE(parse_exr_compression(name, compression)) << name;
        const std::string path = dir.file(std::string(name) + ".exr");
        write_exr(image, path, compression);
        const Image back = read_exr(path);
        ASSERT_EQ(back.channels.size(), image.channels.size()) << name;
        for (const ImageChannel& channel : image.channels) {
            const ImageChannel* read = back.find(channel.name);
            ASSERT_NE(read, nullptr) << name << " " << channel.name;
            EXPECT_EQ(std::memcmp(read->data.data(), channel.data.data(),
                                  channel.data.size() * sizeof(float)),
                      0)
                << name << " " << channel.name;
        }
    }
    // The setting reaches the file: the smooth render-like channels shrink under zip, not
    // under none (which stores 4 bytes per value and channel).
    const Image smooth = make_render_like_image(37, 45);
    write_exr(smooth, dir.file("smooth_zip.exr"), ExrCompression::Zip);
    write_exr(smooth, dir.file("smooth_none.exr"), ExrCompression::None);
    const uintmax_t raw = 37u * 45u * 4u * smooth.channels.size();
    EXPECT_GE(fs::file_size(dir.file("smooth_none.exr")), raw);
    EXPECT_LT(fs::file_size(dir.file("smooth_zip.exr")), raw / 2);
    ExrCompression c = ExrCompression::Zip;
    EXPECT_FALSE(parse_exr_compression("dwaa", c));  // lossy: not offered
    EXPECT_FALSE(parse_exr_compression("", c));
}

TEST(ExrIo, LeavesOnlyTheFinalFileAndReplacesAnOldOne) {
    ScratchDir dir("kasumi_image_io_");
    const std::string path = dir.file("frame.0001.exr");
    Image image = make_render_like_image(3, 2);
    write_exr(image, path);
    image.find("R")->data[1] = 42.0f;
    write_exr(image, path);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame.0001.exr"});
    EXPECT_EQ(read_exr(path).find("R")->data[1], 42.0f);
}

TEST(ExrIo, UnwritablePathIsAnOutputErrorNamingItAndLeavesNoFile) {
    ScratchDir dir("kasumi_image_io_");
    const std::string path = dir.file("missing_dir/out.exr");
    std::string message;
    EXPECT_EQ(error_kind_of([&] { write_exr(make_render_like_image(2, 2), path); }, &message),
              ErrorKind::Output);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_TRUE(dir.entries().empty());

    // A directory in the way of the final name: the rename fails, the temporary goes.
    fs::create_directory(dir.file("taken.exr"));
    fs::create_directory(dir.file("taken.exr/inside"));
    EXPECT_EQ(error_kind_of([&] { write_exr(make_render_like_image(2, 2), dir.file("taken.exr")); },
                            &message),
              ErrorKind::Output);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken.exr"});
}

TEST(ExrIo, RefusesNonFiniteValuesNamingChannelAndPixel) {
    ScratchDir dir("kasumi_image_io_");
    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()}) {
        Image image = make_render_like_image(4, 3);
        image.find("volume.G")->data[2 * 4 + 1] = bad;
        std::string message;
        EXPECT_EQ(error_kind_of([&] { write_exr(image, dir.file("bad.exr")); }, &message),
                  ErrorKind::Runtime);
        EXPECT_NE(message.find("volume.G"), std::string::npos) << message;
        EXPECT_NE(message.find("(1, 2)"), std::string::npos) << message;
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(ExrIo, BorrowedPlanesWriteTheSameFileAsTheImage) {
    // What the renderer does: the header image carries size and metadata, the pixels are read
    // from planes owned elsewhere (the film), in the order given.
    ScratchDir dir("kasumi_image_io_");
    const Image image = make_render_like_image(6, 4);
    Image header(image.width, image.height);
    header.metadata = image.metadata;
    header.chromaticities = image.chromaticities;
    std::vector<ExrChannelView> planes;
    for (const ImageChannel& channel : image.channels)
        planes.push_back({channel.name, channel.data.data()});
    write_exr(header, planes, dir.file("planes.exr"));
    write_exr(image, dir.file("image.exr"));
    const Image a = read_exr(dir.file("planes.exr"));
    const Image b = read_exr(dir.file("image.exr"));
    ASSERT_EQ(a.channels.size(), image.channels.size());
    for (const ImageChannel& channel : image.channels) {
        ASSERT_NE(a.find(channel.name), nullptr) << channel.name;
        EXPECT_EQ(a.find(channel.name)->data, channel.data) << channel.name;
    }
    EXPECT_EQ(a.metadata, b.metadata);
    EXPECT_EQ(a.chromaticities.white_x, image.chromaticities.white_x);

    // Same guards: a non-finite value or a repeated name, and nothing is written.
    std::vector<float> bad(6 * 4, 1.0f);
    bad[5] = std::numeric_limits<float>::quiet_NaN();
    std::vector<ExrChannelView> with_nan = planes;
    with_nan.push_back({"extra.X", bad.data()});
    std::string message;
    EXPECT_EQ(error_kind_of([&] { write_exr(header, with_nan, dir.file("nan.exr")); }, &message),
              ErrorKind::Runtime);
    EXPECT_NE(message.find("extra.X' pixel (5, 0)"), std::string::npos) << message;
    std::vector<ExrChannelView> repeated = planes;
    repeated.push_back(planes.front());
    EXPECT_EQ(error_kind_of([&] { write_exr(header, repeated, dir.file("rep.exr")); }),
              ErrorKind::Runtime);
    EXPECT_FALSE(fs::exists(dir.file("nan.exr")));
    EXPECT_FALSE(fs::exists(dir.file("rep.exr")));
}

TEST(ExrIo, ReadingAMissingOrCorruptFileIsAnInputErrorNamingIt) {
    ScratchDir dir("kasumi_image_io_");
    std::string message;
    const std::string missing = dir.file("nope.exr");
    EXPECT_EQ(error_kind_of([&] { read_exr(missing); }, &message), ErrorKind::Input);
    EXPECT_NE(message.find(missing), std::string::npos) << message;

    const std::string corrupt = dir.file("corrupt.exr");
    std::ofstream(corrupt) << "not an exr";
    EXPECT_EQ(error_kind_of([&] { read_exr(corrupt); }, &message), ErrorKind::Input);
    EXPECT_NE(message.find(corrupt), std::string::npos) << message;
}

uint32_t read_u32_be(const std::vector<uint8_t>& bytes, size_t at) {
    return (uint32_t(bytes.at(at)) << 24) | (uint32_t(bytes.at(at + 1)) << 16) |
           (uint32_t(bytes.at(at + 2)) << 8) | uint32_t(bytes.at(at + 3));
}

struct DecodedPng {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;
    std::vector<std::pair<std::string, std::string>> text;  ///< tEXt chunks, in file order
};

/// A minimal independent PNG checker for 8-bit RGB: signature, chunk CRCs, IHDR fields, IDAT
/// inflated with zlib and unfiltered (PNG spec section 9), IEND last. Failures are gtest failures.
DecodedPng decode_png_rgb8(const std::vector<uint8_t>& png) {
    DecodedPng out;
    const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    EXPECT_TRUE(png.size() >= 8 && std::equal(signature, signature + 8, png.begin()));
    std::vector<uint8_t> idat;
    std::vector<std::string> types;
    for (size_t at = 8; at < png.size();) {
        const uint32_t length = read_u32_be(png, at);
        EXPECT_LE(at + 12 + length, png.size());
        if (at + 12 + length > png.size())
            return out;
        const std::string type(png.begin() + at + 4, png.begin() + at + 8);
        types.push_back(type);
        const uint8_t* data = png.data() + at + 8;
        const uLong crc = crc32(crc32(0L, Z_NULL, 0), png.data() + at + 4, length + 4);
        EXPECT_EQ(read_u32_be(png, at + 8 + length), crc) << type;
        if (type == "IHDR") {
            EXPECT_EQ(length, 13u);
            out.width = static_cast<int>(read_u32_be(png, at + 8));
            out.height = static_cast<int>(read_u32_be(png, at + 12));
            EXPECT_EQ(data[8], 8);   // bit depth
            EXPECT_EQ(data[9], 2);   // truecolour
            EXPECT_EQ(data[10], 0);  // deflate
            EXPECT_EQ(data[11], 0);  // adaptive filtering
            EXPECT_EQ(data[12], 0);  // no interlace
        } else if (type == "IDAT") {
            idat.insert(idat.end(), data, data + length);
        } else if (type == "tEXt") {
            EXPECT_NE(types.size(), 1u) << "tEXt before IHDR";
            const uint8_t* nul = std::find(data, data + length, uint8_t{0});
            EXPECT_NE(nul, data + length) << "tEXt without a NUL separator";
            if (nul != data + length)
                out.text.emplace_back(std::string(data, nul), std::string(nul + 1, data + length));
        }
        at += 12 + length;
    }
    EXPECT_FALSE(types.empty());
    if (types.empty())
        return out;
    EXPECT_EQ(types.front(), "IHDR");
    EXPECT_EQ(types.back(), "IEND");

    const size_t stride = static_cast<size_t>(out.width) * 3;
    std::vector<uint8_t> filtered((stride + 1) * static_cast<size_t>(out.height));
    uLongf size = filtered.size();
    EXPECT_EQ(uncompress(filtered.data(), &size, idat.data(), idat.size()), Z_OK);
    EXPECT_EQ(size, filtered.size());

    out.rgb.assign(stride * static_cast<size_t>(out.height), 0);
    for (int y = 0; y < out.height; ++y) {
        const uint8_t type = filtered[static_cast<size_t>(y) * (stride + 1)];
        EXPECT_LE(type, 4);
        const uint8_t* in = filtered.data() + static_cast<size_t>(y) * (stride + 1) + 1;
        uint8_t* row = out.rgb.data() + static_cast<size_t>(y) * stride;
        for (size_t i = 0; i < stride; ++i) {
            const int a = i >= 3 ? row[i - 3] : 0;
            const int b = y > 0 ? row[i - stride] : 0;
            const int c = (i >= 3 && y > 0) ? row[i - stride - 3] : 0;
            int predictor = 0;
            if (type == 1) {
                predictor = a;
            } else if (type == 2) {
                predictor = b;
            } else if (type == 3) {
                predictor = (a + b) / 2;
            } else if (type == 4) {
                const int p = a + b - c;
                const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
                predictor = (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
            }
            row[i] = static_cast<uint8_t>(in[i] + predictor);
        }
    }
    return out;
}

std::vector<uint8_t> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

TEST(PngIo, WrittenFileDecodesToTheSameBytes) {
    ScratchDir dir("kasumi_image_io_");
    // Gradients, flat areas and noise, so that every filter type wins somewhere.
    const int width = 37, height = 23;
    std::vector<uint8_t> rgb(static_cast<size_t>(width) * height * 3);
    uint32_t state = 12345u;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            state = state * 1664525u + 1013904223u;
            uint8_t* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
            p[0] = static_cast<uint8_t>(x * 7);
            p[1] = static_cast<uint8_t>(y < 10 ? 200 : y * 11 + x);
            p[2] = static_cast<uint8_t>(y % 3 == 0 ? state >> 24 : x + y);
        }
    }
    const std::string path = dir.file("preview.png");
    write_png_rgb8(width, height, rgb, path);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"preview.png"});
    const DecodedPng decoded = decode_png_rgb8(read_bytes(path));
    EXPECT_EQ(decoded.width, width);
    EXPECT_EQ(decoded.height, height);
    EXPECT_EQ(decoded.rgb, rgb);
}

TEST(PngIo, TextChunksFollowTheHeaderAndBadKeywordsAreRefused) {
    const std::vector<PngText> text = {{"Software", "kasumi"},
                                       {"kasumi/preview/exposure_stops", "-13.625"}};
    const DecodedPng png = decode_png_rgb8(encode_png_rgb8(2, 1, {1, 2, 3, 4, 5, 6}, text));
    EXPECT_EQ(png.rgb, (std::vector<uint8_t>{1, 2, 3, 4, 5, 6}));
    ASSERT_EQ(png.text.size(), 2u);
    EXPECT_EQ(png.text[0], (std::pair<std::string, std::string>{"Software", "kasumi"}));
    EXPECT_EQ(png.text[1].second, "-13.625");
    for (const std::string& bad : {std::string(), std::string(80, 'k'), std::string(" lead"),
                                   std::string("two  spaces"), std::string("tab\tin")})
        EXPECT_EQ(error_kind_of([&] {
                      encode_png_rgb8(1, 1, {0, 0, 0}, {{bad, "x"}});
                  }),
                  ErrorKind::Runtime)
            << bad;
    EXPECT_EQ(error_kind_of([] {
                  encode_png_rgb8(1, 1, {0, 0, 0}, {{"Comment", std::string("a\0b", 3)}});
              }),
              ErrorKind::Runtime);
}

TEST(PngIo, OnePixelImageAndBadArguments) {
    const DecodedPng one = decode_png_rgb8(encode_png_rgb8(1, 1, {1, 2, 3}));
    EXPECT_EQ(one.rgb, (std::vector<uint8_t>{1, 2, 3}));
    EXPECT_EQ(error_kind_of([] { encode_png_rgb8(2, 2, {1, 2, 3}); }), ErrorKind::Runtime);
    EXPECT_EQ(error_kind_of([] { encode_png_rgb8(0, 1, {}); }), ErrorKind::Runtime);
}

TEST(PngIo, UnwritablePathIsAnOutputErrorNamingIt) {
    ScratchDir dir("kasumi_image_io_");
    const std::string path = dir.file("no/such/dir/preview.png");
    std::string message;
    EXPECT_EQ(error_kind_of(
                  [&] {
                      write_png_rgb8(1, 1, {0, 0, 0}, path);
                  },
                  &message),
              ErrorKind::Output);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_TRUE(dir.entries().empty());
}

PreviewSettings settings_for(const std::string& view) {
    PreviewSettings settings;
    settings.config_path = kConfig;
    settings.display = "sRGB";
    settings.view = view;
    return settings;
}

float display_grey(float linear, const std::string& view) {
    std::vector<float> rgb = {linear, linear, linear};
    apply_display_view(rgb, settings_for(view));
    return rgb[1];
}

TEST(ColorManagement, ShippedConfigHasTheRequiredViews) {
    const std::vector<std::string> displays = list_displays(kConfig);
    ASSERT_FALSE(displays.empty());
    EXPECT_EQ(displays.front(), "sRGB");
    const std::vector<std::string> views = list_views(kConfig, "sRGB");
    for (const char* required : {"ACES 1.0 - SDR Video", "Un-tone-mapped", "Raw"})
        EXPECT_NE(std::find(views.begin(), views.end(), required), views.end()) << required;
    EXPECT_EQ(views.front(), "ACES 1.0 - SDR Video");
    EXPECT_EQ(list_views(kConfig, ""), views);
}

TEST(ColorManagement, UnToneMappedIsThePlainSrgbEncoding) {
    // IEC 61966-2-1: 1.055 * 0.18^(1/2.4) - 0.055 = 0.46135.
    EXPECT_NEAR(display_grey(0.18f, "Un-tone-mapped"), 0.46135f, 2e-4f);
    EXPECT_NEAR(display_grey(1.0f, "Un-tone-mapped"), 1.0f, 2e-4f);
    EXPECT_NEAR(display_grey(0.0f, "Un-tone-mapped"), 0.0f, 1e-5f);
    // Linear segment below 0.0031308: 12.92 x.
    EXPECT_NEAR(display_grey(0.001f, "Un-tone-mapped"), 0.01292f, 1e-4f);
    // Primaries stay primaries: no gamut change on the way through ACES2065-1.
    std::vector<float> red = {1.0f, 0.0f, 0.0f};
    apply_display_view(red, settings_for("Un-tone-mapped"));
    EXPECT_NEAR(red[0], 1.0f, 1e-3f);
    EXPECT_NEAR(red[1], 0.0f, 1e-3f);
    EXPECT_NEAR(red[2], 0.0f, 1e-3f);
}

TEST(ColorManagement, AcesViewIsPlausibleAndMonotonic) {
    const float grey = display_grey(0.18f, "ACES 1.0 - SDR Video");
    EXPECT_GT(grey, 0.3f);
    EXPECT_LT(grey, 0.5f);
    // Non-decreasing everywhere; strictly increasing above the ODT's black clip (about 6 stops
    // under mid grey maps below 0.5/255).
    float previous = -1.0f;
    for (float stops = -10.0f; stops <= 10.0f; stops += 0.5f) {
        const float v = display_grey(0.18f * std::exp2(stops), "ACES 1.0 - SDR Video");
        if (stops >= -5.5f)
            EXPECT_GT(v, previous) << "at " << stops << " stops";
        else
            EXPECT_GE(v, previous) << "at " << stops << " stops";
        EXPECT_LT(std::abs(v), 0.5f / 255.0f + (stops >= -6.0f ? 2.0f : 0.0f)) << stops;
        previous = v;
    }
    // Tone mapping compresses highlights: 16x mid grey is still below full white.
    EXPECT_LT(display_grey(0.18f * 16.0f, "ACES 1.0 - SDR Video"), 1.0f);
}

TEST(ColorManagement, RawViewAndExposure) {
    EXPECT_FLOAT_EQ(display_grey(0.25f, "Raw"), 0.25f);
    PreviewSettings settings = settings_for("Raw");
    settings.exposure_stops = 2.0f;
    std::vector<float> rgb = {0.25f, 0.5f, 0.125f};
    apply_display_view(rgb, settings);
    EXPECT_FLOAT_EQ(rgb[0], 1.0f);
    EXPECT_FLOAT_EQ(rgb[1], 2.0f);
    EXPECT_FLOAT_EQ(rgb[2], 0.5f);
}

TEST(ColorManagement, PreviewPngQuantisesUnToneMappedGrey) {
    ScratchDir dir("kasumi_image_io_");
    Image image(3, 1);
    for (const char* name : {"R", "G", "B", "A"})
        image.add_channel(name).data = {0.18f, 1.0f, 7.0f};
    image.find("R")->data[2] = -1.0f;
    const std::string path = dir.file("preview.png");
    write_preview_png(image, path, settings_for("Un-tone-mapped"));
    const DecodedPng png = decode_png_rgb8(read_bytes(path));
    EXPECT_EQ(png.width, 3);
    EXPECT_EQ(png.height, 1);
    // 0.18 -> 0.46135 * 255 = 117.6 -> 118; 1 -> 255; above 1 clips to 255, below 0 to 0.
    EXPECT_EQ(png.rgb, (std::vector<uint8_t>{118, 118, 118, 255, 255, 255, 0, 255, 255}));
    // The PNG says how it was made: the view and the exposure, as the EXR's kasumi/preview/*.
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"Software", "kasumi"},
        {"kasumi/preview/display", "sRGB"},
        {"kasumi/preview/view", "Un-tone-mapped"},
        {"kasumi/preview/exposure_stops", "0"}};
    EXPECT_EQ(png.text, expected);
}

TEST(ColorManagement, ErrorsNameTheConfig) {
    std::string message;
    EXPECT_EQ(error_kind_of([&] { list_views(kConfig, "No Such Display"); }, &message),
              ErrorKind::Input);
    EXPECT_NE(message.find(kConfig), std::string::npos) << message;

    EXPECT_EQ(error_kind_of([&] { display_grey(0.5f, "No Such View"); }, &message),
              ErrorKind::Input);
    EXPECT_NE(message.find(kConfig), std::string::npos) << message;

    ScratchDir dir("kasumi_image_io_");
    const std::string broken = dir.file("broken.ocio");
    std::ofstream(broken) << "ocio_profile_version: 2\ncolorspaces: [oops\n";
    EXPECT_EQ(error_kind_of([&] { list_views(broken, ""); }, &message), ErrorKind::Input);
    EXPECT_NE(message.find(broken), std::string::npos) << message;

    const std::string missing = dir.file("missing.ocio");
    EXPECT_EQ(error_kind_of([&] { list_displays(missing); }, &message), ErrorKind::Input);
    EXPECT_NE(message.find(missing), std::string::npos) << message;
}

TEST(ColorManagement, DefaultConfigPathPrefersTheEnvironment) {
    const char* saved = std::getenv("KASUMI_OCIO");
    const std::string saved_value = saved ? saved : "";
    ::unsetenv("KASUMI_OCIO");
    EXPECT_TRUE(fs::exists(default_ocio_config_path())) << default_ocio_config_path();
    EXPECT_EQ(list_views("", "sRGB"), list_views(kConfig, "sRGB"));
    ::setenv("KASUMI_OCIO", "/somewhere/else.ocio", 1);
    EXPECT_EQ(default_ocio_config_path(), "/somewhere/else.ocio");
    if (saved)
        ::setenv("KASUMI_OCIO", saved_value.c_str(), 1);
    else
        ::unsetenv("KASUMI_OCIO");
}

}  // namespace
}  // namespace kasumi
