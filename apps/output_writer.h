#pragma once
/// Writes a render's EXR and PNG preview with metadata.
#include "render/renderer.h"
#include "render/stage_times.h"

#include <string>

namespace kasumi {

struct OutputPaths {
    std::string exr;
    std::string preview;  ///< empty: no preview
};

/// Creates parent directories, then writes both files atomically (temporary name, rename).
/// The EXR metadata holds the stage times given (written as kasumi/time/<stage>_s: write_exr adds
/// the prefix) and the plan's stages that ran and were skipped.
void write_render_outputs(const SceneRuntime& scene, const RenderResult& result,
                          const OutputPaths& paths, const StageTimes& times = {});

/// Render statistics as lines for -v.
std::string format_stats(const SceneRuntime& scene, const RenderResult& result,
                         const StageTimes& times = {});

}  // namespace kasumi
