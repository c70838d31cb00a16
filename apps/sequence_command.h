#pragma once
/// `kasumi sequence`: renders the frames of an animated scene (sequence/sequence.h).
#include <CLI/CLI.hpp>

namespace kasumi {

void add_sequence_command(CLI::App& root);

}  // namespace kasumi
