#pragma once
/// Which stages a scene calls for, and why; the stages not run say why not. The renderer builds
/// and runs exactly the stages that are on.
#include "core/json_node.h"
#include "scene/scene.h"

#include <string>
#include <vector>

namespace kasumi {

struct PlanStage {
    std::string name;
    bool enabled = false;
    std::string reason;
};

struct Plan {
    std::vector<PlanStage> stages;
    bool surfaces = false;       ///< build the BVH, trace camera rays against shapes
    bool direct_light = false;   ///< shade surfaces by the lights
    bool shadow_rays = false;    ///< test visibility of lights (surfaces and media)
    bool ambient = false;        ///< Phong ambient term
    bool volume = false;         ///< media: transmittance along camera rays
    bool in_scattering = false;  ///< media: single-scattered light

    bool shadow_maps = false;     ///< depth maps from lights with "shadows": "map"
    bool shadow_volumes = false;  ///< shadow volumes for lights with "shadows": "shadow-volume"
    bool object_space_shadows = false;  ///< detail polygons for "shadows": "object-space"
    bool scanline_shadows = false;      ///< scanline passes for "shadows": "scanline"
    bool scanline_surface = false;      ///< render.surface "scanline": visible surfaces by scanline
    bool visible_lights = false;        ///< camera and Whitted rays see polygon and sphere lights
};

Plan make_plan(const SceneDesc& scene);

std::string plan_to_text(const Plan& plan);
Json plan_to_json(const Plan& plan);

}  // namespace kasumi
