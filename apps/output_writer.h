#pragma once
/// Writes a render's EXR and PNG preview with metadata.
#include "render/renderer.h"

#include <string>

namespace kasumi {

struct OutputPaths {
    std::string exr;
    std::string preview;  ///< empty: no preview
};

/// Creates parent directories, then writes both files atomically (temporary name, rename).
void write_render_outputs(const SceneRuntime& scene, const RenderResult& result,
                          const OutputPaths& paths);

/// Render statistics as lines for -v.
std::string format_stats(const SceneRuntime& scene, const RenderResult& result);

}  // namespace kasumi
