#pragma once
/// `kasumi probe illuminance SCENE --at X,Y,Z --normal X,Y,Z [--no-shadows] [--samples N]`:
/// lux on a surface at a point, per light, as one JSON object on stdout.
#include <CLI/CLI.hpp>

namespace kasumi {

/// Registers `illuminance` under the `probe` subcommand.
void add_illuminance_command(CLI::App& probe);

}  // namespace kasumi
