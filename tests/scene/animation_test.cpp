// Keyframed scene values: exact interpolation of numbers, arrays and date-times, holds outside
// the keyed range, and located errors for every kind of bad "animate" entry.
#include "scene/animation.h"
#include "core/error.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

SceneDocument doc(const std::string& text) {
    return SceneDocument(parse_json_text(text, "anim.json"), "anim.json");
}

Json value_at(const SceneDocument& root, int64_t frame, const std::string& pointer) {
    return frame_document(root, parse_animation(root), frame).get(pointer);
}

/// The message of the input error parse_animation throws ("" if none).
std::string animation_error(const std::string& text) {
    try {
        parse_animation(doc(text));
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        return e.what();
    }
    return "";
}

const char* kSun = R"({"sun": {"elevation_deg": 3, "datetime": "2026-06-21T18:00:00+02:00"},
    "camera": {"position": [0, 1, 2]},
    "animate": {"/sun/elevation_deg": [[0, 10], [240, -6]]}})";

TEST(Animation, NumbersInterpolateLinearlyBetweenKeys) {
    const SceneDocument root = doc(kSun);
    // 10 + (-6 - 10) f / 240 at f = 0, 15, 60, 120, 180, 240: all exact in binary.
    EXPECT_EQ(value_at(root, 0, "/sun/elevation_deg").get<double>(), 10.0);
    EXPECT_EQ(value_at(root, 15, "/sun/elevation_deg").get<double>(), 9.0);
    EXPECT_EQ(value_at(root, 60, "/sun/elevation_deg").get<double>(), 6.0);
    EXPECT_EQ(value_at(root, 120, "/sun/elevation_deg").get<double>(), 2.0);
    EXPECT_EQ(value_at(root, 180, "/sun/elevation_deg").get<double>(), -2.0);
    EXPECT_EQ(value_at(root, 240, "/sun/elevation_deg").get<double>(), -6.0);
    EXPECT_NEAR(value_at(root, 1, "/sun/elevation_deg").get<double>(), 10.0 - 16.0 / 240.0, 1e-12);
}

TEST(Animation, ValuesHoldOutsideTheKeyedRange) {
    const SceneDocument root = doc(R"({"x": 0, "animate": {"/x": [[10, 4.5], [20, 8.5]]}})");
    EXPECT_EQ(value_at(root, -3, "/x").get<double>(), 4.5);
    EXPECT_EQ(value_at(root, 0, "/x").get<double>(), 4.5);
    EXPECT_EQ(value_at(root, 10, "/x").get<double>(), 4.5);
    EXPECT_EQ(value_at(root, 15, "/x").get<double>(), 6.5);
    EXPECT_EQ(value_at(root, 20, "/x").get<double>(), 8.5);
    EXPECT_EQ(value_at(root, 1000, "/x").get<double>(), 8.5);
}

TEST(Animation, PiecewiseLinearThroughEveryKey) {
    const SceneDocument root =
        doc(R"({"x": 0, "animate": {"/x": [[0, 0], [4, 8], [6, 2], [10, 2]]}})");
    const double expected[] = {0, 2, 4, 6, 8, 5, 2, 2, 2, 2, 2};
    for (int f = 0; f <= 10; ++f)
        EXPECT_EQ(value_at(root, f, "/x").get<double>(), expected[f]) << "frame " << f;
}

TEST(Animation, IntegerKeysGiveIntegersWhereExact) {
    const SceneDocument root = doc(R"({"n": 1, "animate": {"/n": [[0, 1], [2, 3], [5, 4]]}})");
    EXPECT_TRUE(value_at(root, 1, "/n").is_number_integer());
    EXPECT_EQ(value_at(root, 1, "/n").get<int64_t>(), 2);
    const Json third = value_at(root, 3, "/n");
    EXPECT_TRUE(third.is_number_float());
    EXPECT_DOUBLE_EQ(third.get<double>(), 3.0 + 1.0 / 3.0);
}

TEST(Animation, ArraysInterpolateElementwise) {
    const SceneDocument root = doc(R"({"camera": {"position": [0, 1, 2]},
                "animate": {"/camera/position": [[0, [0, 1, 2]], [10, [10, -1, 2.5]]]}})");
    const Json p = value_at(root, 5, "/camera/position");
    ASSERT_EQ(p.size(), 3u);
    EXPECT_EQ(p[0].get<double>(), 5.0);
    EXPECT_EQ(p[1].get<double>(), 0.0);
    EXPECT_EQ(p[2].get<double>(), 2.25);
    EXPECT_EQ(value_at(root, 20, "/camera/position"), Json::parse("[10, -1, 2.5]"));
}

