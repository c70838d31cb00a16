#include "apps/scene_options.h"

#include "core/error.h"

#include <filesystem>
#include <sstream>

namespace kasumi {

void SceneOptions::add_to(CLI::App& command) {
    command.add_option("scene", scene_path, "scene file (JSON, comments allowed)")->required();
    command.add_option("--set", sets, "override a scene value: /json/pointer=VALUE (repeatable)");
    auto* q = command.add_flag("-q,--quiet", quiet, "no progress or logs");
    command.add_flag("-v,--verbose", verbose, "print the plan and render statistics")->excludes(q);
}

std::vector<Override> SceneOptions::overrides() const {
    std::vector<Override> out;
    out.reserve(sets.size());
    for (const std::string& s : sets)
        out.push_back(parse_override(s));
    return out;
}

SceneSource SceneOptions::source() const {
    return SceneSource(scene_path, overrides());
}

SceneDesc SceneOptions::load(int64_t frame) const {
    return source().scene(frame);
}

Vec3 parse_vec3_arg(const std::string& text, const std::string& option) {
    std::istringstream in(text);
    Vec3 v;
    char c1 = 0, c2 = 0;
    if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof() ||
        !is_finite(v)) {
        throw Error(ErrorKind::Usage, option + " expects X,Y,Z, got \"" + text + "\"");
    }
    return v;
}

Resolution parse_resolution_arg(const std::string& text) {
    Resolution r;
    char x = 0;
    std::istringstream in(text);
    if (!(in >> r.width >> x >> r.height) || x != 'x' || !in.eof() || r.width < 1 || r.height < 1) {
        throw Error(
            ErrorKind::Usage,
            "--res expects WxH, two whole numbers >= 1 (e.g. 640x360), got \"" + text + "\"");
    }
    return r;
}

void check_distinct_outputs(const std::string& a, const std::string& b,
                            const std::string& message) {
    const auto normal = [](const std::string& p) {
        // Absolute first: weakly_canonical leaves a relative path relative when none of it
        // exists yet.
        const std::filesystem::path absolute = std::filesystem::absolute(p);
        std::error_code ec;
        const std::filesystem::path resolved = std::filesystem::weakly_canonical(absolute, ec);
        return (ec ? absolute : resolved).lexically_normal();
    };
    if (normal(a) == normal(b))
        throw Error(ErrorKind::Usage, message);
}

}  // namespace kasumi
