// render.quality: the levels fill only what the scene leaves unset, unknown levels are located
// input errors, and the single-scattering bound omega p / (1 - omega p) with its exact inputs.
#include "scene/quality.h"
#include "core/error.h"
#include "scene/plan.h"
#include "scene/scene_loader.h"
#include "volume/grid/density_grid.h"
#include "volume/medium.h"
#include "volume/transmittance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace kasumi {
namespace {

SceneDocument doc_with(const std::string& text) {
    return SceneDocument(parse_json_text(text, "test.json"), "test.json");
}

TEST(Quality, NamesRoundTrip) {
    for (QualityLevel l : {QualityLevel::Draft, QualityLevel::Default, QualityLevel::Final,
                           QualityLevel::Reference}) {
        EXPECT_EQ(quality_from_name(quality_name(l)), l);
    }
    EXPECT_FALSE(quality_from_name("best").has_value());
}

TEST(Quality, LevelsGrowMonotonically) {
    // Each level spends at least as much as the one below and accepts no more left-out light.
    for (int i = 1; i < 4; ++i) {
        const QualityPreset& lo = quality_preset(static_cast<QualityLevel>(i - 1));
        const QualityPreset& hi = quality_preset(static_cast<QualityLevel>(i));
        EXPECT_GE(hi.spp, lo.spp);
        EXPECT_LE(hi.fog_step_m, lo.fog_step_m);
        EXPECT_LE(hi.height_fog_step_m, lo.height_fog_step_m);
        EXPECT_GE(hi.light_samples, lo.light_samples);
        EXPECT_LE(hi.single_scattering_tolerance, lo.single_scattering_tolerance);
    }
}

TEST(Quality, FillsOnlyUnsetKeys) {
    SceneDocument doc = doc_with(R"({
      "film": {"width": 8},
      "lights": [{"type": "point", "position": [0, 1, 0], "intensity_cd": 1},
                 {"type": "sphere", "center": [0, 2, 0], "radius": 0.1, "luminance_cd_m2": 1},
                 {"type": "polygon", "luminance_cd_m2": 1, "samples": 3,
                  "vertices": [[0, 3, 0], [1, 3, 0], [1, 3, 1]]}],
      "media": [{"type": "homogeneous", "sigma_a": 0.1, "sigma_s": 0.1}],
      "render": {"quality": "final", "volume": {"step_m": 0.7}}
    })");
    const QualityChoice c = apply_quality(doc);
    const QualityPreset& p = quality_preset(QualityLevel::Final);
    ASSERT_EQ(c.level, QualityLevel::Final);
    EXPECT_EQ(doc.json()["film"]["spp"].get<int>(), p.spp);
    EXPECT_EQ(doc.json()["render"]["volume"]["step_m"].get<double>(), 0.7);  // the scene's wins
    EXPECT_FALSE(doc.json()["lights"][0].contains("samples"));               // delta light
    EXPECT_EQ(doc.json()["lights"][1]["samples"].get<int>(), p.light_samples);
    EXPECT_EQ(doc.json()["lights"][2]["samples"].get<int>(), 3);         // the scene's wins
    EXPECT_FALSE(doc.json()["render"]["volume"].contains("estimator"));  // no grid
    EXPECT_EQ(c.kept.size(), 2u);
}

// Height fog: the level sets its step and estimator (march: closed-form transmittance, the
// height-fog studies' choice) unless the scene gives them; a homogeneous medium's step and a
// grid's estimator take precedence (the set then takes the general paths they were measured on);
// the plan's expected error names the height-fog figure.
TEST(Quality, HeightFogTakesItsOwnStepAndEstimator) {
    const std::string fog = R"({"type": "height_fog", "sigma_s": 0.1, "scale_height_m": 5})";
    const QualityPreset& p = quality_preset(QualityLevel::Default);
    SceneDocument doc =
        doc_with(R"({"media": [)" + fog + R"(], "render": {"quality": "default"}})");
    QualityChoice c = apply_quality(doc);
    EXPECT_EQ(doc.json()["render"]["volume"]["step_m"].get<double>(), p.height_fog_step_m);
    EXPECT_EQ(doc.json()["render"]["volume"]["estimator"].get<std::string>(),
              p.height_fog_estimator);
    EXPECT_EQ(std::string(p.height_fog_estimator), "march");
    EXPECT_NE(c.expected_error.find("height fog"), std::string::npos) << c.expected_error;

    doc = doc_with(R"({"media": [)" + fog +
                   R"(], "render": {"quality": "draft", "volume": {"estimator": "ratio"}}})");
    c = apply_quality(doc);
    EXPECT_EQ(doc.json()["render"]["volume"]["estimator"].get<std::string>(), "ratio");
    EXPECT_EQ(c.kept, std::vector<std::string>{"/render/volume/estimator"});

    doc =
        doc_with(R"({"media": [)" + fog +
                 R"(, {"type": "homogeneous", "sigma_s": 0.1}], "render": {"quality": "final"}})");
    apply_quality(doc);
    EXPECT_EQ(doc.json()["render"]["volume"]["step_m"].get<double>(),
              quality_preset(QualityLevel::Final).fog_step_m);

    doc = doc_with(R"({"media": [)" + fog +
                   R"(, {"type": "vdb", "file": "x.vdb"}], "render": {"quality": "final"}})");
    apply_quality(doc);
    EXPECT_EQ(doc.json()["render"]["volume"]["estimator"].get<std::string>(),
              quality_preset(QualityLevel::Final).grid_estimator);
    // The same at a level without adaptive sampling: still the grid's estimator, and nothing
    // reported as the scene's own (the fog's fill must not run after the grid's).
    doc = doc_with(R"({"media": [)" + fog +
                   R"(, {"type": "vdb", "file": "x.vdb"}], "render": {"quality": "default"}})");
    c = apply_quality(doc);
    EXPECT_EQ(doc.json()["render"]["volume"]["estimator"].get<std::string>(),
              quality_preset(QualityLevel::Default).grid_estimator);
    EXPECT_TRUE(c.kept.empty());
}