TEST(Animation, DatetimesParseToKnownInstants) {
    Datetime t;
    // 946684800 s: the Unix time of 2000-01-01T00:00:00Z; 1e9 s: 2001-09-09T01:46:40Z.
    ASSERT_TRUE(parse_datetime("2000-01-01T00:00:00Z", t));
    EXPECT_EQ(t.utc_ms, 946684800000);
    ASSERT_TRUE(parse_datetime("2001-09-09T03:46:40+02:00", t));
    EXPECT_EQ(t.utc_ms, 1000000000000);
    EXPECT_EQ(t.offset_minutes, 120);
    ASSERT_TRUE(parse_datetime("2001-09-08T21:16:40.25-0430", t));
    EXPECT_EQ(t.utc_ms, 1000000000250);
    EXPECT_EQ(format_datetime(t), "2001-09-08T21:16:40.250-04:30");
    ASSERT_TRUE(parse_datetime("2028-02-29T12:00", t));
    EXPECT_FALSE(t.has_zone);
    EXPECT_EQ(format_datetime(t), "2028-02-29T12:00:00");
    for (const char* bad : {"2027-02-29T00:00:00Z", "2026-13-01T00:00:00Z", "2026-06-21 18:00",
                            "2026-06-21T24:00:00Z", "2026-06-21T18:00:00+2", "sunset", ""}) {
        EXPECT_FALSE(parse_datetime(bad, t)) << bad;
    }
}

TEST(Animation, DatetimesInterpolateInTime) {
    const SceneDocument root = doc(R"({"sun": {"datetime": "2026-06-21T18:00:00+02:00"},
        "animate": {"/sun/datetime": [[0, "2026-06-21T18:00:00+02:00"],
                                      [240, "2026-06-21T20:00:00+02:00"]]}})");
    EXPECT_EQ(value_at(root, -1, "/sun/datetime"), "2026-06-21T18:00:00+02:00");
    EXPECT_EQ(value_at(root, 1, "/sun/datetime"), "2026-06-21T18:00:30+02:00");
    EXPECT_EQ(value_at(root, 120, "/sun/datetime"), "2026-06-21T19:00:00+02:00");
    EXPECT_EQ(value_at(root, 239, "/sun/datetime"), "2026-06-21T19:59:30+02:00");
    EXPECT_EQ(value_at(root, 240, "/sun/datetime"), "2026-06-21T20:00:00+02:00");
    EXPECT_EQ(value_at(root, 999, "/sun/datetime"), "2026-06-21T20:00:00+02:00");
}

TEST(Animation, DatetimesCrossMidnightYearsAndOffsets) {
    // One hour over three frames: 20 minutes a frame, across a year boundary.
    const SceneDocument root = doc(R"({"t": "2026-12-31T23:30:00Z",
        "animate": {"/t": [[0, "2026-12-31T23:30:00Z"], [3, "2027-01-01T00:30:00Z"]]}})");
    EXPECT_EQ(value_at(root, 1, "/t"), "2026-12-31T23:50:00Z");
    EXPECT_EQ(value_at(root, 2, "/t"), "2027-01-01T00:10:00Z");
    // Keys in different offsets: the same instants, written in the earlier key's offset.
    const SceneDocument dst = doc(R"({"t": "2026-03-29T00:00:00+01:00",
        "animate": {"/t": [[0, "2026-03-29T00:00:00+01:00"], [4, "2026-03-29T05:00:00+02:00"]]}})");
    EXPECT_EQ(value_at(dst, 2, "/t"), "2026-03-29T02:00:00+01:00");
    // Seven frames an hour: fractions of a second are kept to the millisecond.
    const SceneDocument sevenths = doc(R"({"t": "2026-06-21T18:00:00Z",
        "animate": {"/t": [[0, "2026-06-21T18:00:00Z"], [7, "2026-06-21T19:00:00Z"]]}})");
    EXPECT_EQ(value_at(sevenths, 1, "/t"), "2026-06-21T18:08:34.286Z");
}

