#include "phase/phase_json.h"

namespace kasumi {

PhaseFunction parse_phase(const JsonNode& node) {
    JsonObjectReader reader(node);
    const std::string model = reader.required("model").as_string();
    PhaseFunction result;
    if (model == "isotropic") {
        result = Isotropic{};
    } else if (model == "hg") {
        result = HenyeyGreenstein{reader.required("g").in_open(-1.0f, 1.0f)};
    } else {
        reader.required("model").fail("unknown phase model (expected isotropic or hg)");
    }
    reader.finish();
    return result;
}

std::string phase_model_name(const PhaseFunction& p) {
    struct Name {
        std::string operator()(const Isotropic&) const { return "isotropic"; }
        std::string operator()(const HenyeyGreenstein&) const { return "hg"; }
    };
    return std::visit(Name{}, p);
}

}  // namespace kasumi
