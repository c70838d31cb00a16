// Frame sequences: frame ranges and '#' patterns, thumbnails and the contact sheet, a 24-frame
// run of the shipped fog sequence (all frames written, skip-existing leaves files untouched),
// --frame N bit-identical to the same frame of a whole run and to `render --frame N`, reuse of
// meshes, the BVH and the sky's sun-independent tables without changing a bit, and an animated
// light scaling the image.
#include "sequence/sequence.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "render/renderer.h"
#include "scene/animation.h"
#include "sequence/sequence_contact_sheet.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace kasumi {
namespace {

namespace fs = std::filesystem;

const std::string kFogSequence = KASUMI_SOURCE_DIR "/data/scenes/fog_sequence.json";

/// A fresh directory under the build tree for one test.
std::string test_dir(const std::string& name) {
    const fs::path dir = fs::path(KASUMI_BINARY_DIR) / "sequence_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

std::vector<Override> tiny(int width = 32, int height = 18, int spp = 1) {
    return {{"/film/width", std::to_string(width)},
            {"/film/height", std::to_string(height)},
            {"/film/spp", std::to_string(spp)}};
}

SequenceOptions options_for(const std::string& scene, const std::string& dir,
                            std::vector<int64_t> frames) {
    SequenceOptions o;
    o.scene_path = scene;
    o.overrides = tiny();
    o.frames = std::move(frames);
    o.output_pattern = dir + "/frames/fog.####.exr";
    o.log = nullptr;
    return o;
}

void expect_same_pixels(const Image& a, const Image& b, const std::string& what) {
    ASSERT_EQ(a.width, b.width) << what;
    ASSERT_EQ(a.height, b.height) << what;
    for (const char* name : {"R", "G", "B", "A", "depth.Z"}) {
        const ImageChannel* ca = a.find(name);
        const ImageChannel* cb = b.find(name);
        ASSERT_TRUE(ca != nullptr && cb != nullptr) << what << " " << name;
        // Bitwise: memcmp-equal floats (not merely close).
        EXPECT_TRUE(ca->data == cb->data) << what << ": channel " << name << " differs";
    }
}

/// Renders `reuse`'s frames [0, frames) again with reuse off, into <dir>/rebuilt/<name>.####.exr,
/// expects every frame bit-identical to the reusing run's and returns the rebuild's summary.
SequenceSummary rebuild_matches(const SequenceOptions& reuse, const std::string& dir,
                                const std::string& name, int64_t frames) {
    SequenceOptions rebuild = reuse;
    rebuild.reuse = false;
    rebuild.output_pattern = dir + "/rebuilt/" + name + ".####.exr";
    const SequenceSummary without = run_sequence(rebuild);
    for (int64_t f = 0; f < frames; ++f) {
        expect_same_pixels(read_exr(frame_path(reuse.output_pattern, f)),
                           read_exr(frame_path(rebuild.output_pattern, f)),
                           "frame " + std::to_string(f));
    }
    return without;
}

TEST(FrameRange, ParsesRangesStepsAndSingleFrames) {
    EXPECT_EQ(parse_frame_range("0-23").frames().size(), 24u);
    EXPECT_EQ(parse_frame_range("0-10:5").frames(), (std::vector<int64_t>{0, 5, 10}));
    EXPECT_EQ(parse_frame_range("3-11:4").frames(), (std::vector<int64_t>{3, 7, 11}));
    EXPECT_EQ(parse_frame_range("7").frames(), (std::vector<int64_t>{7}));
    for (const char* bad : {"5-3", "a-b", "1-2:0", "-3", "1-", "1-4294967296", "7:2", ""}) {
        try {
            parse_frame_range(bad);
            ADD_FAILURE() << "accepted \"" << bad << "\"";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Usage) << bad;
        }
    }
}

TEST(FramePattern, HashRunsBecomeZeroPaddedFrames) {
    EXPECT_EQ(frame_path("out/sunset.####.exr", 7), "out/sunset.0007.exr");
    EXPECT_EQ(frame_path("out/sunset.####.exr", 12345), "out/sunset.12345.exr");
    EXPECT_EQ(frame_path("f#/x.##.exr", 3), "f3/x.03.exr");
    EXPECT_EQ(frame_preview_path("out/sunset.####.exr", "prev", 42), "prev/sunset.0042.png");
    EXPECT_EQ(default_contact_sheet_path("out/sunset.####.exr", ""),
              "out/sunset.contact_sheet.png");
    EXPECT_EQ(default_contact_sheet_path("out/sunset.####.exr", "prev"),
              "prev/sunset.contact_sheet.png");
    try {
        frame_path("out/sunset.exr", 1);
        ADD_FAILURE() << "a pattern without # was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Usage);
        EXPECT_NE(std::string(e.what()).find("'#'"), std::string::npos);
    }
}

Image ramp(int width, int height) {
    Image image(width, height);
    for (const char* name : {"R", "G", "B"})
        image.add_channel(name);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = static_cast<size_t>(y) * width + x;
            image.channels[0].data[i] = static_cast<float>(x);
            image.channels[1].data[i] = static_cast<float>(y);
            image.channels[2].data[i] = static_cast<float>(x * y);
        }
    }
    return image;
}

