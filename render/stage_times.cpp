#include "render/stage_times.h"

#include <algorithm>
#include <cstdio>
#include <variant>

namespace kasumi {

namespace {

/// The timed stages in order, each followed by its parts.
std::vector<std::pair<std::string, double>> timed(const StageTimes& t) {
    std::vector<std::pair<std::string, double>> out;
    for (const auto& [stage, seconds] :
         {std::make_pair("load", t.load_s), std::make_pair("build", t.build_s),
          std::make_pair("render", t.render_s), std::make_pair("write", t.write_s)}) {
        if (seconds < 0.0)
            continue;
        out.emplace_back(stage, seconds);
        const std::string prefix = std::string(stage) + "/";
        for (const auto& part : t.parts) {
            if (part.first.rfind(prefix, 0) == 0 && part.second >= 0.0)
                out.push_back(part);
        }
    }
    return out;
}

std::string stage_names(const Plan& plan, bool enabled) {
    std::string text;
    for (const PlanStage& s : plan.stages) {
        if (s.enabled == enabled)
            text += (text.empty() ? "" : ",") + s.name;
    }
    return text;
}

}  // namespace

std::string format_stage_times(const StageTimes& times) {
    std::string out;
    char line[96];
    for (const auto& [name, seconds] : timed(times)) {
        const bool part = name.find('/') != std::string::npos;
        std::snprintf(line, sizeof line, "  %-28s %.4f s\n",
                      ((part ? "  time " : "time ") + name).c_str(), seconds);
        out += line;
    }
    return out;
}

std::vector<std::pair<std::string, std::string>> stage_metadata(const StageTimes& times,
                                                                const Plan& plan) {
    std::vector<std::pair<std::string, std::string>> out;
    char value[32];
    for (const auto& [name, seconds] : timed(times)) {
        std::snprintf(value, sizeof value, "%.6f", seconds);
        out.emplace_back("time/" + name + "_s", value);
    }
    out.emplace_back("plan/ran", stage_names(plan, true));
    out.emplace_back("plan/skipped", stage_names(plan, false));
    return out;
}

void add_stage_parts(StageTimes& times, const SceneRuntime& runtime) {
    double grids_s = -1.0;
    for (const Medium& m : runtime.desc().media) {
        if (const auto* vdb = std::get_if<VdbMedium>(&m.model))
            grids_s = std::max(grids_s, 0.0) + vdb->load_s;
    }
    const BuildTimes& b = runtime.build_times();
    for (const auto& [name, seconds] :
         {std::make_pair("load/grids", grids_s), std::make_pair("build/bvh", b.bvh_s),
          std::make_pair("build/shadow-maps", b.shadow_maps_s),
          std::make_pair("build/shadow-volumes", b.shadow_volumes_s),
          std::make_pair("build/object-space", b.object_space_s),
          std::make_pair("build/scanline", b.scanline_s), std::make_pair("build/media", b.media_s),
          std::make_pair("build/sky", b.sky_s), std::make_pair("build/gi", b.gi_s)}) {
        if (seconds >= 0.0)
            times.parts.emplace_back(name, seconds);
    }
}

std::string skipped_stage_names(const Plan& plan) {
    return stage_names(plan, false);
}

}  // namespace kasumi
