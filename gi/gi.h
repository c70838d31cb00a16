#pragma once
/// The global-illumination methods of render.gi, built for a scene: the factory callers pass to
/// SceneRuntime (render/scene_runtime.h), which plugs the method into the renderer's surface
/// stage through render/gi_method.h.
#include "render/gi_method.h"

#include <memory>

namespace kasumi {

/// Builds the scene's render.gi method (null for "none"): the path tracer, radiosity or photon
/// mapping, running its precomputation on `scene` (surfaces, media and sky built). Throws an
/// input error naming the scene file for a method this build does not have.
std::shared_ptr<const GiMethod> make_gi_method(const SceneRuntime& scene);

}  // namespace kasumi
