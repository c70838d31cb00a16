#include "lights/light_json.h"

#include "core/error.h"
#include "core/json_int.h"

#include <filesystem>

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

/// Exactly one of two keys giving the same amount in different units; returns the amount in
/// the first key's unit (a value of `second` is multiplied by `factor`).
float one_of(JsonObjectReader& reader, const char* first, const char* second, float factor,
             const char* light_kind) {
    const auto a = reader.optional(first);
    const auto b = reader.optional(second);
    if (a && b)
        b->fail(std::string("give either ") + first + " or " + second + ", not both");
    if (a)
        return a->non_negative();
    if (b)
        return b->non_negative() * factor;
    reader.node().fail(std::string(light_kind) + " needs " + first + " or " + second);
}

float read_angle_deg(const JsonNode& node, float lo, float hi) {
    const float deg = node.as_float();
    if (!(deg > lo && deg <= hi)) {
        node.fail("must be in (" + std::to_string(static_cast<int>(lo)) + ", " +
                  std::to_string(static_cast<int>(hi)) + "] degrees");
    }
    return deg;
}

SpotLight parse_spot(JsonObjectReader& reader, const Rgb& color) {
    SpotLight l;
    l.position = reader.required("position").as_point();
    l.direction = reader.required("direction").unit_direction();
    const float cone_deg = read_angle_deg(reader.required("cone_deg"), 0.0f, 180.0f);
    float falloff_deg = cone_deg;
    if (const auto f = reader.optional("falloff_deg")) {
        falloff_deg = f->as_float();
        if (!(falloff_deg >= 0.0f && falloff_deg <= cone_deg))
            f->fail("must be in [0, cone_deg] degrees");
    }
    l.cos_cone = std::cos(radians(cone_deg));
    l.cos_falloff = std::cos(radians(falloff_deg));
    l.intensity = color * one_of(reader, "intensity_cd", "flux_lm", 1.0f / spot_flux_per_cd(l),
                                 "a spot light");
    return l;
}

GoniometricLight parse_goniometric(JsonObjectReader& reader, const Rgb& color) {
    GoniometricLight l;
    l.position = reader.required("position").as_point();
    const JsonNode ies = reader.required("ies");
    std::filesystem::path path(ies.as_string());
    if (path.is_relative())
        path = std::filesystem::path(ies.file()).parent_path() / path;
    try {
        l.profile = std::make_shared<const IesProfile>(read_ies(path.lexically_normal().string()));
    } catch (const Error& e) {
        ies.fail(e.what());
    }
    Vec3 rotation_deg(0.0f);
    if (const auto r = reader.optional("rotation_deg")) {
        if (!r->is_number() && !r->is_array())
            r->fail("expected a number (degrees about +y) or [rx, ry, rz]");
        rotation_deg = r->is_number() ? Vec3(0.0f, r->as_float(), 0.0f) : r->as_vec3();
    }
    l.local_to_world = luminaire_frame(rotation_deg);
    l.scale = color;
    if (const auto flux = reader.optional("flux_lm")) {
        const double table_flux = ies_flux_lm(*l.profile);
        if (!(table_flux > 0.0))
            flux->fail("cannot rescale: the IES distribution emits no flux");
        l.scale *= static_cast<float>(flux->non_negative() / table_flux);
    }
    // The file's tilt multiplier (LM-63 TILT=INCLUDE or a tilt file) for this orientation: the
    // tilt is the angle between the luminaire's up axis and the world's +y (docs/lights.md).
    l.scale *= ies_tilt_multiplier(*l.profile, degrees(safe_acos(l.local_to_world[2].y)));
    return l;
}

LineLight parse_line(const JsonNode& node, JsonObjectReader& reader, const Rgb& color) {
    LineLight l;
    l.from = reader.required("from").as_point();
    l.to = reader.required("to").as_point();
    const float length = glm::length(l.to - l.from);
    if (!(length > 0.0f))
        node.fail("a line light needs from != to");
    // Φ = π² I_l L for a Lambertian-in-angle line (docs/lights.md).
    l.intensity_per_m = color * one_of(reader, "intensity_cd_per_m", "flux_lm",
                                       1.0f / (kPi * kPi * length), "a line light");
    return l;
}

PolygonLight parse_polygon(JsonObjectReader& reader, const Rgb& color) {
    const JsonNode vertices_node = reader.required("vertices");
    std::vector<Vec3> vertices;
    for (const JsonNode& v : vertices_node.elements())
        vertices.push_back(v.as_point());
    const std::string problem = polygon_problem(vertices);
    if (!problem.empty())
        vertices_node.fail(problem);
    const float l = reader.required("luminance_cd_m2").non_negative();
    bool two_sided = false;
    if (const auto t = reader.optional("two_sided"))
        two_sided = t->as_bool();
    return make_polygon_light(std::move(vertices), color * l, two_sided);
}

SphereLight parse_sphere(JsonObjectReader& reader, const Rgb& color) {
    SphereLight l;
    l.center = reader.required("center").as_point();
    l.radius = reader.required("radius").positive_length();
    l.luminance = color * reader.required("luminance_cd_m2").non_negative();
    return l;
}

