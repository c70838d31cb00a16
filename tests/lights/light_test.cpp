#include "lights/light_json.h"

#include "core/error.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

Light parse(const std::string& text) {
    static Json doc;  // JsonNode refers into the document
    doc = parse_json_text(text, "lights.json");
    return parse_light(JsonNode(doc, "lights.json", "/lights/0"), 0);
}

TEST(PointLight, InverseSquareLaw) {
    const Light light = parse(R"({"type": "point", "position": [0, 2, 0], "intensity_cd": 100})");
    for (float r : {0.5f, 1.0f, 2.0f, 4.0f, 100.0f}) {
        const IncidentLight in = incident_light(light, Vec3(0.0f, 2.0f - r, 0.0f));
        EXPECT_NEAR(in.irradiance.g, 100.0f / (r * r), 1e-5f * 100.0f / (r * r)) << r;
        EXPECT_NEAR(in.distance, r, 1e-5f * r);
        EXPECT_NEAR(glm::dot(in.wi, Vec3(0, 1, 0)), 1.0f, 1e-6f);
    }
}

TEST(PointLight, FluxIsFourPiIntensity) {
    const Light light = parse(R"({"type": "point", "position": [0, 0, 0], "flux_lm": 1000})");
    EXPECT_NEAR(luminance(std::get<PointLight>(light.emitter).intensity), 1000.0f / (4.0f * kPi),
                1e-3f);
    EXPECT_NEAR(luminous_flux_lm(light), 1000.0f, 1e-2f);
}

TEST(Light, ColourKeepsThePhotometricAmount) {
    const Light light = parse(
        R"({"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 50, "color": [1, 0.5, 0.2]})");
    const Rgb e = incident_light(light, Vec3(0.0f)).irradiance;
    EXPECT_NEAR(luminance(e), 50.0f, 1e-4f);
    EXPECT_NEAR(e.g / e.r, 0.5f, 1e-6f);
}

TEST(DirectionalLight, WiIsOppositeTheTravelDirection) {
    const Light light =
        parse(R"({"type": "directional", "direction": [0, -2, 0], "illuminance_lux": 3})");
    const IncidentLight in = incident_light(light, Vec3(5.0f));
    EXPECT_EQ(in.wi, Vec3(0, 1, 0));
    EXPECT_GE(in.distance, kInfinity);
    EXPECT_EQ(in.irradiance, Rgb(3.0f));
}

std::string error_of(const std::string& text) {
    try {
        parse(text);
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        return e.what();
    }
    return "";
}

TEST(LightJson, BadInputIsLocated) {
    EXPECT_NE(error_of(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": -1})")
                  .find("/lights/0/intensity_cd"),
              std::string::npos);
    EXPECT_NE(
        error_of(R"({"type": "point", "position": [0, 0, 0]})").find("intensity_cd or flux_lm"),
        std::string::npos);
    EXPECT_NE(
        error_of(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "flux_lm": 2})")
            .find("not both"),
        std::string::npos);
    EXPECT_NE(error_of(R"({"type": "directional", "direction": [0, 0, 0], "illuminance_lux": 1})")
                  .find("/lights/0/direction"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"type": "laser"})").find("unknown light type"), std::string::npos);
    EXPECT_NE(
        error_of(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "colour": 1})")
            .find("unknown key \"colour\""),
        std::string::npos);
}

}  // namespace
}  // namespace kasumi
