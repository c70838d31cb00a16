// The scene document: JSON pointers (RFC 6901) read and written like `mkdir -p`, "-" appending,
// located errors for a pointer that cannot be followed, and --set values read as JSON or words.
#include "scene/scene_document.h"

#include "core/error.h"
#include "scene/json_pointer.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

SceneDocument doc(const std::string& text) {
    return SceneDocument(parse_json_text(text, "d.json"), "d.json");
}

/// The message of the input error `set` throws ("" if none).
std::string set_error(SceneDocument d, const std::string& pointer) {
    try {
        d.set(pointer, 1, "--set");
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        return e.what();
    }
    return "";
}

TEST(JsonPointer, TokensUnescapeAndRoundTrip) {
    EXPECT_EQ(*pointer_tokens("/a~1b/c~0d/0"), (std::vector<std::string>{"a/b", "c~d", "0"}));
    EXPECT_TRUE(pointer_tokens("")->empty());
    EXPECT_EQ(*pointer_tokens("/"), std::vector<std::string>{""});
    EXPECT_EQ(pointer_from_tokens({"a/b", "c~d", "0"}), "/a~1b/c~0d/0");
    EXPECT_FALSE(pointer_tokens("a/b"));
    EXPECT_FALSE(pointer_tokens("/a~2"));
    EXPECT_FALSE(pointer_tokens("/a~"));
}

TEST(JsonPointer, ArrayIndicesHaveNoLeadingZero) {
    EXPECT_EQ(array_index("0"), size_t{0});
    EXPECT_EQ(array_index("12"), size_t{12});
    EXPECT_FALSE(array_index("01"));
    EXPECT_FALSE(array_index("-"));
    EXPECT_FALSE(array_index("1x"));
    EXPECT_FALSE(array_index(""));
}

TEST(SceneDocument, GetAndFind) {
    const SceneDocument d = doc(R"({"a": {"b/c": [1, 2]}, "t~": 3})");
    EXPECT_EQ(d.get("/a/b~1c/1"), 2);
    EXPECT_EQ(d.get("/t~0"), 3);
    EXPECT_EQ(d.get(""), d.json());
    EXPECT_EQ(d.find("/a/b~1c/2"), nullptr);
    EXPECT_EQ(d.find("/a/x"), nullptr);
    EXPECT_EQ(d.find("/t~0/0"), nullptr);
    EXPECT_FALSE(d.contains("/a/b~1c/01"));
    try {
        d.get("/a/x");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        EXPECT_EQ(std::string(e.what()), "d.json: /a/x: does not exist in the scene");
    }
}

TEST(SceneDocument, SetCreatesMissingParentsLikeMkdirP) {
    SceneDocument d = doc(R"({"render": {"seed": 1}})");
    d.set("/render/radiosity/patch_size_m", 0.1);
    d.set("/film/width", 8);
    EXPECT_EQ(d.json(), Json::parse(R"({"render": {"seed": 1, "radiosity": {"patch_size_m": 0.1}},
                                        "film": {"width": 8}})"));
    d.set("/render/seed", 2);  // replaces
    EXPECT_EQ(d.get("/render/seed"), 2);
    d.set("/a~1b/c~0", true);
    EXPECT_EQ(d.json()["a/b"]["c~"], true);
    d.set("", Json::object());  // the whole document
    EXPECT_EQ(d.json(), Json::object());
}

TEST(SceneDocument, DashAppendsAndIndicesReplace) {
    SceneDocument d = doc(R"({"lights": [{"n": 0}]})");
    d.set("/lights/-", Json{{"n", 1}});
    d.set("/lights/0/n", 5);
    d.set("/lights/1", Json{{"n", 2}});
    EXPECT_EQ(d.json(), Json::parse(R"({"lights": [{"n": 5}, {"n": 2}]})"));
    d.set("/media/-", Json{{"type", "fog"}});  // a missing array before "-"
    EXPECT_EQ(d.json()["media"], Json::parse(R"([{"type": "fog"}])"));
}

TEST(SceneDocument, UnfollowablePointersAreLocatedErrors) {
    const SceneDocument d = doc(R"({"shapes": [{"r": 1}, {"r": 2}], "film": {"width": 8}})");
    EXPECT_EQ(
        set_error(d, "/shapes/9/r"),
        "d.json: --set /shapes/9/r: index 9 is past the end of /shapes (2 elements; - appends)");
    EXPECT_EQ(
        set_error(d, "/shapes/2"),
        "d.json: --set /shapes/2: index 2 is past the end of /shapes (2 elements; - appends)");
    EXPECT_EQ(set_error(d, "/shapes/x"),
              "d.json: --set /shapes/x: \"x\" is not an array index (0, 1, ... or - to append)");
    EXPECT_EQ(set_error(d, "/shapes/01"),
              "d.json: --set /shapes/01: \"01\" is not an array index (0, 1, ... or - to append)");
    EXPECT_EQ(set_error(d, "/shapes/-/r"),
              "d.json: --set /shapes/-/r: \"-\" is not an array index (0, 1, ... or - to append)");
    EXPECT_EQ(set_error(d, "/film/width/0"),
              "d.json: --set /film/width/0: /film/width is not an object or array");
    EXPECT_EQ(set_error(d, "/film/~2"), "d.json: --set /film/~2: invalid JSON pointer");
    EXPECT_EQ(set_error(d, "/film/height"), "");
}

TEST(SceneDocument, OverrideValuesAreJsonElseWords) {
    auto value = [](const std::string& text) {
        return override_value(Override{"/x", text}, "d.json");
    };
    EXPECT_EQ(value("3"), 3);
    EXPECT_EQ(value("[1, 2]"), Json::parse("[1, 2]"));
    EXPECT_EQ(value("\"path\""), "path");
    EXPECT_EQ(value("path"), "path");
    EXPECT_EQ(value("2 // no comments in a value"), "2 // no comments in a value");
    EXPECT_EQ(value("{\"a\": 1"), "{\"a\": 1");
    for (const char* refused : {"1e999", "-1e999", "{\"a\": 1, \"a\": 2}"}) {
        try {
            value(refused);
            FAIL() << "no error for " << refused;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input);
            EXPECT_EQ(
                std::string(e.what()).rfind("d.json: --set /x: invalid JSON: line 1, column ", 0),
                0u)
                << e.what();
        }
    }
}

TEST(SceneDocument, MalformedOverridesAreUsageErrors) {
    for (const char* text : {"film/width=3", "/film/width", "/film/~x=3", ""}) {
        try {
            parse_override(text);
            FAIL() << "no error for " << text;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Usage) << text;
        }
    }
    const Override o = parse_override("/a/b=c=d");
    EXPECT_EQ(o.pointer, "/a/b");
    EXPECT_EQ(o.value, "c=d");
}

}  // namespace
}  // namespace kasumi
