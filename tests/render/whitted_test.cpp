// Exact answers for Whitted ray tracing: a mirror at normal incidence, a glass slab (the
// geometric series of its internal reflections, cut by max_depth), energy conservation of a
// glass sphere under a uniform background, the recursion limits (counted rays), Gouraud and
// Phong shading of a mesh against per-vertex closed forms, and no NaN anywhere.
#include "core/error.h"
#include "render/integrator.h"
#include "render/probe.h"
#include "surface/fresnel.h"
#include "surface/shading.h"
#include "tests/test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace kasumi {
namespace {

Rgb trace(const SceneRuntime& scene, const Vec3& origin, const Vec3& direction,
          RenderCounters* counters_out = nullptr) {
    RenderCounters counters;
    Pcg32 rng(1, 2);
    const Ray ray{origin, glm::normalize(direction), 0.0f, kInfinity};
    const Rgb radiance = trace_camera_ray(scene, ray, rng, counters).radiance;
    if (counters_out)
        *counters_out = counters;
    return radiance;
}

TEST(Whitted, MirrorAtNormalIncidenceSeesKrTimesWhatItFaces) {
    // The camera at z = 1 looks down -z at a small mirror in z = 0; the mirror faces a white
    // Lambertian wall at z = 2 lit by a directional light of E lux at 36.87° (cos θ = 0.8), whose
    // shadow rays pass beside the mirror. Closed form: L = kr · kd E cos θ / π.
    const auto scene = runtime_from_text(R"({
        "materials": {"mirror": {"type": "mirror", "kr": [0.5, 0.7, 0.9]},
                      "white": {"type": "phong", "kd": 1.0}},
        "shapes": [
          {"type": "quad", "material": "mirror",
           "vertices": [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]]},
          {"type": "quad", "material": "white",
           "vertices": [[-5, -5, 2], [-5, 5, 2], [5, 5, 2], [5, -5, 2]]}],
        "lights": [{"type": "directional", "direction": [0.6, 0, 0.8], "illuminance_lux": 1000}]
    })");
    const Rgb l = probe_radiance(*scene, Vec3(0, 0, 1), Vec3(0, 0, -1), 1).radiance;
    const float wall = 1000.0f * 0.8f / kPi;
    EXPECT_NEAR(l.r, 0.5f * wall, 1e-5f * wall);
    EXPECT_NEAR(l.g, 0.7f * wall, 1e-5f * wall);
    EXPECT_NEAR(l.b, 0.9f * wall, 1e-5f * wall);
    // The mirror itself takes no direct light: kr = 0 shows black.
    const auto dark = runtime_from_text(R"({
        "materials": {"mirror": {"type": "mirror", "kr": 0}},
        "shapes": [{"type": "quad", "material": "mirror",
           "vertices": [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]]}],
        "lights": [{"type": "directional", "direction": [0, 0, -1], "illuminance_lux": 1000}],
        "ambient": 1})");
    EXPECT_EQ(trace(*dark, Vec3(0, 0, 1), Vec3(0, 0, -1)), Rgb(0.0f));
}

/// A glass slab 0.1 m thick (z in [-0.1, 0]) over a background of radiance 1, seen at normal
/// incidence from z = 2; a black plate at z = 5 behind the camera absorbs what the slab
/// reflects back. The light reaching the camera crossed both faces (1 - R)² after 2k internal
/// reflections R^(2k), each path needing 2k + 2 specular bounces after the first hit, so with
/// max_depth D: T(D) = (1 - R)² Σ_{k: 2k + 2 <= D} R^(2k), and T(∞) = (1 - R) / (1 + R). The
/// radiance factors 1/η² on entering and η² on leaving cancel.
std::unique_ptr<SceneRuntime> slab_scene(int max_depth, float min_weight) {
    return runtime_from_text(R"({
        "background": 1,
        "materials": {"glass": {"type": "dielectric", "ior": 1.5},
                      "black": {"type": "phong", "kd": 0}},
        "shapes": [
          {"type": "box", "material": "glass", "min": [-50, -50, -0.1], "max": [50, 50, 0]},
          {"type": "quad", "material": "black",
           "vertices": [[-50, -50, 5], [50, -50, 5], [50, 50, 5], [-50, 50, 5]]}],
        "render": {"whitted": {"max_depth": )" +
                             std::to_string(max_depth) + R"(, "min_weight": )" +
                             std::to_string(min_weight) + "}}}");
}

TEST(Whitted, GlassSlabAtNormalIncidenceTransmitsTheSeriesCutByDepth) {
    const double r = 0.04;  // ((1.5 - 1) / (1.5 + 1))²
    for (const int depth : {0, 1, 2, 3, 4, 5, 6, 9}) {
        double expected = 0.0;
        for (int k = 0; 2 * k + 2 <= depth; ++k)
            expected += (1.0 - r) * (1.0 - r) * std::pow(r, 2 * k);
        const Rgb l = trace(*slab_scene(depth, 0.0f), Vec3(0, 0, 2), Vec3(0, 0, -1));
        EXPECT_NEAR(l.g, expected, 2e-6) << "max_depth " << depth;
    }
    const Rgb l = trace(*slab_scene(64, 0.0f), Vec3(0, 0, 2), Vec3(0, 0, -1));
    EXPECT_NEAR(l.g, (1.0 - r) / (1.0 + r), 2e-6);  // 0.923077
}

TEST(Whitted, MinWeightCutsFaintBranches) {
    // Branch weights inside the slab: 0.96 (in), 0.0384 (one internal reflection), 0.001536
    // (two), then 0.00147 (out after two): min_weight 2e-3 keeps only the direct path.
    const Rgb l = trace(*slab_scene(64, 2e-3f), Vec3(0, 0, 2), Vec3(0, 0, -1));
    EXPECT_NEAR(l.g, 0.96 * 0.96, 2e-6);
}

TEST(Whitted, GlassSphereInAUniformBackgroundConservesEnergy) {
    // No absorption, no tint: every path ends in the background of radiance 1, so whatever a
    // ray hits, L = 1 up to the energy still trapped after max_depth bounces.
    const auto scene = runtime_from_text(R"({
        "background": 1,
        "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
        "shapes": [{"type": "sphere", "material": "glass", "center": [0, 0, 0], "radius": 1}],
        "render": {"whitted": {"max_depth": 40, "min_weight": 0}}})");
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.999f, 0.999f);
    for (int i = 0; i < 200; ++i) {
        const Vec3 target(u(rng), u(rng), 0.0f);
        if (glm::length(target) >= 0.999f)
            continue;
        const Rgb l = trace(*scene, Vec3(target.x, target.y, 5.0f), Vec3(0, 0, -1));
        EXPECT_NEAR(l.g, 1.0f, 1e-4f) << target.x << " " << target.y;
    }
}

