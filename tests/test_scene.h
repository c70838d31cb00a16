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

/// The runtime of a scene given as JSON text; `make_gi` builds its GI method (gi/gi.h's
/// make_gi_method; null: a scene asking for one is an input error).
inline std::unique_ptr<SceneRuntime> runtime_from_text(const std::string& text,
                                                       const GiFactory& make_gi = nullptr) {
    return std::make_unique<SceneRuntime>(scene_from_text(text), make_gi);
}

}  // namespace kasumi
