// render.surface "scanline": the visible surfaces from the scanline renderer of polygons, the
// shadows of "shadows": "scanline" lights from its shadowed sub-spans. The image equals the ray
// renderer's with ray-traced shadows on every pixel whose footprint no silhouette, crease or
// shadow edge cuts (its centre and four corners see one shape, one face plane and one shadow
// state by ray tracing), within float rounding, on data/scenes/shadow_volumes.json (meshes, a
// box, a plate, a sphere) and data/scenes/shadow_polygons_concave.json (concave meshes,
// coplanar faces); 1, 2 and 3 threads give the same image; bad settings are input errors.
#include "core/error.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"
#include "tests/surface/shadow_test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace kasumi {
namespace {

/// What ray tracing sees at image point (x, y): the shape (−1: nothing), its plane's normal
/// (zero on spheres: curved, compared by shape alone) and whether the light is hidden there.
struct FootprintState {
    int shape = -1;
    Vec3 normal{0.0f};
    bool shadowed = false;
    bool operator==(const FootprintState& o) const {
        return shape == o.shape && normal == o.normal && shadowed == o.shadowed;
    }
};

FootprintState traced_state(const SurfaceScene& scene, const std::vector<Shape>& shapes,
                            const LightCentre& light, const PinholeView& view, float x, float y) {
    const auto hit = scene.intersect(Ray{view.eye, view.direction(x, y), 0.0f, kInfinity});
    if (!hit)
        return {};
    const auto facing = facing_hit(scene, light, view, x, y);
    const bool sphere = std::holds_alternative<SphereShape>(shapes[hit->shape].geometry);
    return {int(hit->shape), sphere ? Vec3(0.0f) : hit->geometric_normal,
            !facing || facing->ray_shadow};
}

Image render(SceneDesc desc, SurfaceMethod surface, ShadowMode shadows, int threads) {
    desc.render.surface = surface;
    for (Light& light : desc.lights)
        light.shadows = shadows;
    const SceneRuntime runtime(std::move(desc));
    return render_image(runtime, quiet(threads)).film.to_image();
}

struct Comparison {
    int compared = 0;    ///< pixels whose footprint no edge cuts
    int shadowed = 0;    ///< of those, in shadow by ray tracing
    int differ = 0;      ///< of those, pixels differing beyond float rounding in some channel
    int ties = 0;        ///< pixels left out: coplanar faces of two shapes tie at the centre
    float worst = 0.0f;  ///< the largest relative difference among the compared pixels
    std::string first;   ///< the first differing pixel (for the failure message)
};

Comparison compare_with_ray_renderer(const SceneDesc& desc) {
    const Image ray = render(desc, SurfaceMethod::Ray, ShadowMode::Ray, 2);
    const Image scanline = render(desc, SurfaceMethod::Scanline, ShadowMode::Scanline, 2);
    EXPECT_EQ(scanline.channels.size(), ray.channels.size());
    const SurfaceScene scene(desc.shapes);
    const LightCentre light = light_centre(desc.lights[0]);
    const int w = desc.film.width, h = desc.film.height;
    PinholeView view = pinhole_view(desc.camera.position, desc.camera.look_at, w, h);
    view.half_width = float(w) / float(h) * std::tan(0.5f * radians(desc.camera.fov_deg));
    SceneDesc scanline_desc = desc;
    scanline_desc.render.surface = SurfaceMethod::Scanline;
    for (Light& l : scanline_desc.lights)
        l.shadows = ShadowMode::Scanline;
    const SceneRuntime runtime(scanline_desc);
    // Coplanar faces of two shapes overlapping at a pixel centre: both are at its depth, and
    // which is seen is a tie that each renderer breaks its own way (the scanline by polygon
    // table order, Embree by its traversal, differently in its stream and single-ray paths).
    // A centre is a tie when the scene without the drawn shape has a surface within 1e-5 of the
    // drawn depth; such pixels are counted and left out.
    std::vector<std::unique_ptr<SurfaceScene>> without(desc.shapes.size());
    for (size_t s = 0; s < desc.shapes.size(); ++s) {
        std::vector<Shape> others = desc.shapes;
        others.erase(others.begin() + static_cast<std::ptrdiff_t>(s));
        without[s] = std::make_unique<SurfaceScene>(others);
    }
    const auto coplanar_tie = [&](int x, int y) {
        const Ray centre_ray = runtime.camera().generate_ray(x + 0.5f, y + 0.5f);
        std::optional<SurfaceHit> drawn;
        runtime.scanline_surface()->first_hits(y, &x, &centre_ray, 1, &drawn);
        if (!drawn)
            return false;
        Ray around = centre_ray;
        around.t_min = drawn->t * (1.0f - 1e-5f);
        around.t_max = drawn->t * (1.0f + 1e-5f);
        return without[drawn->shape]->occluded(around);
    };
    const auto state = [&](float x, float y) {
        return traced_state(scene, desc.shapes, light, view, x, y);
    };
    Comparison c;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const FootprintState centre = state(x + 0.5f, y + 0.5f);
            if (!(state(x, y) == centre && state(x + 1, y) == centre && state(x, y + 1) == centre &&
                  state(x + 1, y + 1) == centre))
                continue;
            if (coplanar_tie(x, y)) {
                ++c.ties;
                continue;
            }
            ++c.compared;
            c.shadowed += centre.shape >= 0 && centre.shadowed ? 1 : 0;
            const size_t p = size_t(y) * w + x;
            bool differs = false;
            for (size_t k = 0; k < ray.channels.size(); ++k) {
                const float a = ray.channels[k].data[p], b = scanline.channels[k].data[p];
                const float scale = std::max({std::abs(a), std::abs(b), 1e-3f});
                const float relative = std::abs(a - b) / scale;
                c.worst = std::max(c.worst, relative);
                // Float rounding: the scanline hit's t, u, v come from double plane equations,
                // Embree's from its float intersector (~1e-6 relative in the position).
                differs = differs || !(relative <= 1e-4f);
            }
            if (differs && c.first.empty())
                c.first = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "), shape " +
                          std::to_string(centre.shape);
            c.differ += differs ? 1 : 0;
        }
    ::testing::Test::RecordProperty("compared", c.compared);
    ::testing::Test::RecordProperty("shadowed", c.shadowed);
    ::testing::Test::RecordProperty("ties", c.ties);
    ::testing::Test::RecordProperty("worst_relative", std::to_string(c.worst));
    return c;
}