/// Two parallel mirrors 1 m apart with the camera between: every ray bounces until a limit.
std::unique_ptr<SceneRuntime> mirror_pair(int max_depth, float kr, float min_weight) {
    return runtime_from_text(R"({
        "background": 1,
        "materials": {"m": {"type": "mirror", "kr": )" +
                             std::to_string(kr) + R"(}},
        "shapes": [
          {"type": "quad", "material": "m", "vertices": [[-9, -9, 0], [9, -9, 0], [9, 9, 0], [-9, 9, 0]]},
          {"type": "quad", "material": "m", "vertices": [[-9, -9, 1], [9, -9, 1], [9, 9, 1], [-9, 9, 1]]}],
        "render": {"whitted": {"max_depth": )" +
                             std::to_string(max_depth) + R"(, "min_weight": )" +
                             std::to_string(min_weight) + "}}}");
}

TEST(Whitted, MaxDepthBoundsTheRaysTraced) {
    for (const int depth : {0, 1, 3, 5, 17}) {
        const auto scene = mirror_pair(depth, 1.0f, 0.0f);
        const uint64_t before = scene->surfaces()->stats().closest_rays;
        const Rgb l = trace(*scene, Vec3(0.1f, 0.2f, 0.5f), Vec3(0, 0, -1));
        // The camera ray plus one ray per bounce; the last one is cut, so nothing reaches
        // the background: black.
        EXPECT_EQ(scene->surfaces()->stats().closest_rays - before, uint64_t(1 + depth)) << depth;
        EXPECT_EQ(l, Rgb(0.0f));
    }
    // kr = 0.5 and min_weight 0.1: weights 0.5, 0.25, 0.125 are traced, 0.0625 is not.
    const auto scene = mirror_pair(64, 0.5f, 0.1f);
    const uint64_t before = scene->surfaces()->stats().closest_rays;
    trace(*scene, Vec3(0.1f, 0.2f, 0.5f), Vec3(0, 0, -1));
    EXPECT_EQ(scene->surfaces()->stats().closest_rays - before, 4u);
}

TEST(Whitted, NoNonFiniteRadianceFromAnyDirection) {
    const auto scene = runtime_from_text(R"({
        "background": [0.1, 0.2, 0.3], "ambient": 0.1,
        "materials": {"glass": {"type": "dielectric", "ior": 1.5, "tint": [1, 0.9, 0.8]},
                      "water": {"type": "dielectric", "ior": 0.75},
                      "mirror": {"type": "mirror", "kr": 0.9},
                      "floor": {"type": "phong", "kd": 0.5, "ka": 0.5, "ks": 0.3, "ks_fresnel": "exact"}},
        "shapes": [
          {"type": "sphere", "material": "glass", "center": [0, 1, 0], "radius": 1},
          {"type": "sphere", "material": "water", "center": [0, 1, 0], "radius": 0.4},
          {"type": "sphere", "material": "mirror", "center": [2.5, 1, 0], "radius": 1},
          {"type": "box", "material": "glass", "min": [-3, 0, -3], "max": [-1.5, 2, -1.5]},
          {"type": "quad", "material": "floor", "vertices": [[-9, 0, 9], [9, 0, 9], [9, 0, -9], [-9, 0, -9]]}],
        "lights": [{"type": "point", "position": [1, 5, 3], "intensity_cd": 100}],
        "media": [{"type": "homogeneous", "sigma_a": 0.01, "sigma_s": 0.05}],
        "render": {"whitted": {"max_depth": 12}}})");
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 300; ++i) {
        // Origins inside and outside the glass, every direction.
        const Vec3 origin = (i % 3 == 0) ? Vec3(0.3f * u(rng), 1.0f + 0.3f * u(rng), 0.3f)
                                         : Vec3(4.0f * u(rng), 1.0f + u(rng), 6.0f);
        const Vec3 direction(u(rng), u(rng), u(rng));
        if (glm::length(direction) < 1e-3f)
            continue;
        const Rgb l = trace(*scene, origin, direction);
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(std::isfinite(l[c]) && l[c] >= 0.0f) << i << " " << l[c];
    }
}

