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

TEST(JsonText, OutOfRangeNumbersAreLocatedErrors) {
    EXPECT_EQ(error_of([] { parse_json_text("{\n  \"film\": {\"spp\": 1e999}}", "s.json"); }),
              "s.json: invalid JSON: line 2, column 19: number 1e999 is out of range at /film/spp "
              "(a double holds magnitudes up to 1.8e308)");
    EXPECT_EQ(error_of([] { parse_json_text("[1, -1e999]", "s.json"); }),
              "s.json: invalid JSON: line 1, column 5: number -1e999 is out of range at /1 (a "
              "double holds magnitudes up to 1.8e308)");
    const std::string digits(400, '9');  // an integer beyond any integer type and double
    EXPECT_NE(error_of([&] {
                  parse_json_text("{\"a\": " + digits + "}", "s.json");
              }).find("s.json: invalid JSON: line 1, column 7: number 999"),
              std::string::npos);
    // Below the smallest double a number rounds to zero: not an error.
    EXPECT_EQ(parse_json_text("[1e-999]", "s.json")[0].get<double>(), 0.0);
    EXPECT_EQ(parse_json_text("[1.7e308]", "s.json")[0].get<double>(), 1.7e308);
}

TEST(JsonText, DuplicateKeysAreLocatedErrors) {
    EXPECT_EQ(error_of([] {
                  parse_json_text("{\"film\": {\"spp\": 1,\n /* c \" */ \"spp\": 2}}", "s.json");
              }),
              "s.json: invalid JSON: line 2, column 12: duplicate key \"spp\" in /film (each key "
              "may appear once in an object)");
    EXPECT_EQ(
        error_of([] { parse_json_text(R"({"a": 1, "b": [{}], "a\u0000": 2, "a": 3})", "s.json"); }),
        "s.json: invalid JSON: line 1, column 35: duplicate key \"a\" in / (each key may "
        "appear once in an object)");
    EXPECT_NE(error_of([] {
                  parse_json_text(R"({"x": [{"k\"": 1, "k\"": 2}]})", "s.json");
              }).find("column 19: duplicate key \"k\"\" in /x/0"),
              std::string::npos);
    // The same key in different objects is fine.
    const Json j = parse_json_text(R"({"a": {"k": 1}, "b": {"k": 2}})", "s.json");
    EXPECT_EQ(j["b"]["k"], 2);
}

TEST(JsonText, NestingIsLimited) {
    const std::string deep = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
    EXPECT_EQ(error_of([&] { parse_json_text(deep, "s.json"); }), "");
    const std::string deeper = "{\"a\":\n" + std::string(kMaxJsonDepth, '[') + "{}" +
                               std::string(kMaxJsonDepth, ']') + "}";
    EXPECT_EQ(error_of([&] { parse_json_text(deeper, "s.json"); }),
              "s.json: invalid JSON: line 2, column 256: nested deeper than 256 levels");
}

TEST(JsonText, SyntaxErrorsKeepTheParsersPosition) {
    EXPECT_EQ(error_of([] { parse_json_text("{\"film\": {\"width\": 8,}}", "s.json"); }),
              "s.json: invalid JSON: parse error at line 1, column 22: syntax error while parsing "
              "object key - unexpected '}'; expected string literal");
    EXPECT_EQ(parse_json_if_json("not json", "v"), std::nullopt);
    EXPECT_EQ(parse_json_if_json("[1, // c\n 2]", "v"), std::nullopt);  // no comments
    EXPECT_EQ(*parse_json_if_json("[1, 2]", "v"), Json::parse("[1, 2]"));
    EXPECT_NE(error_of([] { parse_json_if_json("[1e999]", "--set /x"); }).find("--set /x: "),
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