void parse_shadow_map_settings(const JsonNode& node, Light& light) {
    JsonObjectReader reader(node);
    ShadowMapSettings& m = light.shadow_map;
    if (const auto r = reader.optional("resolution"))
        m.resolution = parse_int_in(*r, 16, 8192);
    if (const auto b = reader.optional("bias"))
        m.bias = b->non_negative();
    if (const auto b = reader.optional("slope_bias"))
        m.slope_bias = b->non_negative();
    if (const auto r = reader.optional("pcf_radius"))
        m.pcf_radius = parse_int_in(*r, 0, 8);
    if (const auto v = reader.optional("views")) {
        if (is_delta(light))
            v->fail("views applies to line, polygon and sphere lights; a " +
                    light_type_name(light) + " light has one centre of projection");
        m.views = parse_int_in(*v, 1, 64);
    }
    // Every view of a point-like or area light may be a cube of six faces; cap the memory.
    const int64_t res = shadow_map_resolution(light);
    const int64_t texels = (is_delta(light) ? 1 : m.views) * 6 * res * res;
    if (texels > (int64_t(1) << 28))
        node.fail("the maps would hold " + std::to_string(texels) +
                  " depth texels (views x 6 faces x resolution^2); the limit is 2^28 (1 GiB)");
    reader.finish();
}

void parse_shadow_settings(JsonObjectReader& reader, Light& light) {
    if (const auto s = reader.optional("shadows")) {
        const std::string mode = s->as_string();
        if (mode == "ray") {
            light.shadows = ShadowMode::Ray;
        } else if (mode == "none") {
            light.shadows = ShadowMode::None;
        } else if (mode == "map") {
            light.shadows = ShadowMode::Map;
        } else if (mode == "shadow-volume" || mode == "object-space" || mode == "scanline") {
            // Polygons projected from one centre: a point (Crow 1977; Atherton, Weiler &
            // Greenberg 1978; Bouknight & Kelley 1970) or the point at infinity of a parallel
            // light.
            if (!is_delta(light))
                s->fail("\"" + mode +
                        "\" shadows need a point, spot, goniometric or directional light (a " +
                        light_type_name(light) + " light has no single centre of projection)");
            light.shadows = mode == "shadow-volume"  ? ShadowMode::ShadowVolume
                            : mode == "object-space" ? ShadowMode::ObjectSpace
                                                     : ShadowMode::Scanline;
        } else {
            s->fail(
                "unknown shadow mode (expected \"ray\", \"none\", \"map\", "
                "\"shadow-volume\", \"object-space\" or \"scanline\")");
        }
    }
    if (const auto m = reader.optional("shadow_map")) {
        if (light.shadows != ShadowMode::Map)
            m->fail("shadow_map applies to lights with \"shadows\": \"map\"");
        parse_shadow_map_settings(*m, light);
    }
    if (const auto n = reader.optional("samples")) {
        if (is_delta(light))
            n->fail("samples applies to line, polygon and sphere lights; a " +
                    light_type_name(light) + " light takes one shadow ray");
        const int64_t samples = n->as_int();
        if (samples < 1 || samples > 4096)
            n->fail("must be an integer in [1, 4096]");
        light.samples = static_cast<int>(samples);
    }
    if (const auto n = reader.optional("shadow_probes")) {
        if (is_delta(light))
            n->fail("shadow_probes applies to line, polygon and sphere lights; a " +
                    light_type_name(light) + " light takes one shadow ray");
        const int64_t probes = n->as_int();
        if (probes < 0 || probes > light.samples)
            n->fail("must be an integer in [0, samples = " + std::to_string(light.samples) + "]");
        light.shadow_probes = static_cast<int>(probes);
    }
    if (const auto n = reader.optional("outline_probes")) {
        if (!std::holds_alternative<SphereLight>(light.emitter))
            n->fail("outline_probes applies to sphere lights; this is a " + light_type_name(light) +
                    " light");
        const int64_t probes = n->as_int();
        if (probes != 0 && (probes < 4 || probes > 64))
            n->fail("must be 0 (off) or an integer in [4, 64]");
        light.outline_probes = static_cast<int>(probes);
    }
    if (const auto e = reader.optional("exact_penumbra")) {
        if (!std::holds_alternative<SphereLight>(light.emitter) &&
            !std::holds_alternative<PolygonLight>(light.emitter))
            e->fail("exact_penumbra applies to sphere and polygon lights; this is a " +
                    light_type_name(light) + " light");
        if (light.shadows != ShadowMode::Ray)
            e->fail("exact_penumbra applies to ray-traced shadows (\"shadows\": \"ray\")");
        light.exact_penumbra = e->as_bool();
    }
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
        l.position = reader.required("position").as_point();
        // An isotropic source spreads its flux over 4π sr: I = Φ / (4π).
        l.intensity =
            color * one_of(reader, "intensity_cd", "flux_lm", 1.0f / (4.0f * kPi), "a point light");
        light.emitter = l;
    } else if (type == "spot") {
        light.emitter = parse_spot(reader, color);
    } else if (type == "goniometric") {
        light.emitter = parse_goniometric(reader, color);
    } else if (type == "line") {
        light.emitter = parse_line(node, reader, color);
    } else if (type == "polygon") {
        light.emitter = parse_polygon(reader, color);
    } else if (type == "sphere") {
        light.emitter = parse_sphere(reader, color);
    } else {
        type_node.fail(
            "unknown light type (expected directional, point, spot, goniometric, line, polygon "
            "or sphere)");
    }
    parse_shadow_settings(reader, light);
    reader.finish();
    return light;
}

}  // namespace kasumi