TEST(ContactSheet, ThumbnailsAreBoxMeans) {
    const Image image = ramp(64, 36);
    const Image thumb = make_thumbnail(image, 32);
    ASSERT_EQ(thumb.width, 32);
    ASSERT_EQ(thumb.height, 18);
    // Each thumbnail pixel (i, j) is the mean of frame pixels 2i..2i+1 x 2j..2j+1.
    for (int j = 0; j < 18; ++j) {
        for (int i = 0; i < 32; ++i) {
            const size_t t = static_cast<size_t>(j) * 32 + i;
            EXPECT_EQ(thumb.find("R")->data[t], 2.0f * i + 0.5f);
            EXPECT_EQ(thumb.find("G")->data[t], 2.0f * j + 0.5f);
            EXPECT_EQ(thumb.find("B")->data[t], (2.0f * i + 0.5f) * (2.0f * j + 0.5f));
        }
    }
    // Frames narrower than the thumbnail width are kept as they are.
    const Image small = make_thumbnail(image, 160);
    EXPECT_EQ(small.width, 64);
    EXPECT_TRUE(small.find("B")->data == image.find("B")->data);
}

TEST(ContactSheet, CellsInRowsWithBlackGaps) {
    Image cell = ramp(16, 9);
    for (auto& c : cell.channels)
        std::fill(c.data.begin(), c.data.end(), 1.0f);
    // Five 16x9 cells: ceil(sqrt(5 * 16/9 * 9/16)) = 3 columns, 2 rows, 2-pixel gaps.
    const Image sheet = make_contact_sheet({&cell, &cell, nullptr, &cell, &cell});
    ASSERT_EQ(sheet.width, 3 * 18 + 2);
    ASSERT_EQ(sheet.height, 2 * 11 + 2);
    const auto at = [&](int x, int y) {
        return sheet.find("G")->data[size_t(y) * sheet.width + x];
    };
    EXPECT_EQ(at(2, 2), 1.0f);            // cell 0
    EXPECT_EQ(at(20 + 15, 2 + 8), 1.0f);  // cell 1, last pixel
    EXPECT_EQ(at(38, 2), 0.0f);           // cell 2: missing frame
    EXPECT_EQ(at(2, 13), 1.0f);           // cell 3: second row
    EXPECT_EQ(at(18, 2), 0.0f);           // gap
    EXPECT_EQ(at(2 + 18 * 2, 13), 0.0f);  // no sixth cell
}

