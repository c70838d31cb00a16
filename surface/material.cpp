#include "surface/material.h"

#include <string>

namespace kasumi {

namespace {

/// A reflectance: scalar or [r, g, b], each channel in [0, 1] (a physical surface reflects at
/// most what arrives; larger values are rejected rather than clamped).
Rgb reflectance(const JsonNode& node) {
    const Rgb c = node.as_rgb();
    for (int i = 0; i < 3; ++i) {
        if (!(c[i] >= 0.0f && c[i] <= 1.0f))
            node.fail("must be in [0, 1] in every channel");
    }
    return c;
}

PhongMaterial parse_phong(JsonObjectReader& reader) {
    PhongMaterial m;
    if (const auto ka = reader.optional("ka"))
        m.ka = reflectance(*ka);
    if (const auto kd = reader.optional("kd"))
        m.kd = reflectance(*kd);
    if (const auto ks = reader.optional("ks"))
        m.ks = reflectance(*ks);
    if (const auto n = reader.optional("n"))
        m.n = n->non_negative();
    return m;
}

}  // namespace

Material parse_material(const JsonNode& node) {
    JsonObjectReader reader(node);
    const JsonNode type = reader.required("type");
    const std::string name = type.as_string();
    Material material;
    if (name == "phong") {
        material = parse_phong(reader);
    } else {
        type.fail("unknown material type (known types: phong)");
    }
    reader.finish();
    return material;
}

Rgb albedo(const Material& m) {
    return std::visit([](const PhongMaterial& phong) { return phong.kd; }, m);
}

}  // namespace kasumi
