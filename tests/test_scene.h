#pragma once
/// Builds scenes for tests from JSON text.
#include "render/scene_runtime.h"
#include "scene/scene_loader.h"

#include <memory>

namespace kasumi {

inline SceneDesc scene_from_text(const std::string& text) {
    const Json doc = parse_json_text(text, "test.json");
    return parse_scene(doc, KASUMI_SOURCE_DIR "/data/scenes/test.json");
}

inline std::unique_ptr<SceneRuntime> runtime_from_text(const std::string& text) {
    return std::make_unique<SceneRuntime>(scene_from_text(text));
}

}  // namespace kasumi
