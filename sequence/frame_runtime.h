#pragma once
/// The runtime scene of one frame of a sequence, built with the BVH and sky tables its
/// SequenceCache remembers from earlier frames (and remembering those it builds).
#include "render/scene_runtime.h"
#include "sequence/sequence_cache.h"

#include <memory>
#include <string>

namespace kasumi {

/// Builds `desc` (parsed from the frame document `doc` of `scene_path` through `cache`) with
/// the GI methods of gi/gi.h, reusing the cached BVH and sky tables when `reuse` is on, and
/// counts what it built in `cache`.
std::unique_ptr<SceneRuntime> build_frame_runtime(SequenceCache& cache, const Json& doc,
                                                  const std::string& scene_path, SceneDesc desc,
                                                  bool reuse);

}  // namespace kasumi
