// Exact penumbrae of sphere lights (surface/sphere_light_occluders.h, lights/cap_region.h): the
// closed-form visible projected solid angle against brute-force quadrature of the light's cone
// with a shadow ray per cell (Embree, the renderer's own occlusion query), for spheres, boxes,
// quads, overlapping occluders (inclusion-exclusion) and tilted receivers; the coaxial-sphere
// closed form; umbra and full light exactly; and every case that must fall back to sampling.
#include "core/error.h"
#include "core/json_node.h"
#include "lights/cap_region.h"
#include "lights/light_json.h"
#include "lights/polygon_light.h"
#include "lights/sphere_light.h"
#include "surface/sphere_light_occluders.h"
#include "surface/surface_scene.h"
#include "tests/lights/light_test_util.h"
#include "tests/surface/test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace kasumi {
namespace {

constexpr uint32_t kNoReceiver = std::numeric_limits<uint32_t>::max();

/// ∫ max(0, n·ω) V(ω) dω over the light's cone by the midpoint rule in (cos θ, φ) (equal solid
/// angle per cell; test::sphere_quadrature), V from one shadow ray per cell to the light's near
/// surface. Its error is the cells cut by a shadow edge: O(1/cells) of the cone.
double quadrature(const SurfaceScene& scene, const SphereLight& light, const Vec3& p, const Vec3& n,
                  int cells) {
    const auto visible = [&](const Vec3& from, const Vec3& beyond) {
        const DVec3 w = glm::normalize(DVec3(beyond) - DVec3(from));
        const DVec3 to = DVec3(light.center) - DVec3(from);
        const double b = glm::dot(to, w);
        // Distance to the light along w: b − √(R² − (|to|² − b²)).
        const double t = b - std::sqrt(std::max(0.0, double(light.radius) * light.radius -
                                                         (glm::dot(to, to) - b * b)));
        return !scene.occluded(Ray{from, Vec3(w), 0.0f, static_cast<float>(t)});
    };
    return test::sphere_quadrature(light, p, n, visible, cells) / luminance(light.luminance);
}

/// Snyder's closed form (clipped at the horizon), per unit luminance.
double clipped_unshadowed(const SphereLight& light, const Vec3& p, const Vec3& n) {
    return luminance(unshadowed_irradiance(light, p, n)) / luminance(light.luminance);
}

double unshadowed(const SphereLight& light, const Vec3& p, const Vec3& n) {
    const DVec3 to = DVec3(light.center) - DVec3(p);
    const double d = glm::length(to);
    return kPiD * (light.radius / d) * (light.radius / d) * glm::dot(DVec3(n), to / d);
}

struct Case {
    const char* what;
    std::vector<Shape> shapes;
    Vec3 from, to;  ///< receiver points are scanned along this segment
    Vec3 n;
};

const SphereLight kLight{Vec3(2.5f, 5.0f, -1.0f), 0.4f, Rgb(1.0f)};

std::vector<Case> penumbra_cases() {
    const Vec3 up(0, 1, 0);
    const Vec3 tilted = glm::normalize(Vec3(0.3f, 1.0f, -0.2f));
    // Nearly perpendicular to the direction of the light from the origin (n · axis ≈ 0.03,
    // sin σ ≈ 0.07).
    const Vec3 toward = glm::normalize(kLight.center);
    const Vec3 horizon =
        glm::normalize(glm::normalize(glm::cross(toward, Vec3(0, 0, 1))) + 0.03f * toward);
    // The benchmark scene's occluders (data/scenes/povray_soft_shadows.json).
    const Shape ball = sphere(Vec3(0.3f, 1.6f, 0.0f), 0.6f);
    const Shape block = box(Vec3(-2.2f, 0.0f, -1.5f), Vec3(-1.4f, 1.2f, -0.7f));
    // A thin bar across the disc, a small ball and a tilted plate near the line to the light.
    const Shape bar = box(Vec3(-1.0f, 2.5f, -0.42f), Vec3(3.0f, 2.56f, -0.36f));
    const Shape bead = sphere(Vec3(1.62f, 2.58f, -0.58f), 0.09f);
    const Shape plate = quad(Vec3(1.45f, 2.7f, -0.6f), Vec3(1.85f, 2.75f, -0.6f),
                             Vec3(1.85f, 2.7f, -0.3f), Vec3(1.45f, 2.65f, -0.3f));
    return {
        {"ball", {ball}, Vec3(-0.7f, 0, 0.5f), Vec3(1.3f, 0, 0.5f), up},
        {"ball, tilted receiver", {ball}, Vec3(-0.7f, 0, 0.5f), Vec3(-0.7f, 0, 2.5f), tilted},
        {"block, across its shadow", {block}, Vec3(-4.5f, 0, -1.6f), Vec3(-2.5f, 0, 0.6f), up},
        {"block, tilted receiver", {block}, Vec3(-4.5f, 0, 0.0f), Vec3(-2.0f, 0, -2.0f), tilted},
        {"ball and block", {ball, block}, Vec3(-3.5f, 0, -0.4f), Vec3(0.5f, 0, 0.6f), up},
        {"bar alone", {bar}, Vec3(-0.5f, 0, -0.8f), Vec3(1.5f, 0, 1.2f), up},
        {"bar, bead and plate overlapping",
         {bar, bead, plate},
         Vec3(-0.5f, 0, -0.8f),
         Vec3(1.5f, 0, 1.2f),
         up},
        // A receiver whose horizon cuts the light's cone: every region is clipped to it.
        {"bar, horizon across the cone", {bar}, Vec3(0, 0, -0.6f), Vec3(0, 0, 1.0f), horizon},
        {"plate, tilted receiver", {plate}, Vec3(-0.5f, 0, -1.2f), Vec3(1.5f, 0, 1.2f), tilted},
    };
}

TEST(ExactPenumbra, MatchesQuadratureOfTheVisibleConeAcrossPenumbrae) {
    for (const Case& c : penumbra_cases()) {
        const SurfaceScene scene(c.shapes);
        const SphereLightOccluders& occluders = scene.sphere_light_occluders();
        // The penumbra points of the segment (visible fraction in (0.05, 0.95)), by the exact
        // value; three of them (first, middle, last) are checked, plus one lit and one umbra
        // point where the segment has them.
        std::vector<Vec3> penumbra, lit, umbra;
        for (int k = 0; k <= 200; ++k) {
            const Vec3 p = c.from + (k / 200.0f) * (c.to - c.from);
            const auto v = occluders.visible_projected_solid_angle(kLight, p, c.n, kNoReceiver);
            ASSERT_TRUE(v.has_value()) << c.what << " at " << k;
            const double fraction = *v / clipped_unshadowed(kLight, p, c.n);
            if (fraction > 0.05 && fraction < 0.95)
                penumbra.push_back(p);
            else if (fraction >= 1.0)
                lit.push_back(p);
            else if (fraction <= 0.0)
                umbra.push_back(p);
        }
        ASSERT_GE(penumbra.size(), 3u) << c.what << ": the segment misses the penumbra";
        std::vector<Vec3> checked = {penumbra.front(), penumbra[penumbra.size() / 2],
                                     penumbra.back()};
        if (!lit.empty())
            checked.push_back(lit.front());
        if (!umbra.empty())
            checked.push_back(umbra[umbra.size() / 2]);
        for (const Vec3& p : checked) {
            const double exact =
                *occluders.visible_projected_solid_angle(kLight, p, c.n, kNoReceiver);
            const double full = clipped_unshadowed(kLight, p, c.n);
            // 1000² cells: the midpoint rule's error along an edge stays below 1e-3 of the cone.
            const double reference = quadrature(scene, kLight, p, c.n, 1000);
            EXPECT_NEAR(exact, reference, 1e-3 * full)
                << c.what << " at (" << p.x << ", " << p.z << "), fraction " << exact / full;
        }
    }
}

/// E / L = ∫ max(0, n·ω) V dω over a polygon light by the midpoint rule over its area
/// (test::polygon_quadrature), V from a shadow ray to each cell.
double polygon_quadrature(const SurfaceScene& scene, const PolygonLight& light, const Vec3& p,
                          const Vec3& n, int cells) {
    return test::polygon_quadrature(
        light.vertices, 1.0, light.two_sided, p, n, cells, [&](const Vec3& from, const Vec3& to) {
            const DVec3 d = DVec3(to) - DVec3(from);
            const double r = glm::length(d);
            return !scene.occluded(
                Ray{from, Vec3(d / r), 0.0f, static_cast<float>(r) * (1.0f - 1e-5f)});
        });
}

TEST(ExactPenumbra, PolygonLightMatchesQuadratureOfItsArea) {
    // A 1 m × 0.6 m panel facing down at 3 m (counter-clockwise seen from below), over the
    // benchmark's ball and block and a tilted plate; receivers on the floor, tilted, and one
    // whose horizon cuts the panel.
    const PolygonLight panel =
        make_polygon_light({Vec3(-0.5f, 3.0f, -0.3f), Vec3(0.5f, 3.0f, -0.3f),
                            Vec3(0.5f, 3.0f, 0.3f), Vec3(-0.5f, 3.0f, 0.3f)},
                           Rgb(1.0f), false);
    ASSERT_LT(panel.normal.y, -0.99f);
    const SurfaceScene scene({sphere(Vec3(0.3f, 1.6f, 0.0f), 0.4f),
                              box(Vec3(-1.6f, 0.0f, -0.6f), Vec3(-1.0f, 1.2f, 0.2f)),
                              quad(Vec3(0.6f, 2.0f, -0.4f), Vec3(1.2f, 2.2f, -0.4f),
                                   Vec3(1.2f, 2.2f, 0.4f), Vec3(0.6f, 2.0f, 0.4f))});
    const SphereLightOccluders& occluders = scene.sphere_light_occluders();
    const Vec3 up(0, 1, 0);
    const Vec3 tilted = glm::normalize(Vec3(-0.4f, 1.0f, 0.3f));
    const Vec3 edge_on = glm::normalize(Vec3(1.0f, 0.25f, 0.0f));
    int penumbra = 0;
    for (const Vec3& n : {up, tilted, edge_on}) {
        for (int k = 0; k <= 12; ++k) {
            const Vec3 p(-2.5f + 0.4f * k, 0.0f, 0.45f);  // beside the block, not under it
            const auto exact = occluders.visible_projected_solid_angle(panel, p, n, kNoReceiver);
            ASSERT_TRUE(exact.has_value()) << k;
            const double full = luminance(unshadowed_irradiance(panel, p, n));
            const double reference = polygon_quadrature(scene, panel, p, n, 500);
            EXPECT_NEAR(*exact, reference, 1.5e-3 * full + 1e-9)
                << "p.x " << p.x << " n " << n.x << "," << n.y << " fraction " << *exact / full;
            penumbra += (*exact > 0.05 * full && *exact < 0.95 * full) ? 1 : 0;
        }
    }
    EXPECT_GE(penumbra, 8);  // the scan crosses penumbrae, not only full light and umbra
    // Behind the one-sided panel: no light.
    EXPECT_EQ(*occluders.visible_projected_solid_angle(panel, Vec3(0, 4, 0), up, kNoReceiver), 0.0);
}

TEST(ExactPenumbra, CoaxialBallLeavesTheRingInClosedForm) {
    // A ball on the axis from p to the light, subtending β < σ: the visible ring is
    // π (sin²σ − sin²β) cos θ exactly (both caps about the same axis, above the horizon).
    const Vec3 p(0.0f, 0.0f, 0.0f);
    const Vec3 axis = glm::normalize(kLight.center - p);
    const double d = glm::length(DVec3(kLight.center) - DVec3(p));
    const float dist = 2.0f, radius = 0.08f;
    const SurfaceScene scene({sphere(p + dist * axis, radius)});
    const Vec3 n = glm::normalize(Vec3(0.2f, 1.0f, 0.1f));
    const auto exact =
        scene.sphere_light_occluders().visible_projected_solid_angle(kLight, p, n, kNoReceiver);
    ASSERT_TRUE(exact.has_value());
    const double sin2_sigma = (0.4 / d) * (0.4 / d);
    const double sin2_beta = (double(radius) / dist) * (double(radius) / dist);
    const double expected =
        kPiD * (sin2_sigma - sin2_beta) * glm::dot(DVec3(n), DVec3(kLight.center - p) / d);
    EXPECT_NEAR(*exact, expected, 1e-6 * expected);
}

TEST(ExactPenumbra, UmbraIsZeroAndFullLightIsTheClosedForm) {
    const SurfaceScene scene({sphere(Vec3(0.3f, 1.6f, 0.0f), 0.6f),
                              box(Vec3(-2.2f, 0.0f, -1.5f), Vec3(-1.4f, 1.2f, -0.7f))});
    const Vec3 up(0, 1, 0);
    // Straight below the ball's centre, seen along the light's direction: umbra.
    const Vec3 umbra =
        Vec3(0.3f, 1.6f, 0.0f) - 1.6f / 4.0f * (kLight.center - Vec3(0.3f, 1.6f, 0.0f));
    const auto zero = scene.sphere_light_occluders().visible_projected_solid_angle(
        kLight, Vec3(umbra.x, 0.0f, umbra.z), up, kNoReceiver);
    ASSERT_TRUE(zero.has_value());
    EXPECT_LE(*zero, 1e-9 * unshadowed(kLight, umbra, up));
    // Far from both shadows: the unshadowed closed form, unchanged.
    const Vec3 lit(3.0f, 0.0f, 2.0f);
    const auto full =
        scene.sphere_light_occluders().visible_projected_solid_angle(kLight, lit, up, kNoReceiver);
    ASSERT_TRUE(full.has_value());
    EXPECT_DOUBLE_EQ(*full, unshadowed(kLight, lit, up));
}

TEST(ExactPenumbra, ReceiverShapeIsSkippedAndOccludersBehindTheLightIgnored) {
    // The floor box holds p on its top face: convex, so it hides nothing above its plane; a
    // ball beyond the light (farther than every visible point of it) hides nothing either.
    const Vec3 p(0.0f, 0.0f, 0.0f);
    const Vec3 beyond = kLight.center + 3.0f * glm::normalize(kLight.center - p);
    const SurfaceScene scene({box(Vec3(-6, -0.1f, -6), Vec3(6, 0, 6)), sphere(beyond, 1.0f)});
    const auto v =
        scene.sphere_light_occluders().visible_projected_solid_angle(kLight, p, Vec3(0, 1, 0), 0);
    ASSERT_TRUE(v.has_value());
    EXPECT_DOUBLE_EQ(*v, unshadowed(kLight, p, Vec3(0, 1, 0)));
}

TEST(ExactPenumbra, FallsBackWhereTheClosedFormDoesNotApply) {
    const Vec3 p(0.0f, 0.0f, 0.0f);
    const Vec3 toward = glm::normalize(kLight.center - p);
    const Vec3 up(0, 1, 0);
    const auto fallback = [&](const std::vector<Shape>& shapes, const Vec3& n, const char* what) {
        const SurfaceScene scene(shapes);
        EXPECT_FALSE(scene.sphere_light_occluders()
                         .visible_projected_solid_angle(kLight, p, n, kNoReceiver)
                         .has_value())
            << what;
    };
    Shape mesh;
    mesh.geometry = MeshShape{"", TriangleMesh{{2.0f * toward, 2.0f * toward + Vec3(0.3f, 0, 0),
                                                2.0f * toward + Vec3(0, 0, 0.3f)},
                                               {},
                                               {{0, 1, 2}}}};
    fallback({mesh}, up, "a mesh in the cone");
    // A ball reaching from in front of the light to beyond its nearest point.
    fallback({sphere(kLight.center - 1.0f * toward, 0.8f)}, up, "an occluder straddling d - R");
    fallback({sphere(1.0f * toward, 1.5f)}, up, "p inside an occluder");
    std::vector<Shape> five;
    for (int k = 0; k < 5; ++k)
        five.push_back(sphere((1.0f + 0.5f * k) * toward + Vec3(0.01f * k, 0, 0), 0.05f));
    fallback(five, up, "more than kMaxOccluders in the cone");
}

TEST(CapRegion, OneCapIsSnydersUnclippedFormAndTwoHemispheresALune) {
    // One cap of half-angle h about a: π sin²h (n · a) above the horizon.
    const DVec3 a = glm::normalize(DVec3(0.3, 1.0, 0.2));
    const double h = 0.3;
    const SphericalCap cap{a, std::cos(h), std::sin(h)};
    const DVec3 n(0, 1, 0);
    EXPECT_NEAR(cap_intersection_projected_solid_angle(&cap, 1, n),
                kPiD * std::sin(h) * std::sin(h) * glm::dot(n, a), 1e-12);
    // Two hemispheres x ≥ 0 and z ≥ 0 meet in a lune of angle π/2 about the y axis; its
    // projected solid angle onto n = (0, 0, 1)... by Lambert, ∫ n·ω over the lune x, z ≥ 0 is
    // ½ Σ Θ_i n·m_i over its two great half-circles: with n = (1, 0, 0): ½ (π · 1) = π/2.
    const SphericalCap lune[2] = {{DVec3(1, 0, 0), 0.0, 1.0}, {DVec3(0, 0, 1), 0.0, 1.0}};
    EXPECT_NEAR(cap_intersection_projected_solid_angle(lune, 2, DVec3(1, 0, 0)), kPiD / 2, 1e-12);
    // The same lune with n = (0, 1, 0): symmetric about the equator, so zero.
    EXPECT_NEAR(cap_intersection_projected_solid_angle(lune, 2, DVec3(0, 1, 0)), 0.0, 1e-12);
}

TEST(ExactPenumbra, SceneKeyIsValidated) {
    const auto parse = [](const std::string& text) {
        static Json doc;  // JsonNode refers into the document
        doc = parse_json_text(text, "lights.json");
        return parse_light(JsonNode(doc, "lights.json", "/lights/0"), 0);
    };
    EXPECT_TRUE(parse(R"({"type": "sphere", "center": [0, 4, 0], "radius": 0.5,
                          "luminance_cd_m2": 100, "exact_penumbra": true})")
                    .exact_penumbra);
    EXPECT_FALSE(parse(R"({"type": "sphere", "center": [0, 4, 0], "radius": 0.5,
                           "luminance_cd_m2": 100})")
                     .exact_penumbra);
    const auto fails = [&](const std::string& text, const std::string& what) {
        try {
            parse(text);
            ADD_FAILURE() << "accepted " << text;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input);
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    EXPECT_TRUE(parse(R"({"type": "polygon", "vertices": [[0, 1, 0], [1, 1, 0], [1, 1, 1]],
                          "luminance_cd_m2": 1, "exact_penumbra": true})")
                    .exact_penumbra);
    fails(R"({"type": "point", "position": [0, 1, 0], "intensity_cd": 1,
              "exact_penumbra": true})",
          "exact_penumbra applies to sphere and polygon lights");
    fails(R"({"type": "sphere", "center": [0, 4, 0], "radius": 0.5, "luminance_cd_m2": 1,
              "shadows": "map", "exact_penumbra": true})",
          "exact_penumbra applies to ray-traced shadows");
    fails(R"({"type": "sphere", "center": [0, 4, 0], "radius": 0.5, "luminance_cd_m2": 1,
              "exact_penumbra": 1})",
          "/lights/0/exact_penumbra");
}

}  // namespace
}  // namespace kasumi