// The plan of a lone height fog at draft: the level's choices, the studies' expected error, and
// the stratified march named as what runs (single scattering: draft's tolerance is any).
TEST(Quality, PlanNamesTheHeightFogChoice) {
    const SceneDesc desc = parse_scene(doc_with(R"({
      "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1}],
      "media": [{"type": "height_fog", "sigma_a": 0.0, "sigma_s": 0.1, "scale_height_m": 5}],
      "render": {"quality": "draft"}})")
                                           .json(),
                                       "test.json");
    const Plan plan = make_plan(desc);
    std::string quality, in_scattering;
    for (const PlanStage& s : plan.stages) {
        if (s.name == "quality")
            quality = s.reason;
        if (s.name == "volume-in-scattering")
            in_scattering = s.reason;
    }
    EXPECT_NE(quality.find("/render/volume/estimator = \"march\""), std::string::npos) << quality;
    EXPECT_NE(quality.find("/render/volume/step_m = 4"), std::string::npos) << quality;
    EXPECT_NE(quality.find("height fog 0.000244"), std::string::npos) << quality;
    EXPECT_NE(in_scattering.find("stratified in its closed-form column"), std::string::npos)
        << in_scattering;
}

TEST(Quality, AbsentLevelChangesNothing) {
    SceneDocument doc = doc_with(R"({"render": {"seed": 1}})");
    const Json before = doc.json();
    const QualityChoice c = apply_quality(doc);
    EXPECT_FALSE(c.level.has_value());
    EXPECT_EQ(doc.json(), before);
}

TEST(Quality, UnknownLevelIsALocatedInputError) {
    SceneDocument doc(parse_json_text(R"({"render": {"quality": "ultra"}})", "scene.json"),
                      "scene.json");
    try {
        apply_quality(doc);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        EXPECT_NE(std::string(e.what()).find("scene.json: /render/quality"), std::string::npos);
    }
}

TEST(Quality, SceneLoaderAppliesTheLevel) {
    const std::string scene = R"({"render": {"quality": "draft"}, "film": {"width": 4}})";
    const SceneDesc desc = parse_scene(doc_with(scene).json(), "test.json");
    EXPECT_EQ(desc.film.spp, quality_preset(QualityLevel::Draft).spp);
    const SceneDesc given = parse_scene(
        doc_with(R"({"render": {"quality": "draft"}, "film": {"spp": 7}})").json(), "test.json");
    EXPECT_EQ(given.film.spp, 7);
}

Medium box_medium(float side, Rgb sigma_a, Rgb sigma_s) {
    HomogeneousMedium h;
    h.bounds = Bounds3{Vec3(0.0f), Vec3(side)};
    h.sigma_a = sigma_a;
    h.sigma_s = sigma_s;
    return Medium{"box", h};
}

TEST(ScatteringBound, ExactForACube) {
    // Cube of side L: mean chord 4V/S = 4 L^3 / (6 L^2) = 2L/3. L = 3, sigma_t = 1: tau = 2;
    // omega = 0.5 in the largest channel.
    const ScatteringBound b =
        scattering_bound({box_medium(3.0f, Rgb(0.5f, 0.8f, 0.9f), Rgb(0.5f, 0.2f, 0.1f))});
    EXPECT_NEAR(b.optical_depth, 2.0, 1e-6);
    EXPECT_NEAR(b.albedo, 0.5, 1e-6);
    const double x = 0.5 * (1.0 - std::exp(-2.0));
    EXPECT_NEAR(b.bound, x / (1.0 - x), 1e-6);
    EXPECT_TRUE(b.scatters);
}

