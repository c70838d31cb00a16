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

TEST(LightJson, ExtendedLightsAndShadowSettings) {
    const Light polygon = parse(R"({"type": "polygon", "luminance_cd_m2": 10, "samples": 32,
        "shadows": "none", "vertices": [[0, 2, 0], [1, 2, 0], [1, 2, 1], [0, 2, 1]]})");
    EXPECT_FALSE(is_delta(polygon));
    EXPECT_EQ(polygon.samples, 32);
    EXPECT_EQ(polygon.shadow_probes, 0);
    const Light probed = parse(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1,
        "luminance_cd_m2": 1, "samples": 64, "shadow_probes": 16})");
    EXPECT_EQ(probed.shadow_probes, 16);
    EXPECT_EQ(polygon.shadows, ShadowMode::None);
    EXPECT_EQ(light_type_name(polygon), "polygon");
    const Light spot = parse(R"({"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0],
        "intensity_cd": 1, "cone_deg": 30})");
    EXPECT_TRUE(is_delta(spot));
    EXPECT_EQ(spot.shadows, ShadowMode::Ray);
    EXPECT_EQ(light_type_name(spot), "spot");
}

TEST(LightJson, BadExtendedLightsAreLocated) {
    const auto has = [](const std::string& text, const std::string& what) {
        const std::string e = error_of(text);
        EXPECT_NE(e.find(what), std::string::npos) << e;
    };
    has(R"({"type": "polygon", "luminance_cd_m2": 1, "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0]]})",
        "lights.json: /lights/0/vertices = [[0,0,0],[1,0,0],[2,0,0]]: the polygon has zero area");
    has(R"({"type": "polygon", "luminance_cd_m2": -1, "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]]})",
        "/lights/0/luminance_cd_m2 = -1: must be >= 0");
    has(R"({"type": "sphere", "center": [0, 0, 0], "radius": 0, "luminance_cd_m2": 1})",
        "/lights/0/radius = 0: must be > 0");
    has(R"({"type": "line", "from": [1, 1, 1], "to": [1, 1, 1], "intensity_cd_per_m": 1})",
        "from != to");
    has(R"({"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0], "intensity_cd": 1,
        "cone_deg": 30, "falloff_deg": 40})",
        "/lights/0/falloff_deg = 40: must be in [0, cone_deg]");
    has(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "luminance_cd_m2": 1,
        "shadows": "shadow-volume"})",
        "/lights/0/shadows = \"shadow-volume\": \"shadow-volume\" shadows need a point, spot, "
        "goniometric or directional light");
    has(R"({"type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
        "luminance_cd_m2": 1, "shadows": "scanline"})",
        "/lights/0/shadows = \"scanline\": \"scanline\" shadows need a point, spot, "
        "goniometric or directional light");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1,
        "shadow_map": {"resolution": 512}})",
        "/lights/0/shadow_map = {\"resolution\":512}: shadow_map applies to lights with");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "shadows": "map",
        "shadow_map": {"resolution": 8}})",
        "/lights/0/shadow_map/resolution = 8: must be an integer in [16, 8192]");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "shadows": "map",
        "shadow_map": {"views": 4}})",
        "/lights/0/shadow_map/views = 4: views applies to line, polygon and sphere lights");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "shadows": "map",
        "shadow_map": {"resolution": 8192}})",
        "the limit is 2^28");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "shadows": "map",
        "shadow_map": {"pcf": 1}})",
        "/lights/0/shadow_map/pcf");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "shadows": "soft"})",
        "unknown shadow mode");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "samples": 4})",
        "/lights/0/samples = 4: samples applies to line, polygon and sphere lights");
    has(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "luminance_cd_m2": 1,
        "samples": 0})",
        "/lights/0/samples = 0: must be an integer in [1, 4096]");
    has(R"({"type": "point", "position": [0, 0, 0], "intensity_cd": 1, "shadow_probes": 2})",
        "/lights/0/shadow_probes = 2: shadow_probes applies to line, polygon and sphere lights");
    has(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "luminance_cd_m2": 1,
        "samples": 8, "shadow_probes": 9})",
        "/lights/0/shadow_probes = 9: must be an integer in [0, samples = 8]");
    has(R"({"type": "goniometric", "position": [0, 0, 0], "ies": "nowhere.ies"})",
        "lights.json: /lights/0/ies = \"nowhere.ies\": nowhere.ies: cannot open IES file");
}

}  // namespace
}  // namespace kasumi
