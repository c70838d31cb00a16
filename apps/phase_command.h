#pragma once
/// `kasumi phase eval|mie|validate|plot`: inspect and validate phase functions from the command
/// line. Model parameters use the scene-file names with `-` for `_` (`--g`, `--diameter-um`).
#include <CLI/CLI.hpp>

namespace kasumi {

void add_phase_command(CLI::App& root);

}  // namespace kasumi