TEST(ScatteringBound, LimitsAndNonScatteringMedia) {
    // Thick conservative medium: p -> 1, omega -> 1: unbounded; absorbing only: no scattering.
    EXPECT_TRUE(std::isinf(scattering_bound({box_medium(1e4f, Rgb(0.0f), Rgb(1.0f))}).bound));
    const ScatteringBound absorbing = scattering_bound({box_medium(1.0f, Rgb(1.0f), Rgb(0.0f))});
    EXPECT_FALSE(absorbing.scatters);
    EXPECT_EQ(absorbing.bound, 0.0);
    // Thin: B ~ omega tau as tau -> 0.
    const ScatteringBound thin = scattering_bound({box_medium(0.03f, Rgb(0.0f), Rgb(0.1f))});
    EXPECT_NEAR(thin.bound, 0.1 * 0.03 * 2.0 / 3.0, 1e-5);
}

TEST(ScatteringBound, ChoosesSingleOnlyWithinTolerance) {
    const std::vector<Medium> thin{box_medium(0.3f, Rgb(0.01f), Rgb(0.1f))};    // B ~ 0.02
    const std::vector<Medium> thick{box_medium(30.0f, Rgb(0.01f), Rgb(0.5f))};  // B ~ 40
    auto choose = [](const char* doc_text, const std::vector<Medium>& media) {
        SceneDocument doc(parse_json_text(doc_text, "t.json"), "t.json");
        QualityChoice c = apply_quality(doc);
        VolumeSettings volume;
        volume.integrator = VolumeIntegrator::Single;
        choose_integrator(doc, media, volume, c);
        return volume.integrator;
    };
    EXPECT_EQ(choose(R"({"render": {"quality": "default"}})", thin), VolumeIntegrator::Single);
    EXPECT_EQ(choose(R"({"render": {"quality": "default"}})", thick), VolumeIntegrator::Multiple);
    EXPECT_EQ(choose(R"({"render": {"quality": "draft"}})", thick), VolumeIntegrator::Single);
    EXPECT_EQ(choose(R"({"render": {"quality": "reference"}})", thin), VolumeIntegrator::Multiple);
    // Given by the scene: kept; no level: kept.
    EXPECT_EQ(choose(R"({"render": {"quality": "reference", "volume": {"integrator": "single"}}})",
                     thick),
              VolumeIntegrator::Single);
    EXPECT_EQ(choose(R"({"render": {}})", thick), VolumeIntegrator::Single);
}

/// A 16³-voxel cube of density 1 and sigma_s 2 per voxel: optically thick (tau ~ 20).
std::vector<Medium> thick_cloud() {
    auto grid = std::make_shared<DensityGrid>(IVec3(0), IVec3(15));
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                grid->set(IVec3(x, y, z), 1.0f);
    grid->finalize();
    VdbMedium v;
    v.grid = grid;
    v.sigma_s_per_density = Rgb(2.0f);
    v.bounds_world = Bounds3{Vec3(0.0f), Vec3(15.0f)};
    return {Medium{"cloud", v}};
}

/// A scene document with one VDB medium and `render` as its render object.
SceneDocument vdb_document(const std::string& render) {
    const std::string text =
        R"({"media": [{"type": "vdb", "file": "x.vdb"}], "render": )" + render + "}";
    return SceneDocument(parse_json_text(text, "t.json"), "t.json");
}

TEST(ScatteringBound, SingleScatteredCloudsTakeTheLevelsSingleScatteringEstimator) {
    // A thick cloud: draft chooses single scattering and, with the estimator left to the level,
    // the level's grid_single_estimator; default chooses multiple and keeps grid_estimator; an
    // estimator the scene gives is kept.
    const std::vector<Medium> cloud = thick_cloud();
    auto choose = [&](const std::string& render) {
        SceneDocument doc = vdb_document(render);
        QualityChoice c = apply_quality(doc);
        VolumeSettings volume;
        volume.estimator =
            *estimator_from_name(doc.get("/render/volume/estimator").get<std::string>());
        choose_integrator(doc, cloud, volume, c);
        return volume;
    };
    const VolumeSettings draft = choose(R"({"quality": "draft"})");
    EXPECT_EQ(draft.integrator, VolumeIntegrator::Single);
    EXPECT_STREQ(estimator_name(draft.estimator),
                 quality_preset(QualityLevel::Draft).grid_single_estimator);
    const VolumeSettings by_default = choose(R"({"quality": "default"})");
    EXPECT_EQ(by_default.integrator, VolumeIntegrator::Multiple);
    EXPECT_STREQ(estimator_name(by_default.estimator),
                 quality_preset(QualityLevel::Default).grid_estimator);
    const VolumeSettings given =
        choose(R"({"quality": "draft", "volume": {"estimator": "delta"}})");
    EXPECT_EQ(given.integrator, VolumeIntegrator::Single);
    EXPECT_EQ(given.estimator, Estimator::Delta);
}