TEST(Sequence, TwentyFourFramesAreWrittenAndSkippedWhenPresent) {
    const std::string dir = test_dir("twenty_four");
    SequenceOptions o = options_for(kFogSequence, dir, parse_frame_range("0-23").frames());
    o.preview_dir = dir + "/previews";
    o.contact_sheet = default_contact_sheet_path(o.output_pattern, o.preview_dir);
    const SequenceSummary first = run_sequence(o);
    EXPECT_EQ(first.rendered, 24u);
    EXPECT_EQ(first.skipped, 0u);
    EXPECT_FALSE(first.interrupted);
    std::vector<fs::file_time_type> times;
    for (int64_t f = 0; f < 24; ++f) {
        const std::string path = frame_path(o.output_pattern, f);
        ASSERT_TRUE(fs::exists(path)) << path;
        EXPECT_TRUE(fs::exists(frame_preview_path(o.output_pattern, o.preview_dir, f)));
        const Image image = read_exr(path);
        EXPECT_EQ(image.width, 32);
        EXPECT_EQ(*image.find_metadata("frame"), std::to_string(f));
        times.push_back(fs::last_write_time(path));
    }
    EXPECT_TRUE(fs::exists(dir + "/previews/fog.contact_sheet.png"));
    EXPECT_EQ(first.contact_sheet, dir + "/previews/fog.contact_sheet.png");
    // Nothing but the 24 frames and their manifest records sits beside them (no temporaries).
    size_t files = 0, records = 0;
    for (const auto& entry : fs::directory_iterator(dir + "/frames")) {
        ++files;
        records +=
            entry.path().string().size() > 14 &&
            entry.path().string().substr(entry.path().string().size() - 14) == ".manifest.json";
    }
    EXPECT_EQ(files, 48u);
    EXPECT_EQ(records, 24u);

    const SequenceSummary second = run_sequence(o);
    EXPECT_EQ(second.rendered, 0u);
    EXPECT_EQ(second.skipped, 24u);
    for (int64_t f = 0; f < 24; ++f)
        EXPECT_EQ(fs::last_write_time(frame_path(o.output_pattern, f)), times[size_t(f)]);

    // --no-skip-existing renders again.
    o.skip_existing = false;
    o.frames = {5};
    EXPECT_EQ(run_sequence(o).rendered, 1u);
}

TEST(Sequence, OneFrameAloneIsBitIdenticalToTheSameFrameOfAWholeRun) {
    const std::string dir = test_dir("single");
    SequenceOptions whole = options_for(kFogSequence, dir, parse_frame_range("0-11").frames());
    whole.overrides = tiny(40, 24, 2);
    ASSERT_EQ(run_sequence(whole).rendered, 12u);

    SequenceOptions single = whole;
    single.output_pattern = dir + "/single/fog.####.exr";
    single.frames = {7};
    ASSERT_EQ(run_sequence(single).rendered, 1u);
    const Image from_whole = read_exr(frame_path(whole.output_pattern, 7));
    expect_same_pixels(from_whole, read_exr(frame_path(single.output_pattern, 7)), "--frame 7");

    // What `kasumi render SCENE --frame 7` does: the frame's document, the frame's RNG key.
    const SceneRuntime runtime(load_scene(kFogSequence, whole.overrides, 7));
    RenderOptions render_options;
    render_options.frame = 7;
    render_options.progress = false;
    expect_same_pixels(from_whole, render_image(runtime, render_options).film.to_image(),
                       "render --frame 7");

    // Frames differ: the key frame changes the image (lamp 1 warms up over frames 0-40).
    const Image frame_6 = read_exr(frame_path(whole.output_pattern, 6));
    EXPECT_FALSE(frame_6.find("R")->data == from_whole.find("R")->data);
}

