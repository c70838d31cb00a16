#pragma once
/// Wall time of each stage of one render (`kasumi render -v` and the EXR metadata), and the
/// plan's skipped stages in one line.
#include "render/scene_runtime.h"
#include "scene/plan.h"

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace kasumi {

/// Seconds per stage; negative: the stage did not run (or was not timed).
struct StageTimes {
    double load_s = -1.0;    ///< read and validate the scene: JSON, meshes, VDB grids to bricks
    double build_s = -1.0;   ///< the runtime: Embree BVH, media set, shadow maps, GI, sky tables
    double render_s = -1.0;  ///< tiles: camera rays through every stage
    double write_s = -1.0;   ///< EXR and preview PNG
    /// Parts of the stages above that ran, named "<stage>/<part>" ("load/grids", "build/bvh",
    /// "build/sky", ...), seconds each.
    std::vector<std::pair<std::string, double>> parts;
};

/// Adds to `times.parts` what `runtime` measured: the VDB grids read and bricked while the scene
/// loaded ("load/grids") and each structure its constructor built ("build/bvh",
/// "build/shadow-maps", "build/shadow-volumes", "build/media", "build/sky", "build/gi").
void add_stage_parts(StageTimes& times, const SceneRuntime& runtime);

/// Seconds elapsed on the steady clock since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Lines "  load   0.012 s" for -v, one per timed stage.
std::string format_stage_times(const StageTimes& times);

/// EXR metadata: time/<stage>_s for every timed stage, plan/ran and plan/skipped (stage names,
/// comma-separated).
std::vector<std::pair<std::string, std::string>> stage_metadata(const StageTimes& times,
                                                                const Plan& plan);

/// Names of the plan's stages that did not run, comma-separated ("" if none).
std::string skipped_stage_names(const Plan& plan);

}  // namespace kasumi
