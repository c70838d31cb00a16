#pragma once
/// What `kasumi render` reports on stderr about a render and its files (-v lines, warnings);
/// the files themselves are written by render/frame_output.h.
#include "core/exr_io.h"
#include "render/renderer.h"
#include "render/stage_times.h"

#include <string>

namespace kasumi {

/// The -v lines on the EXR's pixel type (and, for half, the values saturated or flushed to 0).
std::string format_write_stats(const SceneRuntime& scene, const ExrWriteReport& report);

/// A one-line warning when half output saturated values (empty otherwise): how many, the
/// largest value, and that --pixel-type float keeps them.
std::string half_saturation_warning(const ExrWriteReport& report, const std::string& path);

/// Render statistics as lines for -v.
std::string format_stats(const SceneRuntime& scene, const RenderResult& result,
                         const StageTimes& times = {});

}  // namespace kasumi