TEST(Sequence, ReuseKeepsMeshesAndTheBvhWithoutChangingABit) {
    const std::string dir = test_dir("reuse");
    SequenceOptions reuse = options_for(kFogSequence, dir, parse_frame_range("0-5").frames());
    const SequenceSummary with = run_sequence(reuse);
    // fog_street has three lamp-post meshes and a BVH; only camera, lights and fog animate.
    EXPECT_EQ(with.reuse.bvh_built, 1u);
    EXPECT_EQ(with.reuse.bvh_reused, 5u);
    EXPECT_EQ(with.reuse.meshes_loaded, 3u);
    EXPECT_EQ(with.reuse.meshes_reused, 15u);
    EXPECT_EQ(with.reuse.lights_parsed, 4u + 5u);  // only lamp 0 changes over frames 0-5
    EXPECT_EQ(with.reuse.media_parsed, 6u);        // the fog thins every frame

    const SequenceSummary without = rebuild_matches(reuse, dir, "fog", 6);
    EXPECT_EQ(without.reuse.bvh_built, 6u);
    EXPECT_EQ(without.reuse.meshes_loaded, 18u);
}

/// sunset_sequence.json's scene (ground, wall, fast sky with aerial perspective) with the sun
/// sinking from +10 to -4 deg over frames 0-3 and the ground albedo stepping from 0.3 (frames
/// 0-1) to 0.5 (frames 2-3): the sky's sun-independent tables are built at frames 0 and 2.
const char* kAnimatedSky = R"({
  "camera": {"position": [-6.0, 1.6, 9.0], "look_at": [0.0, 1.6, 0.0], "fov_deg": 60},
  "film": {"width": 32, "height": 18, "spp": 1},
  "materials": {"white": {"type": "phong", "kd": 0.8, "ks": 0.0}},
  "shapes": [
    {"name": "ground", "type": "quad", "material": "white",
     "vertices": [[-60, 0, 60], [60, 0, 60], [60, 0, -60], [-60, 0, -60]]},
    {"name": "wall", "type": "box", "material": "white", "min": [-2.5, 0, -0.1], "max": [2.5, 3.0, 0.1]}
  ],
  "atmosphere": {"ground_albedo": 0.3},
  "sun": {"elevation_deg": 10, "azimuth_deg": 160, "illuminance_lux": 128000},
  "render": {"seed": 1, "sky": {"mode": "fast"}},
  "animate": {
    "/sun/elevation_deg": [[0, 10], [3, -4]],
    "/atmosphere/ground_albedo": [[0, 0.3], [1, 0.3], [2, 0.5], [3, 0.5]]
  }
})";

TEST(Sequence, SkyTablesAreReusedUntilTheAtmosphereChangesWithoutChangingABit) {
    const std::string dir = test_dir("sky_reuse");
    const std::string scene = dir + "/sky.json";
    std::ofstream(scene) << kAnimatedSky;
    SequenceOptions reuse = options_for(scene, dir, parse_frame_range("0-3").frames());
    reuse.overrides.clear();
    const SequenceSummary with = run_sequence(reuse);
    EXPECT_EQ(with.rendered, 4u);
    EXPECT_EQ(with.reuse.sky_tables_built, 2u);   // frames 0 and 2 (new albedo)
    EXPECT_EQ(with.reuse.sky_tables_reused, 2u);  // frames 1 and 3
    EXPECT_EQ(with.reuse.bvh_reused, 3u);

    const SequenceSummary without = rebuild_matches(reuse, dir, "sky", 4);
    EXPECT_EQ(without.reuse.sky_tables_built, 4u);
    EXPECT_EQ(without.reuse.sky_tables_reused, 0u);
    // The sun-dependent tables follow the sun: the frames of one atmosphere are not alike.
    const Image first = read_exr(frame_path(reuse.output_pattern, 0));
    const Image second = read_exr(frame_path(reuse.output_pattern, 1));
    EXPECT_FALSE(first.find("R")->data == second.find("R")->data);
}

