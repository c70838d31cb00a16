// The scanline method (Bouknight & Kelley 1970; Appel 1968): its visible face and its
// shadowed sub-spans equal ray tracing on every pixel whose footprint no shadow edge or face
// boundary crosses, for point and parallel light.
#include "surface/scanline/scanline_shadows.h"

#include "tests/surface/shadow_test_scene.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstdio>

namespace kasumi {
namespace {

struct Comparison {
    int shaded = 0, shadowed = 0, cut = 0;
    int wrong_face = 0;  ///< uncut pixels where the scanline shows another shape
    int differ = 0;      ///< uncut pixels whose lit/unlit state differs
};

Comparison compare_image(const std::vector<Shape>& shapes, const LightCentre& light,
                         const Vec3& eye, const Vec3& target, int w, int h) {
    const SurfaceScene scene(shapes);
    const PinholeView view = pinhole_view(eye, target, w, h);
    ScanlineCamera camera;
    camera.eye = eye;
    camera.forward = view.forward;
    camera.right = view.right;
    camera.up = view.up;
    camera.half_width = 0.8;
    camera.width = w;
    camera.height = h;
    const ScanlineImage image = render_scanline_shadows(shapes, light, camera);
    Comparison c;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int centre = ray_shadow_state(scene, light, view, x + 0.5f, y + 0.5f);
            if (centre < 0)
                continue;
            ++c.shaded;
            c.shadowed += centre & 1;
            if (ray_shadow_state(scene, light, view, x, y) != centre ||
                ray_shadow_state(scene, light, view, x + 1, y) != centre ||
                ray_shadow_state(scene, light, view, x, y + 1) != centre ||
                ray_shadow_state(scene, light, view, x + 1, y + 1) != centre) {
                ++c.cut;
                continue;
            }
            const size_t p = size_t(y) * w + x;
            c.wrong_face += image.shape[p] != centre / 2 ? 1 : 0;
            c.differ += image.shadowed[p] != (centre & 1) ? 1 : 0;
        }
    }
    return c;
}

TEST(ScanlineShadowTest, AgreesWithRayTracingOffShadowEdges) {
    for (const LightCentre& light :
         {point_centre(Vec3(0.4f, 4.2f, 0.9f)), parallel_centre(Vec3(-0.5f, 1.0f, 0.6f))}) {
        const Comparison c = compare_image(mesh_scene(), light, Vec3(0.7f, 3.1f, 6.3f),
                                           Vec3(0.0f, 0.5f, 0.0f), 320, 200);
        EXPECT_GT(c.shaded, 30000);
        EXPECT_GT(c.shadowed, 500);
        EXPECT_LT(c.cut, c.shaded / 10);
        EXPECT_EQ(c.wrong_face, 0);
        EXPECT_EQ(c.differ, 0);
    }
}

// The rows run in parallel bands: the image and the counts are the same for 1, 2 and 3 threads.
TEST(ScanlineShadowTest, SameImageForAnyThreadCount) {
    const PinholeView view = pinhole_view(Vec3(0.7f, 3.1f, 6.3f), Vec3(0.0f, 0.5f, 0.0f), 320, 200);
    ScanlineCamera camera;
    camera.eye = view.eye;
    camera.forward = view.forward;
    camera.right = view.right;
    camera.up = view.up;
    camera.half_width = 0.8;
    camera.width = view.w;
    camera.height = view.h;
    const LightCentre light = point_centre(Vec3(0.4f, 4.2f, 0.9f));
    std::vector<ScanlineImage> images;
    for (int threads : {1, 2, 3}) {
        tbb::task_arena arena(threads);
        arena.execute(
            [&] { images.push_back(render_scanline_shadows(mesh_scene(), light, camera)); });
    }
    for (size_t i = 1; i < images.size(); ++i) {
        EXPECT_EQ(images[i].shape, images[0].shape);
        EXPECT_EQ(images[i].primitive, images[0].primitive);
        EXPECT_EQ(images[i].shadowed, images[0].shadowed);
        EXPECT_EQ(images[i].spans, images[0].spans);
        EXPECT_EQ(images[i].shadow_pairs, images[0].shadow_pairs);
    }
    EXPECT_GT(images[0].spans, 500u);
    // Depth is compared per span segment: far fewer depth evaluations than covered pixels.
    std::printf("covered pixels %zu, depth evaluations %zu\n", images[0].covered_pixels,
                images[0].depth_evaluations);
    EXPECT_LT(images[0].depth_evaluations, images[0].covered_pixels / 4);
}

}  // namespace
}  // namespace kasumi
