// The scanline shadow method (surface/scanline/scanline_shadows.h) on a scene, against ray
// tracing: prints one JSON object with the scanline pass's time (median of `runs`, visibility
// and shadow spans together), the time of the same image by camera rays and one shadow ray per
// visible point, the per-span depth comparison's evaluations against the covered pixels a
// Z-buffer would test, and the fraction of the pixels seeing a light-facing polygon whose lit/unlit
// state differs (the pass alone, without spheres and without shading; the render mode
// "shadows": "scanline" is timed by bench/shadow_study.sh). Light 0 must be a point, spot,
// goniometric or directional light.
// Usage: scanline_shadow_bench SCENE.json WxH [runs] [/json/pointer=VALUE]...
#include "bench/shadow_bench_scene.h"
#include "core/camera.h"
#include "surface/scanline/scanline_shadows.h"
#include "surface/surface_scene.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
    using namespace kasumi;
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: scanline_shadow_bench SCENE.json WxH [runs] [/pointer=VALUE]...\n");
        return 2;
    }
    try {
        int width = 0, height = 0;
        if (std::sscanf(argv[2], "%dx%d", &width, &height) != 2 || width < 1 || height < 1)
            throw std::runtime_error(std::string("bad size ") + argv[2]);
        const int runs = argc > 3 ? std::max(1, std::stoi(argv[3])) : 3;
        const ShadowBenchScene loaded = load_shadow_bench_scene(argv[1], argc, argv, 4);
        const SceneDesc& scene = loaded.scene;
        const LightCentre& light = loaded.light;
        const Camera camera(scene.camera, width, height);
        ScanlineCamera view;
        view.eye = scene.camera.position;
        view.forward = glm::normalize(scene.camera.look_at - scene.camera.position);
        view.right = glm::normalize(glm::cross(view.forward, scene.camera.up));
        view.up = glm::cross(view.right, view.forward);
        view.half_width =
            std::tan(0.5 * glm::radians(double(scene.camera.fov_deg))) * width / height;
        view.width = width;
        view.height = height;

        std::vector<double> times;
        ScanlineImage image;
        for (int r = 0; r < runs; ++r) {
            const auto start = Clock::now();
            image = render_scanline_shadows(scene.shapes, light, view);
            times.push_back(seconds_since(start));
        }
        std::sort(times.begin(), times.end());

        const SurfaceScene surfaces(scene.shapes);
        std::vector<double> ray_times;
        size_t compared = 0, differ = 0;
        for (int r = 0; r < runs; ++r) {
            compared = differ = 0;
            const auto start = Clock::now();
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    const Ray ray = camera.generate_ray(x + 0.5f, y + 0.5f);
                    const auto hit = surfaces.intersect(ray);
                    const size_t p = size_t(y) * width + x;
                    if (!hit || image.shape[p] < 0)
                        continue;
                    Vec3 n = hit->geometric_normal;
                    if (glm::dot(n, ray.direction) > 0.0f)
                        n = -n;
                    const Vec3 wi = toward_light(light, hit->position);
                    if (glm::dot(n, wi) <= 0.0f)
                        continue;
                    const Vec3 origin = offset_ray_origin(*hit, wi);
                    const float reach = light.at_infinity
                                            ? kInfinity
                                            : glm::length(light.position - origin) * (1 - 1e-5f);
                    const bool blocked = surfaces.occluded(Ray{origin, wi, 0.0f, reach});
                    ++compared;
                    differ += blocked != (image.shadowed[p] != 0) ? 1 : 0;
                }
            ray_times.push_back(seconds_since(start));
        }
        std::sort(ray_times.begin(), ray_times.end());
        std::printf(
            "{\"pixels\": %zu, \"scanline_s\": %.6g, \"shadow_pairs\": %zu, \"spans\": %zu, "
            "\"covered_pixels\": %zu, \"depth_evaluations\": %zu, "
            "\"ray_s\": %.6g, \"compared\": %zu, \"differ_fraction\": %.6g}\n",
            size_t(width) * height, times[times.size() / 2], image.shadow_pairs, image.spans,
            image.covered_pixels, image.depth_evaluations, ray_times[ray_times.size() / 2],
            compared, compared > 0 ? double(differ) / double(compared) : 0.0);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "scanline_shadow_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
