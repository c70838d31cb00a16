#include "surface/material.h"

#include "test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

using test::input_error_of;

Material parse(const std::string& text) {
    static Json json;  // JsonNode does not own its document
    json = parse_json_text(text, "scene.json");
    return parse_material(JsonNode(json, "scene.json", "/materials/red"));
}

TEST(Material, DefaultsAreDocumented) {
    const auto m = std::get<PhongMaterial>(parse(R"({"type": "phong"})"));
    EXPECT_EQ(m.ka, Rgb(0.0f));
    EXPECT_EQ(m.kd, Rgb(0.8f));
    EXPECT_EQ(m.ks, Rgb(0.0f));
    EXPECT_EQ(m.n, 20.0f);
}

TEST(Material, ScalarAndRgbReflectances) {
    const auto m = std::get<PhongMaterial>(
        parse(R"({"type": "phong", "ka": 0.1, "kd": [0.5, 0.25, 1], "ks": 0.2, "n": 0})"));
    EXPECT_EQ(m.ka, Rgb(0.1f));
    EXPECT_EQ(m.kd, Rgb(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(m.ks, Rgb(0.2f));
    EXPECT_EQ(m.n, 0.0f);
    EXPECT_EQ(albedo(Material(m)), Rgb(0.5f, 0.25f, 1.0f));
}

TEST(Material, ReflectanceAboveOneIsRejected) {
    const std::string message =
        input_error_of([] { parse(R"({"type": "phong", "kd": [0.5, 1.2, 0.5]})"); });
    EXPECT_NE(message.find("scene.json: /materials/red/kd"), std::string::npos) << message;
    EXPECT_NE(message.find("[0, 1]"), std::string::npos) << message;
}

TEST(Material, NegativeValuesAreRejected) {
    EXPECT_NE(
        input_error_of([] { parse(R"({"type": "phong", "ka": -0.1})"); }).find("/materials/red/ka"),
        std::string::npos);
    EXPECT_NE(
        input_error_of([] { parse(R"({"type": "phong", "n": -1})"); }).find("/materials/red/n"),
        std::string::npos);
}

TEST(Material, UnknownKeyIsRejected) {
    const std::string message = input_error_of([] { parse(R"({"type": "phong", "kD": 0.5})"); });
    EXPECT_NE(message.find("/materials/red/kD"), std::string::npos) << message;
}

TEST(Material, UnknownTypeListsKnownTypes) {
    const std::string message = input_error_of([] { parse(R"({"type": "lambert"})"); });
    EXPECT_NE(message.find("/materials/red/type"), std::string::npos) << message;
    EXPECT_NE(message.find("phong"), std::string::npos) << message;
}

TEST(Material, MirrorAndDielectricParse) {
    const auto mirror = std::get<MirrorMaterial>(parse(R"({"type": "mirror"})"));
    EXPECT_EQ(mirror.kr, Rgb(1.0f));
    EXPECT_EQ(std::get<MirrorMaterial>(parse(R"({"type": "mirror", "kr": [0.9, 0.8, 0.7]})")).kr,
              Rgb(0.9f, 0.8f, 0.7f));
    const auto glass =
        std::get<DielectricMaterial>(parse(R"({"type": "dielectric", "ior": 1.33})"));
    EXPECT_EQ(glass.ior, 1.33f);
    EXPECT_EQ(glass.tint, Rgb(1.0f));
    const Material tinted = parse(R"({"type": "dielectric", "ior": 1.5, "tint": [1, 0.9, 0.8]})");
    EXPECT_EQ(albedo(tinted), Rgb(1.0f, 0.9f, 0.8f));
    EXPECT_TRUE(is_specular(tinted));
    EXPECT_FALSE(is_specular(parse(R"({"type": "phong"})")));
    EXPECT_EQ(
        std::get<PhongMaterial>(parse(R"({"type": "phong", "ks_fresnel": "exact"})")).ks_fresnel,
        SpecularFresnel::Exact);
}

TEST(Material, BadMirrorAndDielectricValuesNameThePath) {
    std::string message = input_error_of([] { parse(R"({"type": "mirror", "kr": 1.2})"); });
    EXPECT_NE(message.find("scene.json: /materials/red/kr"), std::string::npos) << message;
    for (const char* text :
         {R"({"type": "dielectric", "ior": 0})", R"({"type": "dielectric", "ior": -1.5})"}) {
        message = input_error_of([&] { parse(text); });
        EXPECT_NE(message.find("scene.json: /materials/red/ior"), std::string::npos) << message;
    }
    message = input_error_of([] { parse(R"({"type": "dielectric"})"); });
    EXPECT_NE(message.find("ior"), std::string::npos) << message;
    message = input_error_of([] { parse(R"({"type": "dielectric", "ior": 1.5, "tint": 2})"); });
    EXPECT_NE(message.find("/materials/red/tint"), std::string::npos) << message;
    message = input_error_of([] { parse(R"({"type": "phong", "ks_fresnel": "fast"})"); });
    EXPECT_NE(message.find("/materials/red/ks_fresnel"), std::string::npos) << message;
    message = input_error_of([] { parse(R"({"type": "mirror", "ior": 1.5})"); });
    EXPECT_NE(message.find("/materials/red/ior"), std::string::npos) << message;
}

TEST(Material, MissingTypeIsRejected) {
    EXPECT_NE(input_error_of([] { parse(R"({"kd": 0.5})"); }).find("type"), std::string::npos);
}

}  // namespace
}  // namespace kasumi
