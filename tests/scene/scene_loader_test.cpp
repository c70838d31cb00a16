// Scene files: every documented key is read into the description, overrides apply by JSON
// pointer, and each class of bad input is an input error naming file and JSON path.
#include "core/error.h"
#include "scene/scene_document.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

TEST(SceneLoader, DocumentedKeysAreRead) {
    const SceneDesc s = scene_from_text(R"({
        // comments are allowed
        "camera": {"position": [1, 2, 3], "look_at": [0, 1, 0], "up": [0, 2, 0], "fov_deg": 35},
        "film": {"width": 320, "height": 200, "spp": 7},
        "ambient": [0.1, 0.2, 0.3], "background": 0.5,
        "materials": {"m": {"type": "phong", "ka": 0.1, "kd": [0.2, 0.3, 0.4], "ks": 0.25, "n": 12}},
        "shapes": [{"type": "sphere", "center": [0, 1, 0], "radius": 2, "material": "m"}],
        "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 20, "name": "sun"},
                   {"type": "point", "position": [1, 1, 1], "intensity_cd": 30}],
        "media": [{"type": "homogeneous", "bounds": [[-1, -2, -3], [1, 2, 3]], "sigma_a": 0.01,
                   "sigma_s": [0.1, 0.2, 0.3], "phase": {"model": "hg", "g": 0.5}}],
        "render": {"seed": 9, "threads": 2, "tile_size": 8, "shadows": false,
                   "volume": {"step_m": 0.3, "light_sampling": "all"},
                   "preview": {"view": "Un-tone-mapped", "exposure_stops": -1}}})");
    EXPECT_EQ(s.camera.position, Vec3(1, 2, 3));
    EXPECT_EQ(s.camera.look_at, Vec3(0, 1, 0));
    EXPECT_EQ(s.camera.up, Vec3(0, 1, 0));
    EXPECT_EQ(s.camera.fov_deg, 35.0f);
    EXPECT_EQ(s.film.width, 320);
    EXPECT_EQ(s.film.height, 200);
    EXPECT_EQ(s.film.spp, 7);
    EXPECT_EQ(s.ambient, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.background, Rgb(0.5f));
    ASSERT_EQ(s.materials.size(), 1u);
    const auto& m = std::get<PhongMaterial>(s.materials[0]);
    EXPECT_EQ(m.ka, Rgb(0.1f));
    EXPECT_EQ(m.kd, Rgb(0.2f, 0.3f, 0.4f));
    EXPECT_EQ(m.ks, Rgb(0.25f));
    EXPECT_EQ(m.n, 12.0f);
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(std::get<SphereShape>(s.shapes[0].geometry).radius, 2.0f);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].name, "sun");
    EXPECT_EQ(s.lights[1].name, "light1");
    EXPECT_EQ(std::get<PointLight>(s.lights[1].emitter).intensity, Rgb(30.0f));
    ASSERT_EQ(s.media.size(), 1u);
    const auto& fog = std::get<HomogeneousMedium>(s.media[0].model);
    EXPECT_EQ(fog.bounds->min, Vec3(-1, -2, -3));
    EXPECT_EQ(fog.sigma_s, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(std::get<HenyeyGreenstein>(fog.phase).g, 0.5f);
    EXPECT_EQ(s.render.seed, 9u);
    EXPECT_EQ(s.render.threads, 2);
    EXPECT_EQ(s.render.tile_size, 8);
    EXPECT_FALSE(s.render.shadows);
    EXPECT_EQ(s.render.volume.step_m, 0.3f);
    EXPECT_EQ(s.render.volume.light_sampling, LightSampling::All);
    EXPECT_EQ(s.render.preview.view, "Un-tone-mapped");
    EXPECT_EQ(s.render.preview.exposure_stops, -1.0f);
}

TEST(SceneLoader, OverridesApplyByPointer) {
    SceneDocument doc(parse_json_text(R"({"film": {"width": 10}, "media": [{"type": "homogeneous",
        "sigma_a": 0, "sigma_s": 1, "phase": {"model": "hg", "g": 0.1}}]})",
                                      "o.json"),
                      "o.json");
    apply_overrides(doc, {parse_override("/film/width=20"), parse_override("/media/0/phase/g=0.7"),
                          parse_override("/film/spp=3"), parse_override("/render={\"seed\": 4}")});
    const SceneDesc s = parse_scene(doc.json(), "o.json");
    EXPECT_EQ(s.film.width, 20);
    EXPECT_EQ(s.film.spp, 3);
    EXPECT_EQ(s.render.seed, 4u);
    EXPECT_FLOAT_EQ(
        std::get<HenyeyGreenstein>(std::get<HomogeneousMedium>(s.media[0].model).phase).g, 0.7f);
}

