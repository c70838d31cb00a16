#pragma once
/// `kasumi make-cloud`: writes the project's procedural cumulus as an OpenVDB fog volume.
#include <CLI/CLI.hpp>

namespace kasumi {

void add_make_cloud_command(CLI::App& root);

}  // namespace kasumi