TEST(SequenceCache, SkyTablesKeyIgnoresTheSunDirectionOnly) {
    const Json doc = Json::parse(R"({"atmosphere": {"ground_albedo": 0.3}})");
    SkyScene sky;
    sky.settings.mode = SkyMode::Fast;
    sky.sun_radius_rad = 0.00465;
    const std::string key = sky_tables_key(doc, "a.json", &sky);
    EXPECT_FALSE(key.empty());
    SkyScene moved = sky;
    moved.sun_direction = DVec3(0.0, 0.0, 1.0);
    moved.sun.elevation_deg = -4.0;
    EXPECT_EQ(sky_tables_key(doc, "a.json", &moved), key);
    SkyScene wider = sky;
    wider.sun_radius_rad = 0.005;  // the disc fraction above the horizon enters Psi_ms
    EXPECT_NE(sky_tables_key(doc, "a.json", &wider), key);
    SkyScene bluer = sky;
    bluer.atmosphere.wavelengths_nm[2] = 450.0;
    EXPECT_NE(sky_tables_key(doc, "a.json", &bluer), key);
    const Json albedo = Json::parse(R"({"atmosphere": {"ground_albedo": 0.5}})");
    EXPECT_NE(sky_tables_key(albedo, "a.json", &sky), key);
    EXPECT_NE(sky_tables_key(doc, "b/a.json", &sky), key);  // relative table paths
    SkyScene reference = sky;
    reference.settings.mode = SkyMode::Reference;  // no tables to keep
    EXPECT_TRUE(sky_tables_key(doc, "a.json", &reference).empty());
    EXPECT_TRUE(sky_tables_key(doc, "a.json", nullptr).empty());
}

TEST(Sequence, AnimatedShapesRebuildTheBvh) {
    const std::string dir = test_dir("moving");
    const std::string scene = dir + "/moving.json";
    std::ofstream(scene) << R"({
      "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
      "materials": {"white": {"type": "phong", "kd": 0.8}},
      "shapes": [{"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "white"},
                 {"type": "quad", "material": "white",
                  "vertices": [[-5, 0, 5], [5, 0, 5], [5, 0, -5], [-5, 0, -5]]}],
      "lights": [{"type": "point", "position": [0, 3, 2], "intensity_cd": 50}],
      "animate": {"/shapes/0/center": [[0, [-1, 1, 0]], [3, [1, 1, 0]]]}})";
    const SequenceSummary s = run_sequence(options_for(scene, dir, {0, 1, 2, 3, 4}));
    // Frames 0-3 move the sphere; frame 4 holds frame 3's position.
    EXPECT_EQ(s.reuse.bvh_built, 4u);
    EXPECT_EQ(s.reuse.bvh_reused, 1u);
    EXPECT_EQ(s.reuse.shapes_parsed, 2u + 3u);  // both at frame 0, then the sphere in 1-3
}

TEST(Sequence, DoublingALightDoublesThePixels) {
    // One point light in fog over a diffuse floor: radiance is linear in the intensity, so with
    // the same random numbers (same frame key) frame 10 (200 cd) is exactly twice a still scene
    // at 100 cd up to float rounding of the sums (relative 1e-5).
    const std::string dir = test_dir("doubling");
    const std::string body = R"(
      "camera": {"position": [0, 1.5, 6], "look_at": [0, 1, 0]},
      "film": {"width": 24, "height": 16, "spp": 4},
      "materials": {"white": {"type": "phong", "kd": 0.7}},
      "shapes": [{"type": "quad", "material": "white",
                  "vertices": [[-9, 0, 9], [9, 0, 9], [9, 0, -9], [-9, 0, -9]]}],
      "media": [{"type": "homogeneous", "bounds": [[-9, 0, -9], [9, 6, 9]], "sigma_a": 0.01,
                 "sigma_s": 0.08, "phase": {"model": "hg", "g": 0.5}}],
      "lights": [{"type": "point", "position": [0.5, 2.5, 0], "intensity_cd": 100}])";
    const std::string animated = dir + "/animated.json", still = dir + "/still.json";
    std::ofstream(animated) << "{" << body
                            << R"(, "animate": {"/lights/0/intensity_cd": [[0, 100], [10, 200]]}})";
    std::ofstream(still) << "{" << body << "}";

    SequenceOptions a = options_for(animated, dir, {0, 10});
    a.overrides.clear();
    ASSERT_EQ(run_sequence(a).rendered, 2u);
    SequenceOptions s = a;
    s.scene_path = still;
    s.output_pattern = dir + "/still/s.####.exr";
    s.frames = {10};
    ASSERT_EQ(run_sequence(s).rendered, 1u);

    const Image doubled = read_exr(frame_path(a.output_pattern, 10));
    const Image base = read_exr(frame_path(s.output_pattern, 10));
    for (const char* name : {"R", "G", "B"}) {
        const auto& d = doubled.find(name)->data;
        const auto& b = base.find(name)->data;
        ASSERT_EQ(d.size(), b.size());
        size_t lit = 0;
        for (size_t i = 0; i < d.size(); ++i) {
            EXPECT_NEAR(d[i], 2.0f * b[i], 1e-5f * 2.0f * b[i] + 1e-12f) << name << " pixel " << i;
            lit += b[i] > 0.0f ? 1 : 0;
        }
        EXPECT_GT(lit, d.size() / 2) << "the test scene should light most pixels";
    }
    // Frame 0 (100 cd, other random numbers) is not frame 10.
    EXPECT_FALSE(read_exr(frame_path(a.output_pattern, 0)).find("R")->data ==
                 doubled.find("R")->data);
}

