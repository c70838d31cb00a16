#include "surface/material.h"

#include "surface/fresnel.h"

#include <cmath>
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

SpecularFresnel parse_specular_fresnel(const JsonNode& node) {
    const std::string mode = node.as_string();
    if (mode == "none")
        return SpecularFresnel::None;
    if (mode == "schlick")
        return SpecularFresnel::Schlick;
    if (mode == "exact")
        return SpecularFresnel::Exact;
    node.fail("must be \"none\", \"schlick\" or \"exact\"");
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
    if (const auto fresnel = reader.optional("ks_fresnel"))
        m.ks_fresnel = parse_specular_fresnel(*fresnel);
    return m;
}

MirrorMaterial parse_mirror(JsonObjectReader& reader) {
    MirrorMaterial m;
    if (const auto kr = reader.optional("kr"))
        m.kr = reflectance(*kr);
    return m;
}

DielectricMaterial parse_dielectric(JsonObjectReader& reader) {
    DielectricMaterial m;
    const JsonNode ior = reader.required("ior");
    m.ior = ior.positive();
    if (const auto tint = reader.optional("tint"))
        m.tint = reflectance(*tint);
    return m;
}

/// η with F(1, η) = ((η - 1) / (η + 1))² = f0, taking η >= 1: η = (1 + √f0) / (1 - √f0).
float ior_from_normal_reflectance(float f0) {
    const float r = std::sqrt(f0);
    return (1.0f + r) / (1.0f - r);
}

}  // namespace

Material parse_material(const JsonNode& node) {
    JsonObjectReader reader(node);
    const JsonNode type = reader.required("type");
    const std::string name = type.as_string();
    Material material;
    if (name == "phong") {
        material = parse_phong(reader);
    } else if (name == "mirror") {
        material = parse_mirror(reader);
    } else if (name == "dielectric") {
        material = parse_dielectric(reader);
    } else {
        type.fail("unknown material type (known types: dielectric, mirror, phong)");
    }
    if (const auto e = reader.optional("emission_cd_m2")) {
        const Rgb emitted = e->non_negative_rgb();
        std::visit([&](auto& m) { m.emission = emitted; }, material);
    }
    reader.finish();
    return material;
}

Rgb albedo(const Material& m) {
    struct Visitor {
        Rgb operator()(const PhongMaterial& phong) const { return phong.kd; }
        Rgb operator()(const MirrorMaterial& mirror) const { return mirror.kr; }
        Rgb operator()(const DielectricMaterial& dielectric) const { return dielectric.tint; }
    };
    return std::visit(Visitor{}, m);
}

Rgb emission(const Material& m) {
    return std::visit([](const auto& material) { return material.emission; }, m);
}

bool is_specular(const Material& m) {
    return !std::holds_alternative<PhongMaterial>(m);
}

Rgb specular_reflectance(const PhongMaterial& m, float cos_theta_i) {
    switch (m.ks_fresnel) {
        case SpecularFresnel::None:
            return m.ks;
        case SpecularFresnel::Schlick:
            return Rgb(fresnel_schlick(cos_theta_i, m.ks.r), fresnel_schlick(cos_theta_i, m.ks.g),
                       fresnel_schlick(cos_theta_i, m.ks.b));
        case SpecularFresnel::Exact:
            break;
    }
    Rgb w;
    for (int c = 0; c < 3; ++c) {
        // ks = 1 is a perfect reflector at every angle (η → ∞).
        w[c] = m.ks[c] >= 1.0f
                   ? 1.0f
                   : fresnel_dielectric(cos_theta_i, ior_from_normal_reflectance(m.ks[c]));
    }
    return w;
}

}  // namespace kasumi
