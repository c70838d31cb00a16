// Film read-out: the AOV selection writes exactly the chosen channels with the same values as
// the full image, a reused Image gets the new film's values with no stale data and no new
// buffers, and a film whose storage is recycled from a destroyed one starts empty.
#include "core/film.h"
#include "core/zeroed_allocator.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace kasumi {
namespace {

/// A film whose every pixel holds values that depend on (x, y) and `salt`.
Film make_film(int width, int height, float salt, uint32_t aovs = kAovAll) {
    Film film(width, height, aovs);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float v = salt + static_cast<float>(x) + 100.0f * static_cast<float>(y);
            PixelSample sum;
            sum.radiance = Rgb(v, v + 1.0f, v + 2.0f);
            sum.surface = Rgb(v + 3.0f, v + 4.0f, v + 5.0f);
            sum.volume = Rgb(v + 6.0f, v + 7.0f, v + 8.0f);
            sum.transmittance = Rgb(0.25f, 0.5f, 0.75f);
            sum.albedo = Rgb(0.1f, 0.2f, 0.3f + salt);
            film.set_pixel(x, y, sum, 1, (x + y) % 2, 2.0f + v);
        }
    }
    return film;
}

std::vector<std::string> names_of(const Image& image) {
    std::vector<std::string> names;
    for (const ImageChannel& c : image.channels)
        names.push_back(c.name);
    return names;
}

TEST(Film, AovSelectionWritesExactlyTheChosenChannels) {
    const Film film = make_film(5, 3, 0.5f);
    const Image all = film.to_image();
    EXPECT_EQ(names_of(all),
              (std::vector<std::string>{"R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B",
                                        "depth.Z", "surface.R", "surface.G", "surface.B",
                                        "volume.R", "volume.G", "volume.B", "transmittance.R",
                                        "transmittance.G", "transmittance.B"}));
    Image some;
    film.to_image(some, kAovDepth | kAovVolume);
    EXPECT_EQ(names_of(some), (std::vector<std::string>{"R", "G", "B", "A", "depth.Z", "volume.R",
                                                        "volume.G", "volume.B"}));
    for (const ImageChannel& c : some.channels)
        EXPECT_EQ(c.data, all.find(c.name)->data) << c.name;
    Image beauty;
    film.to_image(beauty, kAovNone);
    EXPECT_EQ(names_of(beauty), (std::vector<std::string>{"R", "G", "B", "A"}));
    for (const ImageChannel& c : beauty.channels)
        EXPECT_EQ(c.data, all.find(c.name)->data) << c.name;
}

