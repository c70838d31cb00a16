#include "apps/illuminance_command.h"

#include "apps/scene_options.h"
#include "core/error.h"
#include "gi/gi.h"
#include "render/illuminance.h"
#include "render/probe_json.h"

#include <iostream>
#include <memory>

namespace kasumi {

namespace {

Vec3 to_vec3(const std::vector<float>& v, const std::string& option) {
    const Vec3 p(v.at(0), v.at(1), v.at(2));
    if (!is_finite(p))
        throw Error(ErrorKind::Usage, option + " expects finite X,Y,Z");
    return p;
}

}  // namespace

void add_illuminance_command(CLI::App& probe) {
    struct Options {
        SceneOptions scene;
        std::vector<float> at, normal;
        bool no_shadows = false;
        int samples = 4096;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = probe.add_subcommand(
        "illuminance", "illuminance (lux) on a surface at a point, per light (media left out)");
    options->scene.add_to(*cmd);
    cmd->add_option("--at", options->at, "the point X,Y,Z (metres)")
        ->required()
        ->delimiter(',')
        ->expected(3);
    cmd->add_option("--normal", options->normal, "the surface normal X,Y,Z")
        ->required()
        ->delimiter(',')
        ->expected(3);
    cmd->add_flag("--no-shadows", options->no_shadows,
                  "unoccluded: every light's closed form, no shadow rays");
    cmd->add_option("--samples", options->samples,
                    "shadow samples per extended light (default 4096)")
        ->check(CLI::Range(1, 1 << 24));
    cmd->callback([options] {
        const Vec3 at = to_vec3(options->at, "--at");
        const Vec3 normal = to_vec3(options->normal, "--normal");
        if (!(glm::length(normal) > 0.0f))
            throw Error(ErrorKind::Usage, "--normal must be a non-zero vector");
        const SceneRuntime runtime(options->scene.load(), make_gi_method);
        const IlluminanceProbe p = probe_illuminance(runtime, at, glm::normalize(normal),
                                                     !options->no_shadows, options->samples);
        std::cout << probe_json(p).dump(2) << std::endl;
    });
}

}  // namespace kasumi
