#include "volume/medium_json.h"

#include "phase/phase_json.h"
#include "volume/grid/vdb_io.h"
#include "volume/visibility.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace kasumi {

namespace {

HomogeneousMedium parse_homogeneous(JsonObjectReader& reader) {
    HomogeneousMedium m;
    if (auto bounds = reader.optional("bounds")) {
        if (!bounds->is_array() || bounds->size() != 2)
            bounds->fail("expected [min, max]");
        Bounds3 b{bounds->child(0).as_point(), bounds->child(1).as_point()};
        if (!(b.min.x < b.max.x && b.min.y < b.max.y && b.min.z < b.max.z)) {
            bounds->fail("min must be below max on every axis");
        }
        m.bounds = b;
    }
    auto visibility = reader.optional("visibility_m");
    auto threshold = reader.optional("contrast_threshold");
    auto albedo = reader.optional("albedo");
    if (visibility) {
        // Fog given by its visibility (volume/visibility.h): sigma_t = -ln(eps) / V, grey,
        // split by the albedo.
        if (reader.has("sigma_a") || reader.has("sigma_s"))
            visibility->fail("give either visibility_m or sigma_a and sigma_s, not both");
        const double visibility_m = visibility->as_double();
        if (!(visibility_m > 0.0))
            visibility->fail("must be > 0");
        double eps = kMorContrastThreshold;
        if (threshold) {
            eps = threshold->as_double();
            if (!(eps > 0.0 && eps < 1.0))
                threshold->fail("must be in (0, 1)");
        }
        const double sigma_t = extinction_from_visibility(visibility_m, eps);
        if (!(sigma_t <= 3.0e38))
            visibility->fail("too short: sigma_t = -ln(eps) / V is beyond single precision");
        Rgb a(1.0f);
        if (albedo) {
            a = albedo->non_negative_rgb();
            if (max_component(a) > 1.0f)
                albedo->fail("must be in [0, 1] per channel");
        }
        m.sigma_s = a * static_cast<float>(sigma_t);
        m.sigma_a = (Rgb(1.0f) - a) * static_cast<float>(sigma_t);
    } else {
        if (threshold)
            threshold->fail("goes with visibility_m");
        if (albedo)
            albedo->fail("goes with visibility_m (else give sigma_a and sigma_s)");
        if (!reader.has("sigma_a") && !reader.has("sigma_s"))
            reader.node().fail("give sigma_a and sigma_s, or visibility_m");
        m.sigma_a = reader.required("sigma_a").non_negative_rgb();
        m.sigma_s = reader.required("sigma_s").non_negative_rgb();
    }
    if (auto phase = reader.optional("phase"))
        m.phase = parse_phase(*phase);
    return m;
}

/// Height fog: the homogeneous keys (bounds, coefficients or visibility at the reference
/// height, phase) plus `scale_height_m` H > 0 (required) and `reference_height_m` h0 (default 0).
HeightFogMedium parse_height_fog(JsonObjectReader& reader) {
    const JsonNode scale = reader.required("scale_height_m");
    const HomogeneousMedium at_h0 = parse_homogeneous(reader);
    HeightFogMedium m;
    m.bounds = at_h0.bounds;
    m.sigma_a = at_h0.sigma_a;
    m.sigma_s = at_h0.sigma_s;
    m.phase = at_h0.phase;
    m.scale_height_m = scale.as_double();
    if (!(m.scale_height_m > 0.0 && std::isfinite(m.scale_height_m)))
        scale.fail("must be > 0 and finite (an infinite H is a homogeneous medium)");
    if (auto h0 = reader.optional("reference_height_m")) {
        m.reference_height_m = h0->as_double();
        if (!std::isfinite(m.reference_height_m))
            h0->fail("must be finite");
    }
    m.cap_density();
    return m;
}

/// {"translate": [x, y, z] m, "rotate": [rx, ry, rz] degrees (about world x, then y, then z),
/// "scale": s or [sx, sy, sz] > 0}, composed as translate * rotate * scale.
glm::dmat4 parse_transform(const JsonNode& node) {
    JsonObjectReader reader(node);
    glm::dmat4 m(1.0);
    if (auto v = reader.optional("translate"))
        m = glm::translate(m, glm::dvec3(v->as_point()));
    if (auto v = reader.optional("rotate")) {
        const glm::dvec3 deg(v->as_vec3());
        m = glm::rotate(m, glm::radians(deg.z), glm::dvec3(0, 0, 1));
        m = glm::rotate(m, glm::radians(deg.y), glm::dvec3(0, 1, 0));
        m = glm::rotate(m, glm::radians(deg.x), glm::dvec3(1, 0, 0));
    }
    if (auto v = reader.optional("scale")) {
        const Rgb s = v->as_rgb();
        if (!(s.x > 0.0f && s.y > 0.0f && s.z > 0.0f))
            v->fail("must be > 0 on every axis");
        m = glm::scale(m, glm::dvec3(s));
    }
    reader.finish();
    return m;
}

/// `temperature`: {"grid" (default "temperature"), "file" (default: the medium's file),
/// "scale" K per unit (default 1), "offset" K (default 0), "emission_scale" (default 1)}.
VdbTemperature parse_temperature(const JsonNode& node, const std::string& medium_file,
                                 const std::string& base_dir, const glm::dmat4& user) {
    JsonObjectReader reader(node);
    VdbTemperature t;
    t.file = medium_file;
    std::string grid_name = "temperature";
    if (auto v = reader.optional("grid"))
        grid_name = v->as_string();
    std::optional<JsonNode> file_node = reader.optional("file");
    if (file_node) {
        std::filesystem::path file = file_node->as_string();
        if (file.is_relative() && !base_dir.empty())
            file = std::filesystem::path(base_dir) / file;
        t.file = file.string();
    }
    if (auto v = reader.optional("scale"))
        t.scale = v->non_negative();
    if (auto v = reader.optional("offset"))
        t.offset = v->as_float();
    if (auto v = reader.optional("emission_scale"))
        t.emission_scale = v->non_negative();
    reader.finish();
    const JsonNode& where = file_node ? *file_node : node;
    const LoadedGrid loaded =
        load_density_grid(t.file, grid_name, where.file() + ": " + where.pointer());
    t.grid = loaded.grid;
    t.grid_name = loaded.grid_name;
    t.world_to_index = Mat4(glm::inverse(user * loaded.index_to_world));
    t.blackbody = std::make_shared<const BlackbodyTable>();
    return t;
}

VdbMedium parse_vdb(JsonObjectReader& reader, const std::string& base_dir) {
    const auto start = std::chrono::steady_clock::now();
    VdbMedium m;
    const JsonNode file_node = reader.required("file");
    std::filesystem::path file = file_node.as_string();
    if (file.is_relative() && !base_dir.empty())
        file = std::filesystem::path(base_dir) / file;
    m.file = file.string();
    std::string grid_name;
    if (auto v = reader.optional("grid"))
        grid_name = v->as_string();
    float density_scale = 1.0f;
    if (auto v = reader.optional("density_scale"))
        density_scale = v->non_negative();

    auto albedo = reader.optional("albedo");
    auto sigma_a = reader.optional("sigma_a");
    auto sigma_s = reader.optional("sigma_s");
    // Visibility form (volume/visibility.h): V is the visibility where the scaled density is 1,
    // extinction per unit density -ln(eps) / V times density_scale, split by the albedo.
    auto visibility = reader.optional("visibility_m");
    auto threshold = reader.optional("contrast_threshold");
    if (visibility && (sigma_a || sigma_s))
        visibility->fail("give either visibility_m or sigma_a and sigma_s, not both");
    if (threshold && !visibility)
        threshold->fail("goes with visibility_m");
    double extinction_per_density = 1.0;  // 1/m at density 1, before density_scale
    if (visibility) {
        const double visibility_m = visibility->as_double();
        if (!(visibility_m > 0.0))
            visibility->fail("must be > 0");
        const double eps = threshold ? threshold->as_double() : kMorContrastThreshold;
        if (!(eps > 0.0 && eps < 1.0))
            threshold->fail("must be in (0, 1)");
        extinction_per_density = extinction_from_visibility(visibility_m, eps);
        if (!(extinction_per_density * density_scale <= 3.0e38))
            visibility->fail(
                "too short: -ln(eps) / V times density_scale is beyond single precision");
    }
    if (albedo && (sigma_a || sigma_s))
        albedo->fail("give either albedo or sigma_a and sigma_s, not both");
    if (bool(sigma_a) != bool(sigma_s))
        (sigma_a ? *sigma_a : *sigma_s).fail("sigma_a and sigma_s go together");
    if (sigma_a) {
        m.sigma_a_per_density = sigma_a->non_negative_rgb() * density_scale;
        m.sigma_s_per_density = sigma_s->non_negative_rgb() * density_scale;
    } else {
        // albedo form: extinction per unit density is density_scale (1/m), or the visibility's.
        Rgb a(1.0f);
        if (albedo) {
            a = albedo->non_negative_rgb();
            if (max_component(a) > 1.0f)
                albedo->fail("must be in [0, 1] per channel");
        }
        const float extinction = static_cast<float>(extinction_per_density * density_scale);
        m.sigma_s_per_density = a * extinction;
        m.sigma_a_per_density = (Rgb(1.0f) - a) * extinction;
    }
    if (auto v = reader.optional("phase"))
        m.phase = parse_phase(*v);
    glm::dmat4 user(1.0);
    if (auto v = reader.optional("transform"))
        user = parse_transform(*v);
    if (auto v = reader.optional("temperature"))
        m.temperature = parse_temperature(*v, m.file, base_dir, user);

    const LoadedGrid loaded =
        load_density_grid(m.file, grid_name, file_node.file() + ": " + file_node.pointer());
    m.grid = loaded.grid;
    m.grid_name = loaded.grid_name;
    const glm::dmat4 index_to_world = user * loaded.index_to_world;
    m.world_to_index = Mat4(glm::inverse(index_to_world));
    m.voxel_size_m = static_cast<float>(std::min({glm::length(glm::dvec3(index_to_world[0])),
                                                  glm::length(glm::dvec3(index_to_world[1])),
                                                  glm::length(glm::dvec3(index_to_world[2]))}));
    if (!m.grid->empty()) {
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? m.grid->upper().x : m.grid->lower().x,
                               (corner & 2) ? m.grid->upper().y : m.grid->lower().y,
                               (corner & 4) ? m.grid->upper().z : m.grid->lower().z);
            m.bounds_world.extend(Vec3(glm::dvec3(index_to_world * glm::dvec4(p, 1.0))));
        }
    }
    m.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return m;
}

}  // namespace

Medium parse_medium(const JsonNode& node, size_t index, const std::string& base_dir) {
    JsonObjectReader reader(node);
    Medium medium;
    medium.name = "medium" + std::to_string(index);
    if (auto name = reader.optional("name"))
        medium.name = name->as_string();
    const JsonNode type_node = reader.required("type");
    const std::string type = type_node.as_string();
    if (type == "homogeneous") {
        medium.model = parse_homogeneous(reader);
    } else if (type == "vdb") {
        medium.model = parse_vdb(reader, base_dir);
    } else if (type == "height_fog") {
        medium.model = parse_height_fog(reader);
    } else {
        type_node.fail("unknown medium type (expected homogeneous, height_fog or vdb)");
    }
    reader.finish();
    return medium;
}

}  // namespace kasumi