SceneDesc small(const std::string& scene) {
    return load_scene(KASUMI_SOURCE_DIR "/data/scenes/" + scene,
                      {{"/film/width", "320"}, {"/film/height", "200"}, {"/film/jitter", "false"}});
}

TEST(ScanlineSurfaceTest, EqualsRayRendererOffEdgesOnTheShadowVolumeScene) {
    const Comparison c = compare_with_ray_renderer(small("shadow_volumes.json"));
    EXPECT_GT(c.compared, 52000);  // of 64000 pixels
    EXPECT_GT(c.shadowed, 1400);
    EXPECT_EQ(c.ties, 0);
    EXPECT_EQ(c.differ, 0) << c.compared << " compared, " << c.shadowed << " shadowed, worst "
                           << c.worst << " at " << c.first;
}

TEST(ScanlineSurfaceTest, EqualsRayRendererOffEdgesOnConcaveMeshesAndCoplanarFaces) {
    const Comparison c = compare_with_ray_renderer(small("shadow_polygons_concave.json"));
    EXPECT_GT(c.compared, 52000);
    EXPECT_GT(c.shadowed, 900);
    EXPECT_GT(c.ties, 0);  // the lid lying on both box tops
    EXPECT_LT(c.ties, 100);
    EXPECT_EQ(c.differ, 0) << c.compared << " compared, " << c.shadowed << " shadowed, worst "
                           << c.worst << " at " << c.first;
}

TEST(ScanlineSurfaceTest, OneTwoAndThreeThreadsGiveTheSameImage) {
    const SceneDesc desc = small("shadow_volumes.json");
    const Image one = render(desc, SurfaceMethod::Scanline, ShadowMode::Scanline, 1);
    for (const int threads : {2, 3}) {
        const Image other = render(desc, SurfaceMethod::Scanline, ShadowMode::Scanline, threads);
        ASSERT_EQ(one.channels.size(), other.channels.size());
        for (size_t k = 0; k < one.channels.size(); ++k)
            EXPECT_EQ(one.channels[k].data, other.channels[k].data)
                << threads << " threads: " << one.channels[k].name;
    }
}

TEST(ScanlineSurfaceTest, PlanNamesTheStage) {
    SceneDesc desc = small("shadow_volumes.json");
    desc.render.surface = SurfaceMethod::Scanline;
    const Plan plan = make_plan(desc);
    EXPECT_TRUE(plan.scanline_surface);
    bool found = false;
    for (const PlanStage& s : plan.stages)
        if (s.name == "scanline-surface") {
            found = true;
            EXPECT_TRUE(s.enabled);
            EXPECT_NE(s.reason.find("scanline renderer (Bouknight & Kelley 1970)"),
                      std::string::npos)
                << s.reason;
            EXPECT_NE(s.reason.find("1 sphere ray-cast"), std::string::npos) << s.reason;
        }
    EXPECT_TRUE(found);
    desc.render.surface = SurfaceMethod::Ray;
    EXPECT_FALSE(make_plan(desc).scanline_surface);
}

/// The input error of loading `scene` with `overrides`.
std::string load_error(const std::string& scene, const std::vector<Override>& overrides) {
    try {
        load_scene(KASUMI_SOURCE_DIR "/data/scenes/" + scene, overrides);
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
}

TEST(ScanlineSurfaceTest, BadSettingsAreInputErrorsNamingThePointer) {
    const std::string unknown = load_error(
        "shadow_volumes.json", {{"/render/surface", "\"raster\""}, {"/film/jitter", "false"}});
    EXPECT_NE(unknown.find("shadow_volumes.json"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("/render/surface"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("expected \"ray\" or \"scanline\""), std::string::npos) << unknown;
    const std::string jitter =
        load_error("shadow_volumes.json", {{"/render/surface", "\"scanline\""}});
    EXPECT_NE(jitter.find("/render/surface"), std::string::npos) << jitter;
    EXPECT_NE(jitter.find("film.jitter"), std::string::npos) << jitter;
}

}  // namespace
}  // namespace kasumi
