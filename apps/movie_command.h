#pragma once
#include <CLI/CLI.hpp>

namespace kasumi {

/// `kasumi movie 'out/s.####.exr' -o s.mp4 [--fps 24] [--frames A-B[:step]]`: the H.264 movie of
/// a sequence's EXRs through their previews' view and exposure (sequence/movie.h).
void add_movie_command(CLI::App& root);

}  // namespace kasumi