TEST(ScatteringBound, MultiplyScatteredCloudsTakeTheLevelsShadowRouletteAndCameraTransmittance) {
    // A thick cloud rendered with multiple scattering (chosen by the level or given by the
    // scene): the level's shadow roulette and first-flight camera transmittance, unless the
    // scene sets them; single scattering (draft) and the reference level leave them off.
    const std::vector<Medium> cloud = thick_cloud();
    struct Chosen {
        VolumeSettings volume;
        QualityChoice choice;
        SceneDocument doc;
    };
    auto choose = [&](const std::string& render) {
        SceneDocument doc = vdb_document(render);
        QualityChoice c = apply_quality(doc);
        VolumeSettings volume;
        if (doc.contains("/render/volume/integrator"))
            volume.integrator = doc.get("/render/volume/integrator").get<std::string>() == "single"
                                    ? VolumeIntegrator::Single
                                    : VolumeIntegrator::Multiple;
        choose_integrator(doc, cloud, volume, c);
        return Chosen{volume, c, doc};
    };
    const Chosen by_default = choose(R"({"quality": "default"})");
    EXPECT_EQ(by_default.volume.integrator, VolumeIntegrator::Multiple);
    EXPECT_FLOAT_EQ(by_default.volume.shadow_roulette,
                    quality_preset(QualityLevel::Default).grid_shadow_roulette);
    EXPECT_GT(by_default.volume.shadow_roulette, 0.0f);
    EXPECT_EQ(by_default.volume.camera_transmittance, CameraTransmittance::FirstFlight);
    const Chosen final_level = choose(R"({"quality": "final"})");
    EXPECT_EQ(final_level.volume.camera_transmittance, CameraTransmittance::FirstFlight);
    // Final's 64 spp with a grid: adaptive sampling at the level's threshold (the unbiased
    // neighbourhood rule, film.noise_window's default); draft and default (spp <= min_spp)
    // and reference leave it off.
    ASSERT_TRUE(final_level.doc.contains("/film/noise_threshold"));
    EXPECT_DOUBLE_EQ(final_level.doc.get("/film/noise_threshold").get<double>(),
                     quality_preset(QualityLevel::Final).grid_noise_threshold);
    EXPECT_GT(quality_preset(QualityLevel::Final).grid_noise_threshold, 0.0);
    EXPECT_NE(std::find(final_level.choice.applied.begin(), final_level.choice.applied.end(),
                        "/film/noise_threshold = 0.1"),
              final_level.choice.applied.end());
    EXPECT_FALSE(by_default.doc.contains("/film/noise_threshold"));
    // A scene that gives film.spp keeps uniform sampling (the threshold was measured at 64).
    SceneDocument own_spp(
        parse_json_text(R"({"film": {"spp": 256}, "media": [{"type": "vdb", "file": "x.vdb"}],
                            "render": {"quality": "final"}})",
                        "t.json"),
        "t.json");
    apply_quality(own_spp);
    EXPECT_FALSE(own_spp.contains("/film/noise_threshold"));
    // Given by the scene: the integrator (multiple) and the roulette; the camera transmittance
    // still comes from the level.
    const Chosen given = choose(
        R"({"quality": "default", "volume": {"integrator": "multiple", "shadow_roulette": 0}})");
    EXPECT_EQ(given.volume.shadow_roulette, 0.0f);
    EXPECT_EQ(given.volume.camera_transmittance, CameraTransmittance::FirstFlight);
    EXPECT_NE(std::find(given.choice.kept.begin(), given.choice.kept.end(),
                        "/render/volume/shadow_roulette"),
              given.choice.kept.end());
    const Chosen draft = choose(R"({"quality": "draft"})");
    EXPECT_EQ(draft.volume.integrator, VolumeIntegrator::Single);
    EXPECT_EQ(draft.volume.shadow_roulette, 0.0f);
    EXPECT_EQ(draft.volume.camera_transmittance, CameraTransmittance::Walk);
    const Chosen reference = choose(R"({"quality": "reference"})");
    EXPECT_EQ(reference.volume.integrator, VolumeIntegrator::Multiple);
    EXPECT_EQ(reference.volume.shadow_roulette, 0.0f);
    EXPECT_EQ(reference.volume.camera_transmittance, CameraTransmittance::Walk);
    EXPECT_FALSE(reference.doc.contains("/film/noise_threshold"));
    EXPECT_FALSE(draft.doc.contains("/film/noise_threshold"));
}

}  // namespace
}  // namespace kasumi
