#pragma once
/// The plan's lines for render.quality and for the light single scattering leaves out.
#include "scene/plan.h"
#include "scene/scene.h"

namespace kasumi {

/// "quality": the level, the values it set, those the scene kept, the expected error.
PlanStage quality_plan_stage(const SceneDesc& scene);

/// "single-scattering-bound": on when scattering media are rendered with single scattering;
/// states the bound of scene/quality.h on the light left out.
PlanStage scattering_bound_plan_stage(const SceneDesc& scene, const Plan& plan);

}  // namespace kasumi