TEST(Film, ReusedImageGetsTheNewFilmWithoutNewBuffers) {
    Image image;
    make_film(6, 4, 1.0f).to_image(image);
    image.metadata = {{"frame", "1"}};
    const float* before = image.find("volume.G")->data.data();
    const Film second = make_film(6, 4, 7.0f);
    second.to_image(image);
    EXPECT_EQ(image.find("volume.G")->data.data(), before) << "the buffer was reallocated";
    EXPECT_TRUE(image.metadata.empty());
    const Image fresh = second.to_image();
    ASSERT_EQ(names_of(image), names_of(fresh));
    for (const ImageChannel& c : fresh.channels)
        EXPECT_EQ(image.find(c.name)->data, c.data) << c.name;
    // A different size or channel set rebuilds the image.
    make_film(3, 2, 0.0f).to_image(image, kAovNone);
    EXPECT_EQ(image.width, 3);
    EXPECT_EQ(names_of(image), (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_EQ(image.find("R")->data.size(), 6u);
}

/// Every pixel as a film no sample reached holds it: transmittance 1, everything else 0.
void expect_empty(const Image& image) {
    for (const ImageChannel& c : image.channels) {
        const float expected = c.name.rfind("transmittance.", 0) == 0 ? 1.0f : 0.0f;
        for (size_t i = 0; i < c.data.size(); ++i) {
            if (c.data[i] != expected) {
                ADD_FAILURE() << c.name << " pixel " << i << " = " << c.data[i];
                break;
            }
        }
    }
}

TEST(Film, RecycledStorageStartsEmpty) {
    // Large enough for its storage to be kept after destruction (films of >= 65536 pixels).
    const int width = 320, height = 240;
    { const Film used = make_film(width, height, 3.0f); }
    const Film film(width, height);  // takes the storage of `used`
    const Image image = film.to_image();
    expect_empty(image);
}

TEST(Film, StoresOnlyTheChosenAovsWithTheFullFilmsValues) {
    const Image all = make_film(7, 5, 0.25f).to_image();
    const uint32_t choices[] = {kAovNone, kAovDepth | kAovVolume, kAovTransmittance,
                                kAovAlbedo | kAovSurface};
    for (const uint32_t aovs : choices) {
        const Film film = make_film(7, 5, 0.25f, aovs);
        EXPECT_EQ(film.aovs(), aovs);
        Image expected_names;
        make_film(1, 1, 0.0f).to_image(expected_names, aovs);
        const Image image = film.to_image();
        EXPECT_EQ(names_of(image), names_of(expected_names)) << "aovs " << aovs;
        for (const ImageChannel& c : image.channels)
            EXPECT_EQ(c.data, all.find(c.name)->data) << c.name << ", aovs " << aovs;
    }
}

TEST(Film, PixelsAreSampleMeansAndAlphaNeedsNoStoredTransmittance) {
    // 4 samples, 2 of which hit at depths summing to 6 m; summed transmittance 2 (mean 0.5):
    // alpha = hit fraction 1/2 + (1 - 1/2) * (1 - luminance(T) = 0.5) = 0.75.
    PixelSample sum;
    sum.radiance = Rgb(4.0f, 8.0f, 12.0f);
    sum.transmittance = Rgb(2.0f);
    for (const uint32_t aovs : {uint32_t{kAovNone}, uint32_t{kAovAll}}) {
        Film film(2, 1, aovs);
        film.set_pixel(1, 0, sum, 4, 2, 6.0f);
        const Image image = film.to_image();
        EXPECT_FLOAT_EQ(image.find("R")->data[1], 1.0f);
        EXPECT_FLOAT_EQ(image.find("G")->data[1], 2.0f);
        EXPECT_FLOAT_EQ(image.find("B")->data[1], 3.0f);
        EXPECT_FLOAT_EQ(image.find("A")->data[1], 0.75f);
        EXPECT_EQ(image.find("A")->data[0], 0.0f);  // never set: empty
        if (aovs == kAovAll) {
            EXPECT_FLOAT_EQ(image.find("depth.Z")->data[1], 3.0f);
            EXPECT_FLOAT_EQ(image.find("transmittance.G")->data[1], 0.5f);
            EXPECT_EQ(image.find("transmittance.G")->data[0], 1.0f);
        }
    }
}

TEST(Film, RecycledStorageOfAnAovSubsetStartsEmpty) {
    const int width = 320, height = 240;
    const uint32_t aovs = kAovTransmittance | kAovDepth;
    { const Film used = make_film(width, height, 3.0f, aovs); }
    const Film film(width, height, aovs);  // storage of the same size: taken from `used`
    const Image image = film.to_image();
    ASSERT_EQ(image.channels.size(), 8u);
    expect_empty(image);
}

TEST(Film, ParsesAovLists) {
    uint32_t aovs = 0;
    EXPECT_TRUE(parse_film_aovs("all", aovs));
    EXPECT_EQ(aovs, static_cast<uint32_t>(kAovAll | kAovSamples | kAovNoisy));
    EXPECT_TRUE(parse_film_aovs("noisy", aovs));
    EXPECT_EQ(aovs, static_cast<uint32_t>(kAovNoisy));
    EXPECT_TRUE(parse_film_aovs("samples", aovs));
    EXPECT_EQ(aovs, static_cast<uint32_t>(kAovSamples));
    EXPECT_TRUE(parse_film_aovs("none", aovs));
    EXPECT_EQ(aovs, static_cast<uint32_t>(kAovNone));
    EXPECT_TRUE(parse_film_aovs("depth,albedo", aovs));
    EXPECT_EQ(aovs, static_cast<uint32_t>(kAovDepth | kAovAlbedo));
    EXPECT_TRUE(parse_film_aovs("surface,volume,transmittance", aovs));
    EXPECT_EQ(aovs, static_cast<uint32_t>(kAovSurface | kAovVolume | kAovTransmittance));
    EXPECT_FALSE(parse_film_aovs("depth,normals", aovs));
    EXPECT_FALSE(parse_film_aovs("", aovs));
}

// samples.count holds the n of set_pixel; asking a film for an AOV it does not store gives
// the stored ones only (a uniform render's film has no samples plane).
TEST(Film, SampleCountPlane) {
    Film film(2, 1, kAovDepth | kAovSamples);
    PixelSample sum;
    sum.radiance = Rgb(8.0f);
    film.set_pixel(1, 0, sum, 24, 0, 0.0f);
    const Image image = film.to_image();
    ASSERT_NE(image.find("samples.count"), nullptr);
    EXPECT_EQ(image.find("samples.count")->data, (std::vector<float>{0.0f, 24.0f}));
    EXPECT_FLOAT_EQ(image.find("R")->data[1], 8.0f / 24.0f);
    Film uniform(2, 1, kAovDepth);
    Image some;
    uniform.to_image(some, kAovAll | kAovSamples);
    EXPECT_EQ(some.find("samples.count"), nullptr);
    EXPECT_NE(some.find("depth.Z"), nullptr);
}

TEST(Film, NewFilmsOnFreshHugePageStorageStartEmpty) {
    // 1024x1024 with every AOV is 68 MB: fresh storage mapped in 2 MiB pages, never filled.
    // A first film is written and destroyed, a film of another size then gets new storage.
    { const Film used = make_film(1024, 1024, 5.0f); }
    const Film film(1000, 1000);
    expect_empty(film.to_image());
}

TEST(ZeroedAllocator, LargeBlocksAreZeroAlignedAndKeepTheirValuesWhenGrown) {
    using Floats = std::vector<float, ZeroedAllocator<float>>;
    constexpr size_t kHuge = ZeroedAllocator<float>::kHugePage;
    for (const size_t n : {size_t{1000}, kHuge / sizeof(float), 3 * kHuge / sizeof(float) + 7}) {
        Floats v;
        v.resize(n);  // zeros without a fill
        size_t nonzero = 0;
        for (const float x : v)
            nonzero += x != 0.0f;
        EXPECT_EQ(nonzero, 0u) << n;
        if (n >= kHuge / sizeof(float)) {  // mapped: on a huge-page boundary
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % kHuge, 0u) << n;
        }
        for (size_t i = 0; i < n; i += 4093)
            v[i] = static_cast<float>(i);
        v.resize(2 * n + 1);  // reallocates: old values copied, the new tail zero
        size_t wrong = 0;
        for (size_t i = 0; i < v.size(); ++i)
            wrong += v[i] != (i < n && i % 4093 == 0 ? static_cast<float>(i) : 0.0f);
        EXPECT_EQ(wrong, 0u) << n;
    }
}

}  // namespace
}  // namespace kasumi