TEST(SceneLoader, OverrideValueThatIsNotJsonIsAString) {
    SceneDocument doc(parse_json_text(R"({"render": {"preview": {"view": "Raw"}}})", "o.json"),
                      "o.json");
    apply_overrides(doc, {parse_override("/render/preview/view=Un-tone-mapped")});
    EXPECT_EQ(parse_scene(doc.json(), "o.json").render.preview.view, "Un-tone-mapped");
}

struct BadScene {
    const char* text;
    const char* expected_in_message;
};

class SceneLoaderErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneLoaderErrors, NameFileAndPath) {
    try {
        scene_from_text(GetParam().text);
        FAIL() << "no error for " << GetParam().text;
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        const std::string message = e.what();
        EXPECT_NE(message.find("test.json"), std::string::npos) << message;
        EXPECT_NE(message.find(GetParam().expected_in_message), std::string::npos) << message;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Classes, SceneLoaderErrors,
    ::testing::Values(
        BadScene{R"({"camra": {}})", "unknown key \"camra\""},
        BadScene{R"({"film": {"width": 0}})", "/film/width"},
        BadScene{R"({"film": {"spp": 1.5}})", "/film/spp"},
        BadScene{R"({"camera": {"fov_deg": 180}})", "/camera/fov_deg"},
        BadScene{R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 0]}})", "/camera"},
        BadScene{R"({"media": [{"type": "homogeneous", "sigma_a": -0.1, "sigma_s": 0}]})",
                 "/media/0/sigma_a"},
        BadScene{R"({"media": [{"type": "homogeneous", "sigma_a": 0, "sigma_s": [1, -1, 1]}]})",
                 "/media/0/sigma_s"},
        BadScene{
            R"({"media": [{"type": "homogeneous", "sigma_a": 0, "sigma_s": 1, "phase": {"model": "hg", "g": 1.0}}]})",
            "/media/0/phase/g"},
        BadScene{
            R"({"media": [{"type": "homogeneous", "sigma_a": 0, "sigma_s": 1, "phase": {"model": "hg", "g": -1.5}}]})",
            "/media/0/phase/g"},
        BadScene{
            R"({"media": [{"type": "homogeneous", "bounds": [[0, 0, 0], [1, -1, 1]], "sigma_a": 0, "sigma_s": 1}]})",
            "/media/0/bounds"},
        BadScene{R"({"lights": [{"type": "point", "position": [0, 0], "intensity_cd": 1}]})",
                 "/lights/0/position"},
        BadScene{
            R"({"shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "nope"}]})",
            "/shapes/0/material"},
        BadScene{R"({"shapes": [{"type": "mesh", "file": "missing.obj", "material": "m"}],
                     "materials": {"m": {"type": "phong"}}})",
                 "missing.obj"},
        BadScene{R"({"render": {"volume": {"step_m": 0}}})", "/render/volume/step_m"},
        BadScene{R"({"render": {"volume": {"shadow_roulette": 1.5}}})",
                 "/render/volume/shadow_roulette"},
        BadScene{R"({"render": {"volume": {"shadow_roulette": -0.1}}})",
                 "/render/volume/shadow_roulette"}));

TEST(SceneLoader, MissingFileAndBadJson) {
    EXPECT_THROW(load_scene("/nonexistent/scene.json"), Error);
    EXPECT_THROW(parse_json_text("{\"a\": [1, 2}", "bad.json"), Error);
}

TEST(SceneLoader, OverrideCreatesMissingParents) {
    SceneDocument doc(parse_json_text("{}", "o.json"), "o.json");
    apply_overrides(doc, {parse_override("/film/width=3"),
                          parse_override("/render/radiosity/patch_size_m=0.1")});
    const SceneDesc s = parse_scene(doc.json(), "o.json");
    EXPECT_EQ(s.film.width, 3);
    EXPECT_FLOAT_EQ(s.render.radiosity.patch_size_m, 0.1f);
    EXPECT_THROW(parse_override("film/width=3"), Error);
}

}  // namespace
}  // namespace kasumi
