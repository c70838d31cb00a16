#include "scene/quality_plan.h"

namespace kasumi {

namespace {

std::string join(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& s : items)
        text += (text.empty() ? "" : ", ") + s;
    return text;
}

}  // namespace

PlanStage quality_plan_stage(const SceneDesc& scene) {
    const QualityChoice& q = scene.render.quality;
    if (!q.level)
        return {"quality", false, "render.quality not set: the scene's settings and the defaults"};
    std::string reason = std::string(quality_name(*q.level)) + ": ";
    reason += q.applied.empty() ? "set nothing" : "set " + join(q.applied);
    if (!q.kept.empty())
        reason += "; the scene's own " + join(q.kept) + " kept";
    if (!q.integrator.empty())
        reason += "; " + q.integrator;
    reason += "; " + q.expected_error;
    return {"quality", true, reason};
}

PlanStage scattering_bound_plan_stage(const SceneDesc& scene, const Plan& plan) {
    const bool single = scene.render.volume.integrator == VolumeIntegrator::Single;
    if (!plan.in_scattering)
        return {"single-scattering-bound", false, "no in-scattering"};
    if (!single)
        return {"single-scattering-bound", false, "multiple scattering: no order left out"};
    return {"single-scattering-bound", true, scattering_bound_text(scattering_bound(scene.media))};
}

}  // namespace kasumi