TEST(Sequence, CancelledBeforeAFrameWritesNothing) {
    const std::string dir = test_dir("cancel");
    std::atomic<bool> cancel{true};
    SequenceOptions o = options_for(kFogSequence, dir, {0, 1, 2});
    o.cancel = &cancel;
    o.contact_sheet = dir + "/sheet.png";
    const SequenceSummary s = run_sequence(o);
    EXPECT_TRUE(s.interrupted);
    EXPECT_EQ(s.rendered, 0u);
    EXPECT_FALSE(fs::exists(dir + "/frames"));
    EXPECT_FALSE(fs::exists(dir + "/sheet.png"));
}

TEST(Sequence, BackgroundWriterAovsAndCompressionKeepEveryBeautyBit) {
    // Written in turn (no background writer, every AOV, zip) and in the background (RLE, no
    // AOVs): the same frames, bit for bit in R, G, B, A, and the same contact sheet.
    const std::string dir = test_dir("writer");
    SequenceOptions a = options_for(kFogSequence, dir + "/a", {0, 5, 11});
    a.write_queue = 0;
    a.contact_sheet = dir + "/a/sheet.png";
    SequenceOptions b = options_for(kFogSequence, dir + "/b", {0, 5, 11});
    b.write_queue = 1;
    b.aovs = kAovNone;
    b.compression = ExrCompression::Rle;
    b.contact_sheet = dir + "/b/sheet.png";
    EXPECT_EQ(run_sequence(a).rendered, 3u);
    const SequenceSummary sb = run_sequence(b);
    EXPECT_EQ(sb.rendered, 3u);
    EXPECT_GT(sb.write_seconds, 0.0);
    for (const int64_t f : {0, 5, 11}) {
        const Image ia = read_exr(frame_path(a.output_pattern, f));
        const Image ib = read_exr(frame_path(b.output_pattern, f));
        EXPECT_EQ(ia.channels.size(), 17u);
        ASSERT_EQ(ib.channels.size(), 4u) << "frame " << f;
        for (const char* name : {"R", "G", "B", "A"}) {
            ASSERT_NE(ib.find(name), nullptr) << name;
            EXPECT_TRUE(ia.find(name)->data == ib.find(name)->data)
                << "frame " << f << " channel " << name;
        }
        EXPECT_EQ(*ib.find_metadata("frame"), std::to_string(f));
    }
    std::ifstream sa(a.contact_sheet, std::ios::binary), sb_file(b.contact_sheet, std::ios::binary);
    const std::string bytes_a((std::istreambuf_iterator<char>(sa)), {});
    const std::string bytes_b((std::istreambuf_iterator<char>(sb_file)), {});
    EXPECT_FALSE(bytes_a.empty());
    EXPECT_EQ(bytes_a, bytes_b);
}

