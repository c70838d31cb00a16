#include "lights/light_json.h"

namespace kasumi {

namespace {

/// A colour normalised to luminance 1, so it scales a photometric amount without changing it.
Rgb read_color(JsonObjectReader& reader) {
    const auto node = reader.optional("color");
    if (!node)
        return Rgb(1.0f);
    const Rgb c = node->non_negative_rgb();
    const float y = luminance(c);
    if (!(y > 0.0f))
        node->fail("must have non-zero luminance");
    return c / y;
}

}  // namespace

Light parse_light(const JsonNode& node, size_t index) {
    JsonObjectReader reader(node);
    Light light;
    light.name = "light" + std::to_string(index);
    if (auto name = reader.optional("name"))
        light.name = name->as_string();
    const JsonNode type_node = reader.required("type");
    const std::string type = type_node.as_string();
    const Rgb color = read_color(reader);
    if (type == "directional") {
        DirectionalLight l;
        l.direction = reader.required("direction").unit_direction();
        l.illuminance = color * reader.required("illuminance_lux").non_negative();
        light.emitter = l;
    } else if (type == "point") {
        PointLight l;
        l.position = reader.required("position").as_vec3();
        const auto intensity = reader.optional("intensity_cd");
        const auto flux = reader.optional("flux_lm");
        if (intensity && flux)
            flux->fail("give either intensity_cd or flux_lm, not both");
        if (intensity) {
            l.intensity = color * intensity->non_negative();
        } else if (flux) {
            // An isotropic source spreads its flux over 4π sr: I = Φ / (4π).
            l.intensity = color * (flux->non_negative() / (4.0f * kPi));
        } else {
            node.fail("a point light needs intensity_cd or flux_lm");
        }
        light.emitter = l;
    } else {
        type_node.fail("unknown light type (expected directional or point)");
    }
    reader.finish();
    return light;
}

}  // namespace kasumi
