#include "volume/medium_json.h"

#include "phase/phase_json.h"

namespace kasumi {

Medium parse_medium(const JsonNode& node, size_t index) {
    JsonObjectReader reader(node);
    Medium medium;
    medium.name = "medium" + std::to_string(index);
    if (auto name = reader.optional("name"))
        medium.name = name->as_string();
    const JsonNode type_node = reader.required("type");
    const std::string type = type_node.as_string();
    if (type != "homogeneous")
        type_node.fail("unknown medium type (expected homogeneous)");

    HomogeneousMedium m;
    if (auto bounds = reader.optional("bounds")) {
        if (!bounds->is_array() || bounds->size() != 2)
            bounds->fail("expected [min, max]");
        Bounds3 b{bounds->child(0).as_vec3(), bounds->child(1).as_vec3()};
        if (!(b.min.x < b.max.x && b.min.y < b.max.y && b.min.z < b.max.z)) {
            bounds->fail("min must be below max on every axis");
        }
        m.bounds = b;
    }
    m.sigma_a = reader.required("sigma_a").non_negative_rgb();
    m.sigma_s = reader.required("sigma_s").non_negative_rgb();
    if (auto phase = reader.optional("phase"))
        m.phase = parse_phase(*phase);
    reader.finish();
    medium.model = m;
    return medium;
}

}  // namespace kasumi