TEST(Sequence, AFailedWriteStopsTheRunWithAnOutputErrorAndNoPartialFile) {
    // Frame 3's final name is taken by a non-empty directory, so its rename fails. Frames 0-2
    // (written before it) stay; frames after it are not written, even if already rendered;
    // no temporary is left behind and no contact sheet is made.
    for (const size_t queue : {size_t{0}, size_t{1}}) {
        const std::string dir = test_dir("write_error_" + std::to_string(queue));
        SequenceOptions o = options_for(kFogSequence, dir, {0, 1, 2, 3, 4, 5});
        o.skip_existing = false;
        o.write_queue = queue;
        o.contact_sheet = dir + "/sheet.png";
        const std::string taken = frame_path(o.output_pattern, 3);
        fs::create_directories(taken + "/inside");
        try {
            run_sequence(o);
            ADD_FAILURE() << "the failed write was not reported";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Output);
            EXPECT_NE(std::string(e.what()).find(taken), std::string::npos) << e.what();
        }
        for (const int64_t f : {0, 1, 2})
            EXPECT_EQ(read_exr(frame_path(o.output_pattern, f)).width, 32) << "frame " << f;
        EXPECT_TRUE(fs::is_directory(taken));
        for (const int64_t f : {4, 5})
            EXPECT_FALSE(fs::exists(frame_path(o.output_pattern, f))) << "frame " << f;
        for (const auto& entry : fs::directory_iterator(dir + "/frames"))
            EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
                << entry.path();
        EXPECT_FALSE(fs::exists(o.contact_sheet));
    }
}

TEST(Sequence, AnimationErrorsAreInputErrorsNamingTheScene) {
    const std::string dir = test_dir("errors");
    const std::string scene = dir + "/bad.json";
    std::ofstream(scene)
        << R"({"lights": [{"type": "point", "position": [0, 1, 0], "intensity_cd": 1}],
      "animate": {"/lights/1/intensity_cd": [[0, 1], [5, 2]]}})";
    try {
        run_sequence(options_for(scene, dir, {0}));
        ADD_FAILURE() << "an unknown pointer was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        EXPECT_NE(std::string(e.what()).find("bad.json: /animate/~1lights~11~1intensity_cd"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(fs::exists(dir + "/frames"));
}

TEST(Sequence, ABadValueBetweenKeyFramesNamesTheFrameAndItsKeys) {
    // spp is an integer at its key frames 0 and 4 but 1.5 at frame 1, no key frame (`check`
    // cannot see it), and 2.5 at frame 3, the other track's key frame: the error names the
    // frame as check names key frames, and the keys around it of the value it is about.
    const std::string dir = test_dir("between_keys");
    const std::string scene = dir + "/spp.json";
    std::ofstream(scene) << R"({
      "film": {"width": 8, "height": 4, "spp": 1},
      "lights": [{"type": "point", "position": [0, 1, 0], "intensity_cd": 1}],
      "animate": {"/film/spp": [[0, 1], [4, 3]], "/lights/0/intensity_cd": [[0, 1], [3, 2]]}})";
    const std::pair<int64_t, std::string> cases[] = {
        {1, " (at frame 1 of /animate; /film/spp between key frames 0 and 4)"},
        {3, " (at key frame 3 of /animate; /film/spp between key frames 0 and 4)"}};
    for (const auto& [frame, context] : cases) {
        SequenceOptions o = options_for(scene, dir, {frame});
        o.overrides.clear();
        try {
            run_sequence(o);
            ADD_FAILURE() << "frame " << frame << " rendered";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(e.kind(), ErrorKind::Input);
            EXPECT_EQ(what.find(scene + ": /film/spp = "), 0u) << what;
            ASSERT_GE(what.size(), context.size());
            EXPECT_EQ(what.substr(what.size() - context.size()), context) << what;
        }
    }
    EXPECT_FALSE(fs::exists(dir + "/frames"));
}

}  // namespace
}  // namespace kasumi
