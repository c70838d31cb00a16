#pragma once
/// The plan's global-illumination stage: whether render.gi is on and which surfaces and media
/// take part; after the precomputation the method's summary (residual, time) is appended.
#include <string>
#include "scene/plan.h"

namespace kasumi {

/// The "global-illumination" stage for `scene` (enabled unless render.gi is "none").
PlanStage gi_plan_stage(const SceneDesc& scene);

/// Appends `summary` (GiMethod::summary(): what the precomputation did) to the plan's
/// global-illumination stage.
void add_gi_summary(Plan& plan, const std::string& summary);

}  // namespace kasumi