TEST(Whitted, BadWhittedSettingsNameThePath) {
    for (const char* bad : {R"({"render": {"whitted": {"max_depth": -1}}})",
                            R"({"render": {"whitted": {"max_depth": 65}}})",
                            R"({"render": {"whitted": {"min_weight": 1.5}}})",
                            R"({"render": {"whitted": {"depth": 3}}})"}) {
        try {
            scene_from_text(bad);
            ADD_FAILURE() << "accepted " << bad;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input);
            EXPECT_NE(std::string(e.what()).find("/render/whitted/"), std::string::npos)
                << e.what();
        }
    }
    const SceneDesc defaults = scene_from_text("{}");
    EXPECT_EQ(defaults.render.whitted.max_depth, 5);
    EXPECT_EQ(defaults.render.whitted.min_weight, 1e-3f);
}

/// The icosphere under a directional light of E lux travelling -z, seen from +z; kd = 1, no
/// ambient: a vertex with (computed) normal n has radiance E max(0, n_z) / π.
std::unique_ptr<SceneRuntime> lit_icosphere(const char* shading) {
    return runtime_from_text(std::string(R"({
        "materials": {"white": {"type": "phong", "kd": 1}},
        "shapes": [{"type": "mesh", "file": ")") +
                             KASUMI_SOURCE_DIR + R"(/data/meshes/icosphere2.obj",
                    "material": "white", "shading": ")" +
                             shading + R"("}],
        "lights": [{"type": "directional", "direction": [0, 0, -1], "illuminance_lux": 1000}]})");
}

TEST(Whitted, GouraudAndPhongMatchVertexClosedFormsAtVerticesAndMidpoints) {
    const TriangleMesh mesh = load_obj(KASUMI_SOURCE_DIR "/data/meshes/icosphere2.obj");
    const std::vector<Vec3> normals = angle_weighted_normals(mesh.positions, mesh.triangles);
    const auto vertex_radiance = [&](uint32_t i) {
        return 1000.0f * std::max(0.0f, normals[i].z) / kPi;
    };
    const auto gouraud = lit_icosphere("gouraud");
    const auto phong = lit_icosphere("phong");
    const auto flat = lit_icosphere("flat");
    int checked = 0;
    for (const auto& tri : mesh.triangles) {
        if (normals[tri[0]].z < 0.5f || normals[tri[1]].z < 0.5f || normals[tri[2]].z < 0.5f)
            continue;
        ++checked;
        const Vec3 above(0.0f, 0.0f, 5.0f);
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = tri[k], b = tri[(k + 1) % 3];
            const Vec3 vertex = mesh.positions[a];
            const float at_vertex = vertex_radiance(a);
            EXPECT_NEAR(trace(*gouraud, vertex + above, Vec3(0, 0, -1)).g, at_vertex,
                        1e-4f * at_vertex);
            EXPECT_NEAR(trace(*phong, vertex + above, Vec3(0, 0, -1)).g, at_vertex,
                        1e-4f * at_vertex);
            // Edge midpoint: Gouraud averages the vertices' radiance; Phong lights the
            // renormalised average normal.
            const Vec3 mid = 0.5f * (mesh.positions[a] + mesh.positions[b]);
            const float gouraud_mid = 0.5f * (vertex_radiance(a) + vertex_radiance(b));
            const float phong_mid = 1000.0f * glm::normalize(normals[a] + normals[b]).z / kPi;
            EXPECT_NEAR(trace(*gouraud, mid + above, Vec3(0, 0, -1)).g, gouraud_mid,
                        1e-4f * gouraud_mid);
            EXPECT_NEAR(trace(*phong, mid + above, Vec3(0, 0, -1)).g, phong_mid, 1e-4f * phong_mid);
        }
        // Flat: the face's cosine everywhere on the triangle.
        const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]],
                   p2 = mesh.positions[tri[2]];
        const float face = 1000.0f * glm::normalize(glm::cross(p1 - p0, p2 - p0)).z / kPi;
        for (const Vec3& point : {(p0 + p1 + p2) / 3.0f, 0.6f * p0 + 0.3f * p1 + 0.1f * p2})
            EXPECT_NEAR(trace(*flat, point + above, Vec3(0, 0, -1)).g, face, 1e-4f * face);
    }
    EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace kasumi
