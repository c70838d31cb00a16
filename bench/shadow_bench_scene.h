#pragma once
// The scene of a shadow bench's command line, with its /json/pointer=VALUE overrides, and the
// centre of its light 0 (which must be a point, spot, goniometric or directional light).
#include "scene/scene_loader.h"
#include "surface/shadows/light_centre.h"

#include <stdexcept>
#include <vector>

namespace kasumi {

struct ShadowBenchScene {
    SceneDesc scene;
    LightCentre light;
};

/// Loads argv's scene `path` with the overrides argv[first_override..argc).
inline ShadowBenchScene load_shadow_bench_scene(const char* path, int argc, char** argv,
                                                int first_override) {
    std::vector<Override> overrides;
    for (int i = first_override; i < argc; ++i)
        overrides.push_back(parse_override(argv[i]));
    SceneDesc scene = load_scene(path, overrides);
    if (scene.lights.empty() || !is_delta(scene.lights[0]))
        throw std::runtime_error("light 0 must be a point-like or directional light");
    const LightCentre light = light_centre(scene.lights[0]);
    return {std::move(scene), light};
}

}  // namespace kasumi
