#include "apps/scene_options.h"

namespace kasumi {

void SceneOptions::add_to(CLI::App& command) {
    command.add_option("scene", scene_path, "scene file (JSON, comments allowed)")->required();
    command.add_option("--set", sets, "override a scene value: /json/pointer=VALUE (repeatable)");
    auto* q = command.add_flag("-q,--quiet", quiet, "no progress or logs");
    command.add_flag("-v,--verbose", verbose, "print the plan and render statistics")->excludes(q);
}

SceneDesc SceneOptions::load() const {
    std::vector<Override> overrides;
    overrides.reserve(sets.size());
    for (const std::string& s : sets)
        overrides.push_back(parse_override(s));
    return load_scene(scene_path, overrides);
}

}  // namespace kasumi
