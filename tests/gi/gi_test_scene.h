#pragma once
/// Scenes with their GI method for the tests of gi/.
#include "gi/gi.h"
#include "tests/test_scene.h"

namespace kasumi {

/// The runtime of a scene given as JSON text, its render.gi method built by make_gi_method.
inline std::unique_ptr<SceneRuntime> gi_runtime_from_text(const std::string& text) {
    return runtime_from_text(text, make_gi_method);
}

}  // namespace kasumi