TEST(Animation, FrameDocumentReplacesOnlyAnimatedValues) {
    const SceneDocument root = doc(kSun);
    const Json frame = frame_document(root, parse_animation(root), 120).json();
    EXPECT_FALSE(frame.contains("animate"));
    Json expected = root.json();
    expected.erase("animate");
    expected["sun"]["elevation_deg"] = 2;
    EXPECT_EQ(frame, expected);
}

TEST(Animation, SceneWithoutAnimateIsUnchanged) {
    SceneDocument root = doc(R"({"camera": {"position": [0, 1, 2]}, "film": {"spp": 3}})");
    const Json before = root.json();
    EXPECT_TRUE(parse_animation(root).empty());
    apply_animation(root, 17);
    EXPECT_EQ(root.json(), before);
}

TEST(Animation, AnimatedLightReachesTheParsedScene) {
    SceneDocument root =
        doc(R"({"lights": [{"type": "point", "position": [0, 1, 0], "intensity_cd": 100}],
        "animate": {"/lights/0/intensity_cd": [[0, 100], [10, 200]]}})");
    apply_animation(root, 5);
    const SceneDesc scene = parse_scene(root.json(), "anim.json");
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_FLOAT_EQ(std::get<PointLight>(scene.lights[0].emitter).intensity.g, 150.0f);
}

TEST(Animation, ErrorsNameFileAndPointer) {
    const std::string unknown =
        animation_error(R"({"sun": {}, "animate": {"/sun/elevation_deg": [[0, 1]]}})");
    EXPECT_NE(unknown.find("anim.json: /animate/~1sun~1elevation_deg"), std::string::npos)
        << unknown;
    EXPECT_NE(unknown.find("unknown pointer"), std::string::npos) << unknown;
    EXPECT_NE(animation_error(R"({"animate": {"/moon/x": [[0, 1]]}})").find("unknown pointer"),
              std::string::npos);
    EXPECT_NE(
        animation_error(R"({"a": [1, 2], "animate": {"/a/2": [[0, 1]]}})").find("unknown pointer"),
        std::string::npos);

    const std::string duplicate =
        animation_error(R"({"x": 1, "animate": {"/x": [[0, 1], [5, 2], [5, 3]]}})");
    EXPECT_NE(duplicate.find("anim.json: /animate/~1x/2/0 = 5: duplicate key frame"),
              std::string::npos)
        << duplicate;
    const std::string unsorted =
        animation_error(R"({"x": 1, "animate": {"/x": [[0, 1], [9, 2], [5, 3]]}})");
    EXPECT_NE(unsorted.find("/animate/~1x/2/0 = 5: unsorted key frame"), std::string::npos)
        << unsorted;

    const std::string mismatch =
        animation_error(R"({"p": [0, 0, 0], "animate": {"/p": [[0, [1, 2, 3]], [4, 7]]}})");
    EXPECT_NE(mismatch.find("/animate/~1p/1/1 = 7: type mismatch"), std::string::npos) << mismatch;
    EXPECT_NE(animation_error(R"({"p": [0, 0, 0], "animate": {"/p": [[0, [1, 2]]]}})")
                  .find("of length 3"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"x": 1, "animate": {"/x": [[0, "2026-06-21T18:00:00Z"]]}})")
                  .find("type mismatch"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"t": "2026-06-21T18:00:00Z",
                                  "animate": {"/t": [[0, "2026-06-21T18:00:00"]]}})")
                  .find("time zone"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"s": "fog", "animate": {"/s": [[0, "mist"]]}})")
                  .find("cannot animate /s"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"x": 1, "animate": {"/x": [[0.5, 1]]}})")
                  .find("/animate/~1x/0/0 = 0.5: expected an integer"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"x": 1, "animate": {"/x": [[0, 1, 2]]}})")
                  .find("/animate/~1x/0 = [0,1,2]: expected a keyframe"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"x": 1, "animate": {"/x": []}})").find("expected keyframes"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"x": 1, "animate": {"x": [[0, 1]]}})").find("JSON pointer"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"animate": {"/animate": [[0, 1]]}})").find("animation itself"),
              std::string::npos);
    EXPECT_NE(animation_error(R"({"animate": [1]})").find("/animate = [1]: expected an object"),
              std::string::npos);
}

}  // namespace
}  // namespace kasumi
