#include "render/stage_times.h"

#include <cstdio>

namespace kasumi {

namespace {

std::vector<std::pair<const char*, double>> timed(const StageTimes& t) {
    std::vector<std::pair<const char*, double>> out;
    for (const auto& s :
         {std::make_pair("load", t.load_s), std::make_pair("build", t.build_s),
          std::make_pair("render", t.render_s), std::make_pair("write", t.write_s)}) {
        if (s.second >= 0.0)
            out.push_back(s);
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
        std::snprintf(line, sizeof line, "  %-19s %.4f s\n", (std::string("time ") + name).c_str(),
                      seconds);
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
        out.emplace_back(std::string("time/") + name + "_s", value);
    }
    out.emplace_back("plan/ran", stage_names(plan, true));
    out.emplace_back("plan/skipped", stage_names(plan, false));
    return out;
}

std::string skipped_stage_names(const Plan& plan) {
    return stage_names(plan, false);
}

}  // namespace kasumi
