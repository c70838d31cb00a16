#pragma once
/// Options every scene-reading subcommand shares: the scene path, --set overrides, verbosity.
#include "scene/scene_loader.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace kasumi {

struct SceneOptions {
    std::string scene_path;
    std::vector<std::string> sets;
    bool quiet = false;
    bool verbose = false;

    /// Registers SCENE, --set, -q and -v on `command`.
    void add_to(CLI::App& command);
    /// The --set overrides, parsed (a usage error for a malformed one).
    std::vector<Override> overrides() const;
    /// The scene file with the overrides applied (scene/scene_loader.h), as every command reads it.
    SceneSource source() const;
    /// The scene of `frame` with the overrides applied (an animated scene's frame 0 by default).
    SceneDesc load(int64_t frame = 0) const;
};

/// Parses a command-line vector "X,Y,Z"; throws ErrorKind::Usage naming `option` otherwise.
Vec3 parse_vec3_arg(const std::string& text, const std::string& option);

/// Film size in pixels.
struct Resolution {
    int width = 0, height = 0;
};
/// Parses `--res WxH` (whole numbers >= 1); throws ErrorKind::Usage otherwise.
Resolution parse_resolution_arg(const std::string& text);

/// Throws ErrorKind::Usage with `message` when output paths `a` and `b` name the same file
/// (compared absolute, with what exists of them resolved): one write would replace the other.
void check_distinct_outputs(const std::string& a, const std::string& b, const std::string& message);

}  // namespace kasumi
