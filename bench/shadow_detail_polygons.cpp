// The object-space method's pass 1 (surface/shadows/shadow_polygons.h) on a scene, with both
// clippers: prints one JSON object with, for Weiler–Atherton (the face clipped once against its
// united shadow) and for the convex split (each lit piece cut by every occluder's lines in
// turn), the number of lit and shadowed detail polygons, their rings, and pass 1's time
// (median of `runs`, no cache). Light 0 must be a point, spot, goniometric or directional light.
// Usage: shadow_detail_polygons SCENE.json [runs] [/json/pointer=VALUE]...
#include "bench/shadow_bench_scene.h"
#include "surface/shadows/shadow_polygons.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;

struct Counts {
    size_t lit = 0, shadowed = 0, rings = 0;
    double seconds = 0.0;
};

Counts measure(const std::vector<kasumi::Shape>& shapes, const kasumi::LightCentre& light,
               kasumi::ShadowClipper clipper, int runs) {
    std::vector<double> times;
    kasumi::ShadowPolygons polygons;
    for (int r = 0; r < runs; ++r) {
        const auto start = Clock::now();
        polygons = kasumi::build_shadow_polygons(shapes, light, clipper);
        times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    Counts c;
    c.seconds = times[times.size() / 2];
    for (const auto& shape : polygons.faces)
        for (const kasumi::FaceDetail& face : shape) {
            c.lit += face.lit.size();
            c.shadowed += face.shadowed.size();
            for (const auto* list : {&face.lit, &face.shadowed})
                for (const kasumi::PolygonRegion& p : *list)
                    c.rings += p.rings.size();
        }
    return c;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace kasumi;
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: shadow_detail_polygons SCENE.json [runs] [/pointer=VALUE]...\n");
        return 2;
    }
    try {
        const int runs = argc > 2 ? std::max(1, std::stoi(argv[2])) : 3;
        const ShadowBenchScene loaded = load_shadow_bench_scene(argv[1], argc, argv, 3);
        const LightCentre& light = loaded.light;
        std::printf("{");
        const char* separator = "";
        for (const auto& [name, clipper] :
             {std::pair{"weiler_atherton", ShadowClipper::WeilerAtherton},
              std::pair{"convex_split", ShadowClipper::ConvexSplit}}) {
            const Counts c = measure(loaded.scene.shapes, light, clipper, runs);
            std::printf(
                "%s\"%s\": {\"lit\": %zu, \"shadowed\": %zu, \"rings\": %zu, \"build_s\": "
                "%.6g}",
                separator, name, c.lit, c.shadowed, c.rings, c.seconds);
            separator = ", ";
        }
        std::printf("}\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "shadow_detail_polygons: %s\n", e.what());
        return 1;
    }
    return 0;
}
