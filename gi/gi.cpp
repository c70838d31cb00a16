#include "gi/gi.h"

#include "core/error.h"
#include "gi/path_tracer.h"
#include "gi/photon/photon_gi.h"
#include "gi/radiosity_gi.h"
#include "render/scene_runtime.h"

namespace kasumi {

std::shared_ptr<const GiMethod> make_gi_method(const SceneRuntime& scene) {
    const SceneDesc& desc = scene.desc();
    switch (desc.render.gi) {
        case GiMode::None:
            return nullptr;
        case GiMode::Path:
            return std::make_shared<PathTracer>(scene);
        case GiMode::Radiosity:
            return std::make_shared<RadiosityGi>(scene);
        case GiMode::Photons:
            return std::make_shared<PhotonGi>(scene);
    }
    throw_input_error(desc.file + ": render.gi = " + gi_mode_name(desc.render.gi) +
                      ": not available in this build");
}

}  // namespace kasumi
