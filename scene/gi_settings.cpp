#include "scene/gi_settings.h"

#include "core/json_choice.h"
#include "core/json_int.h"

#include <filesystem>

namespace kasumi {

const char* gi_mode_name(GiMode mode) {
    switch (mode) {
        case GiMode::None:
            return "none";
        case GiMode::Radiosity:
            return "radiosity";
        case GiMode::Photons:
            return "photons";
        case GiMode::Path:
            return "path";
    }
    return "none";
}

GiMode parse_gi_mode(const JsonNode& node) {
    const std::string name = node.as_string();
    for (const GiMode mode : {GiMode::None, GiMode::Radiosity, GiMode::Photons, GiMode::Path}) {
        if (name == gi_mode_name(mode))
            return mode;
    }
    node.fail("expected \"none\", \"radiosity\", \"photons\" or \"path\"");
}

PathSettings parse_path_settings(const JsonNode& node) {
    JsonObjectReader reader(node);
    PathSettings path;
    if (auto v = reader.optional("max_depth"))
        path.max_depth = parse_int_in(*v, 0, 1024);
    if (auto v = reader.optional("rr_depth"))
        path.rr_depth = parse_int_in(*v, 1, 1024);
    reader.finish();
    return path;
}

RadiositySettings parse_radiosity_settings(const JsonNode& node) {
    JsonObjectReader reader(node);
    RadiositySettings r;
    if (auto v = reader.optional("patch_size_m"))
        r.patch_size_m = v->positive();
    if (auto v = reader.optional("max_subdivision"))
        r.max_subdivision = parse_int_in(*v, 0, 8);
    if (auto v = reader.optional("refine_threshold"))
        r.refine_threshold = v->positive();
    if (auto v = reader.optional("solver"))
        r.solver =
            parse_choice<RadiositySolver>(*v, {{"shooting", RadiositySolver::Shooting},
                                               {"gauss-seidel", RadiositySolver::GaussSeidel}});
    if (auto v = reader.optional("tolerance"))
        r.tolerance = v->in_open(0.0f, 1.0f);
    if (auto v = reader.optional("max_iterations"))
        r.max_iterations = parse_int_in(*v, 1, 100000000);
    if (auto v = reader.optional("form_factor_samples"))
        r.form_factor_samples = parse_int_in(*v, 1, 256);
    if (auto v = reader.optional("cache")) {
        std::filesystem::path path(v->as_string());
        if (path.empty())
            v->fail("must be a file name");
        if (path.is_relative())
            path = std::filesystem::path(v->file()).parent_path() / path;
        r.cache = path.lexically_normal().string();
    }
    reader.finish();
    return r;
}

}  // namespace kasumi
