#pragma once
/// `kasumi study`: accuracy against time over combinations of scene settings (study/study.h).
#include <CLI/CLI.hpp>

namespace kasumi {

void add_study_command(CLI::App& root);

}  // namespace kasumi
