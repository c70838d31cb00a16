#include "render/plan.h"

#include "volume/medium_set.h"

#include <sstream>

namespace kasumi {

namespace {

bool any_ambient_material(const SceneDesc& scene) {
    for (const Material& m : scene.materials) {
        if (max_component(std::get<PhongMaterial>(m).ka) > 0.0f)
            return true;
    }
    return false;
}

std::string count(size_t n, const char* what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

Plan make_plan(const SceneDesc& scene) {
    Plan plan;
    const bool has_shapes = !scene.shapes.empty();
    const bool has_lights = !scene.lights.empty();
    const bool has_media = !scene.media.empty();
    const bool media_scatter = MediumSet(scene.media).scatters();

    plan.surfaces = has_shapes;
    plan.stages.push_back({"surfaces", plan.surfaces,
                           has_shapes
                               ? count(scene.shapes.size(), "shape") + ": Embree BVH, closest hit"
                               : "no shapes: no BVH built"});

    plan.direct_light = has_shapes && has_lights;
    plan.stages.push_back({"direct-light", plan.direct_light,
                           plan.direct_light
                               ? count(scene.lights.size(), "light") + ", Phong shading"
                           : !has_shapes ? "no shapes to light"
                                         : "no lights"});

    plan.shadow_rays = has_shapes && has_lights && scene.render.shadows;
    plan.stages.push_back({"shadow-rays", plan.shadow_rays,
                           plan.shadow_rays        ? "one shadow ray per delta light (hard shadows)"
                           : !scene.render.shadows ? "render.shadows is false"
                           : !has_shapes           ? "no shapes can cast shadows"
                                                   : "no lights"});

    plan.ambient = has_shapes && max_component(scene.ambient) > 0.0f && any_ambient_material(scene);
    plan.stages.push_back({"ambient", plan.ambient,
                           plan.ambient ? "ambient light and materials with ka > 0"
                                        : "ambient light or every ka is zero"});

    plan.volume = has_media;
    plan.stages.push_back(
        {"volume-transmittance", plan.volume,
         has_media ? count(scene.media.size(), "homogeneous medium") + ": exact Beer-Lambert"
                   : "no media"});

    plan.in_scattering = has_media && media_scatter && has_lights;
    plan.stages.push_back(
        {"volume-in-scattering", plan.in_scattering,
         plan.in_scattering ? "single scattering, marched with step " +
                                  std::to_string(scene.render.volume.step_m) + " m" +
                                  (plan.shadow_rays ? ", shadowed by surfaces" : "")
         : !has_media     ? "no media"
         : !media_scatter ? "media do not scatter (sigma_s = 0): transmittance only"
                          : "no lights to scatter"});

    plan.stages.push_back({"multiple-scattering", false,
                           plan.in_scattering
                               ? "not in this build: light scattered more than once is left out"
                               : "no in-scattering"});
    plan.stages.push_back({"background", max_component(scene.background) > 0.0f,
                           max_component(scene.background) > 0.0f ? "constant background radiance"
                                                                  : "black background"});
    return plan;
}

std::string plan_to_text(const Plan& plan) {
    std::ostringstream out;
    for (const PlanStage& s : plan.stages) {
        out << (s.enabled ? "  run   " : "  skip  ") << s.name << ": " << s.reason << "\n";
    }
    return out.str();
}

Json plan_to_json(const Plan& plan) {
    Json stages = Json::array();
    for (const PlanStage& s : plan.stages) {
        stages.push_back({{"name", s.name}, {"enabled", s.enabled}, {"reason", s.reason}});
    }
    return Json{{"stages", stages}};
}

}  // namespace kasumi
