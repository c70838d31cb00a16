// Object-space shadows (Atherton, Weiler & Greenberg 1978): the detail polygons partition every
// face (no cracks, no overlaps by area), and the lit/unlit state they give equals ray tracing
// on every pixel whose footprint no shadow edge crosses, for point and parallel light, on the
// shared polygon scene and on one with the hard cases (the light in a face's plane, occluders
// touching their receiver, a receiver reaching behind the light, T-junctions, slivers, coplanar
// faces). Also the clipper itself and the cache between frames.
#include "surface/shadows/object_space_shadows.h"
#include "surface/shadows/shadow_polygon_cache.h"

#include "tests/surface/shadow_test_scene.h"
#include "tests/surface/test_shapes.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace kasumi {
namespace {

TEST(ConvexPolygonTest, SplitKeepsBothSidesAndTheirAreas) {
    const ConvexPolygon square{{{0, 0}, {2, 0}, {2, 2}, {0, 2}}};
    // A diagonal through two vertices: two triangles, no new vertex.
    const HalfPlane diagonal{glm::normalize(DVec2(-1, 1)), 0.0};
    const PolygonSplit d = split(square, diagonal, 1e-12);
    EXPECT_EQ(d.inside.vertices.size(), 3u);
    EXPECT_EQ(d.outside.vertices.size(), 3u);
    EXPECT_DOUBLE_EQ(area(d.inside), 2.0);
    EXPECT_DOUBLE_EQ(area(d.outside), 2.0);
    // A line grazing an edge within the tolerance leaves the polygon whole on one side.
    const PolygonSplit g = split(square, HalfPlane{{0, 1}, -1e-13}, 1e-12);
    EXPECT_TRUE(g.outside.vertices.empty());
    EXPECT_EQ(g.inside.vertices.size(), 4u);
    // A sliver cut: areas still sum to the whole.
    const PolygonSplit s = split(square, HalfPlane{glm::normalize(DVec2(1e-7, 1)), -1e-6}, 1e-12);
    EXPECT_NEAR(area(s.inside) + area(s.outside), 4.0, 4e-15);
    EXPECT_GT(area(s.outside), 0.0);
    EXPECT_TRUE(contains(square, {1, 1}, 0.0));
    EXPECT_FALSE(contains(square, {2.1, 1}, 0.0));
}

const Vec3 kPointLight(0.4f, 4.2f, 0.9f);
const Vec3 kSun(-0.5f, 1.0f, 0.6f);

/// Detail polygons partition every face: areas sum to the face's within 1e-9 relative, and
/// every sample point of the face away from the pieces' edges lies in exactly one piece (no
/// crack, no overlap). Counts the faces with a shadow and the detail polygons.
void expect_partition(const ShadowPolygons& polygons, ShadowClipper clipper, size_t& shadowed_faces,
                      size_t& pieces) {
    for (const auto& shape : polygons.faces) {
        for (const FaceDetail& face : shape) {
            const double whole = area(face.face);
            double sum = 0.0;
            for (const auto* list : {&face.lit, &face.shadowed})
                for (const PolygonRegion& p : *list) {
                    if (clipper == ShadowClipper::WeilerAtherton) {
                        EXPECT_GT(area(p), 0.0);
                    } else {
                        EXPECT_GE(area(p), 0.0);  // the convex split may leave a degenerate piece
                    }
                    sum += area(p);
                }
            EXPECT_NEAR(sum, whole, 1e-9 * whole);
            shadowed_faces += face.shadowed.empty() ? 0 : 1;
            pieces += face.lit.size() + face.shadowed.size();
            if (face.face.vertices.size() != 3)
                continue;
            // Barycentric samples on a 13 × 13 lattice strictly inside the triangle.
            const std::vector<DVec2>& v = face.face.vertices;
            const double tolerance = 1e-9 * std::sqrt(whole);
            for (int i = 1; i < 13; ++i)
                for (int j = 1; i + j < 13; ++j) {
                    const DVec2 p = v[0] + (i / 13.0) * (v[1] - v[0]) + (j / 13.0) * (v[2] - v[0]);
                    int covering = 0;
                    bool near_edge = false;
                    for (const auto* list : {&face.lit, &face.shadowed})
                        for (const PolygonRegion& piece : *list) {
                            near_edge = near_edge || distance_to_boundary(piece, p) < tolerance;
                            covering += contains(piece, p) ? 1 : 0;
                        }
                    if (!near_edge) {
                        EXPECT_EQ(covering, 1) << "at (" << p.x << ", " << p.y << ")";
                    }
                }
        }
    }
}

TEST(ObjectSpaceShadowTest, DetailPolygonsPartitionEveryFace) {
    for (const auto& shapes : {mesh_scene(), hard_case_scene()}) {
        for (const LightCentre& light : {point_centre(kPointLight), parallel_centre(kSun)}) {
            for (const ShadowClipper clipper :
                 {ShadowClipper::WeilerAtherton, ShadowClipper::ConvexSplit}) {
                const ShadowPolygons polygons = build_shadow_polygons(shapes, light, clipper);
                size_t shadowed_faces = 0, pieces = 0;
                expect_partition(polygons, clipper, shadowed_faces, pieces);
                EXPECT_GT(shadowed_faces, 20u);
                EXPECT_GT(polygons.clipped_pairs, 50u);
            }
        }
    }
}

// The face clipped against its whole shadow at once gives fewer detail polygons than the
// convex pieces of splitting by each occluder in turn (a concave shadow is one polygon).
TEST(ObjectSpaceShadowTest, WeilerAthertonGivesFewerDetailPolygonsThanConvexSplit) {
    for (const auto& shapes : {mesh_scene(), hard_case_scene()}) {
        for (const LightCentre& light : {point_centre(kPointLight), parallel_centre(kSun)}) {
            size_t faces_wa = 0, faces_convex = 0, wa = 0, convex = 0;
            for (const ShadowClipper clipper :
                 {ShadowClipper::WeilerAtherton, ShadowClipper::ConvexSplit}) {
                const bool is_wa = clipper == ShadowClipper::WeilerAtherton;
                expect_partition(build_shadow_polygons(shapes, light, clipper), clipper,
                                 is_wa ? faces_wa : faces_convex, is_wa ? wa : convex);
            }
            std::printf("detail polygons: Weiler-Atherton %zu, convex split %zu\n", wa, convex);
            EXPECT_EQ(faces_wa, faces_convex);
            EXPECT_LT(wa, convex);
        }
    }
}

TEST(ObjectSpaceShadowTest, LightInTheFacePlaneLightsNoPointOfIt) {
    const std::vector<Shape> shapes = hard_case_scene();
    const ShadowPolygons polygons = build_shadow_polygons(shapes, point_centre(kPointLight));
    const std::vector<FaceDetail>& panel = polygons.faces[shapes.size() - 3];
    ASSERT_EQ(panel.size(), 2u);
    for (const FaceDetail& face : panel) {
        EXPECT_FALSE(face.faces_light);
        EXPECT_TRUE(face.lit.empty());
    }
}

struct Comparison {
    int shaded = 0;    ///< pixels on a surface facing the light
    int shadowed = 0;  ///< of those, in shadow by ray tracing
    int cut = 0;       ///< footprint crossed by a shadow edge or a face boundary: not compared
    int differ = 0;    ///< uncut pixels whose lit/unlit state differs from ray tracing
};

/// Lit/unlit states of a w × h pinhole image. A pixel is compared when ray tracing gives its
/// centre and four corners the same state on the same shape (no shadow edge cuts it).
Comparison compare_image(const std::vector<Shape>& shapes, const LightCentre& light,
                         const Vec3& eye, const Vec3& target, int w, int h,
                         ShadowClipper clipper = ShadowClipper::WeilerAtherton) {
    const SurfaceScene scene(shapes);
    const ObjectSpaceShadows shadows(
        std::make_shared<const ShadowPolygons>(build_shadow_polygons(shapes, light, clipper)),
        light, shapes, scene);
    const PinholeView view = pinhole_view(eye, target, w, h);
    const auto ray_state = [&](float x, float y) {
        return ray_shadow_state(scene, light, view, x, y);
    };
    Comparison c;
    for_each_facing_pixel(scene, light, view, [&](int x, int y, const FacingHit& f) {
        const int centre = int(f.hit.shape) * 2 + (f.ray_shadow ? 1 : 0);
        ++c.shaded;
        c.shadowed += f.ray_shadow ? 1 : 0;
        if (ray_state(x, y) != centre || ray_state(x + 1, y) != centre ||
            ray_state(x, y + 1) != centre || ray_state(x + 1, y + 1) != centre) {
            ++c.cut;
            return;
        }
        c.differ += shadows.in_shadow(f.hit, f.origin) != f.ray_shadow ? 1 : 0;
    });
    return c;
}

TEST(ObjectSpaceShadowTest, AgreesWithRayTracingOffShadowEdges) {
    const Vec3 eye(0.7f, 3.1f, 6.3f), target(0.0f, 0.5f, 0.0f);
    for (const auto& shapes : {mesh_scene(), hard_case_scene()}) {
        for (const LightCentre& light : {point_centre(kPointLight), parallel_centre(kSun)}) {
            for (const ShadowClipper clipper :
                 {ShadowClipper::WeilerAtherton, ShadowClipper::ConvexSplit}) {
                const Comparison c = compare_image(shapes, light, eye, target, 320, 200, clipper);
                EXPECT_GT(c.shaded, 30000);
                EXPECT_GT(c.shadowed, 500);
                EXPECT_LT(c.cut, c.shaded / 10);
                EXPECT_EQ(c.differ, 0);
            }
        }
    }
}

// The back wall reaches above the light; the eye looks at it and at the plate next to the
// light whose shadow falls far up the wall.
TEST(ObjectSpaceShadowTest, ReceiverBehindTheLight) {
    const Comparison c = compare_image(hard_case_scene(), point_centre(kPointLight),
                                       Vec3(0.5f, 3.0f, 5.0f), Vec3(0.0f, 4.0f, -3.0f), 320, 200);
    EXPECT_GT(c.shaded, 20000);
    EXPECT_GT(c.shadowed, 500);
    EXPECT_EQ(c.differ, 0);
}

TEST(ObjectSpaceShadowTest, SpheresCastAndReceiveByShadowRays) {
    const std::vector<Shape> shapes = {
        quad(Vec3(-5, 0, 5), Vec3(5, 0, 5), Vec3(5, 0, -5), Vec3(-5, 0, -5)),
        sphere(Vec3(0.0f, 1.0f, 0.0f), 0.5f),
        box(Vec3(-0.2f, 2.0f, -0.2f), Vec3(0.2f, 2.2f, 0.2f))};
    const SurfaceScene scene(shapes);
    const LightCentre light = point_centre(Vec3(0.0f, 4.0f, 0.0f));
    const ObjectSpaceShadows shadows(
        std::make_shared<const ShadowPolygons>(build_shadow_polygons(shapes, light)), light, shapes,
        scene);
    const auto at = [&](const Vec3& from, const Vec3& to) {
        const auto hit = scene.intersect(Ray{from, glm::normalize(to - from), 0.0f, kInfinity});
        EXPECT_TRUE(hit.has_value());
        return shadows.in_shadow(*hit, offset_ray_origin(*hit, toward_light(light, hit->position)));
    };
    EXPECT_TRUE(at(Vec3(0.0f, 0.5f, 3.0f), Vec3(0.0f, 0.0f, 0.6f)));       // floor under the ball
    EXPECT_FALSE(at(Vec3(0.0f, 0.5f, 3.0f), Vec3(0.0f, 0.0f, 2.5f)));      // floor in the open
    EXPECT_TRUE(at(Vec3(2.0f, 1.6f, 0.0f), Vec3(0.1f, 1.49f, 0.0f)));      // ball under the box
    EXPECT_FALSE(at(Vec3(2.0f, 1.8f, 0.0f), Vec3(0.354f, 1.354f, 0.0f)));  // out of its shadow
}

TEST(ObjectSpaceShadowTest, CacheReusesPolygonsWhileLightAndGeometryStay) {
    std::vector<Shape> shapes = mesh_scene();
    const LightCentre light = point_centre(Vec3(0.41f, 4.2f, 0.9f));
    bool reused = true;
    const auto first = cached_shadow_polygons(shapes, light, &reused);
    EXPECT_FALSE(reused);
    const auto second = cached_shadow_polygons(shapes, light, &reused);
    EXPECT_TRUE(reused);
    EXPECT_EQ(first.get(), second.get());
    // The light moves: rebuilt.
    cached_shadow_polygons(shapes, point_centre(Vec3(0.41f, 4.3f, 0.9f)), &reused);
    EXPECT_FALSE(reused);
    // A vertex moves: rebuilt.
    std::get<BoxShape>(shapes[3].geometry).max.y += 0.01f;
    const auto moved = cached_shadow_polygons(shapes, light, &reused);
    EXPECT_FALSE(reused);
    EXPECT_NE(moved.get(), first.get());
}

}  // namespace
}  // namespace kasumi
