#include "core/json_node.h"

#include "core/error.h"
#include "core/json_choice.h"
#include "core/json_int.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        return e.what();
    }
    return "";
}

TEST(JsonNode, CommentsAreAllowed) {
    const Json j = parse_json_text("{ // a comment\n \"a\": /* inline */ 1 }", "s.json");
    EXPECT_EQ(j["a"].get<int>(), 1);
}

TEST(JsonNode, ParseErrorNamesFile) {
    EXPECT_NE(error_of([] { parse_json_text("{ \"a\": }", "bad.json"); }).find("bad.json"),
              std::string::npos);
}

TEST(JsonNode, RangeErrorNamesFileAndPointer) {
    const Json j = parse_json_text(R"({"media": [{"phase": {"g": 1.2}}]})", "scene.json");
    const JsonNode root(j, "scene.json");
    const std::string message = error_of(
        [&] { root.child("media").child(0).child("phase").child("g").in_open(-1.0f, 1.0f); });
    EXPECT_EQ(message, "scene.json: /media/0/phase/g = 1.2: must be in (-1, 1)");
}

TEST(JsonNode, UnknownKeyIsReported) {
    const Json j = parse_json_text(R"({"width": 3, "widht": 4})", "f.json");
    JsonObjectReader reader(JsonNode(j, "f.json", "/film"));
    EXPECT_EQ(reader.required("width").as_int(), 3);
    const std::string message = error_of([&] { reader.finish(); });
    EXPECT_NE(message.find("/film/widht"), std::string::npos) << message;
    EXPECT_NE(message.find("unknown key"), std::string::npos) << message;
}

TEST(JsonNode, RgbAcceptsScalarOrTriple) {
    const Json j = parse_json_text(R"({"a": 0.5, "b": [1, 2, 3], "c": [1, 2]})", "f.json");
    const JsonNode root(j, "f.json");
    EXPECT_EQ(root.child("a").as_rgb(), Rgb(0.5f));
    EXPECT_EQ(root.child("b").as_rgb(), Rgb(1, 2, 3));
    EXPECT_FALSE(error_of([&] { root.child("c").as_rgb(); }).empty());
}

TEST(JsonNode, NegativeCoefficientIsRejected) {
    const Json j = parse_json_text(R"({"sigma_a": [0.1, -0.2, 0.3]})", "f.json");
    const JsonNode root(j, "f.json");
    EXPECT_NE(error_of([&] { root.child("sigma_a").non_negative_rgb(); }).find("/sigma_a"),
              std::string::npos);
}

TEST(JsonNode, PointerEscapesKeys) {
    EXPECT_EQ(json_pointer_escape("a/b~c"), "a~1b~0c");
}

TEST(JsonNode, ChoicesAndRangedIntegersNameWhatTheyExpect) {
    const Json j =
        parse_json_text(R"({"a": "cone", "b": "disc", "c": 2, "n": 65, "m": 1.5})", "s.json");
    const JsonNode root(j, "s.json");
    enum class Filter { Box, Cone, Epanechnikov };
    const auto filter = [&](const char* key) {
        return parse_choice<Filter>(
            root.child(key),
            {{"box", Filter::Box}, {"cone", Filter::Cone}, {"epanechnikov", Filter::Epanechnikov}});
    };
    EXPECT_EQ(filter("a"), Filter::Cone);
    EXPECT_EQ(error_of([&] { filter("b"); }),
              "s.json: /b = \"disc\": expected \"box\", \"cone\" or \"epanechnikov\"");
    EXPECT_EQ(error_of([&] {
                  parse_choice<bool>(root.child("b"), {{"on", true}, {"off", false}});
              }),
              "s.json: /b = \"disc\": expected \"on\" or \"off\"");
    EXPECT_NE(error_of([&] { filter("c"); }).find("/c = 2: expected a string"), std::string::npos);
    EXPECT_EQ(parse_int_in(root.child("c"), 0, 64), 2);
    EXPECT_EQ(error_of([&] { parse_int_in(root.child("n"), 0, 64); }),
              "s.json: /n = 65: must be an integer in [0, 64]");
    EXPECT_NE(error_of([&] { parse_int_in(root.child("m"), 0, 64); }).find("expected an integer"),
              std::string::npos);
}

}  // namespace
}  // namespace kasumi
