#include "sequence/frame_runtime.h"

#include "gi/gi.h"

namespace kasumi {

std::unique_ptr<SceneRuntime> build_frame_runtime(SequenceCache& cache, const Json& doc,
                                                  const std::string& scene_path, SceneDesc desc,
                                                  bool reuse) {
    const std::string key = reuse ? bvh_key(doc) : std::string();
    std::shared_ptr<const SurfaceScene> bvh = cache.surfaces(key);
    const bool bvh_reused = bvh != nullptr;
    const std::string sky_key =
        reuse ? sky_tables_key(doc, scene_path, desc.sky.get()) : std::string();
    std::shared_ptr<const SkyLuts> sky_tables = cache.sky_tables(sky_key);
    auto runtime = std::make_unique<SceneRuntime>(std::move(desc), std::move(bvh),
                                                  std::move(sky_tables), make_gi_method);
    if (runtime->surfaces() != nullptr && !bvh_reused) {
        cache.count_bvh_built();
        cache.remember_surfaces(key, runtime->shared_surfaces());
    }
    if (runtime->sky() != nullptr && runtime->sky()->shared_tables() != nullptr &&
        !runtime->sky()->tables_reused()) {
        cache.count_sky_tables_built();
        cache.remember_sky_tables(sky_key, runtime->sky()->shared_tables());
    }
    return runtime;
}

}  // namespace kasumi
