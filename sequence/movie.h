#pragma once
/// The movie of a sequence (docs/sequences.md#movie): every frame's EXR, in frame order, through
/// the same OCIO view and exposure as its preview PNG (read from the EXR's kasumi/preview/*
/// metadata, which frame_metadata writes), encoded to H.264 by sequence/movie_encoder.h. The
/// EXRs are tone-mapped again rather than the PNGs read back, so a movie needs only the EXRs
/// (a Slurm run without --preview-dir, or `kasumi movie` on frames from elsewhere) and looks
/// exactly like the previews.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace kasumi {

struct MovieOptions {
    std::string pattern;          ///< EXR pattern with a '#' run, as `sequence -o`
    std::vector<int64_t> frames;  ///< in movie order; empty: movie_frames(pattern)
    std::string path;             ///< the movie (.mp4)
    double fps = 24.0;            ///< frames per second, in (0, 1000]
    std::FILE* log = stderr;      ///< a summary line; null: silent
};

struct MovieSummary {
    std::string path;
    size_t frames = 0;
    int width = 0;  ///< the movie's (even) size in pixels
    int height = 0;
    double seconds = 0.0;  ///< wall time of reading, tone mapping and encoding
};

/// Frame numbers of the existing files named by `pattern` (its file name's '#' run, any width
/// the pattern would write), ascending. Throws a usage error for a pattern without '#' or with
/// '#' in its directory.
std::vector<int64_t> frames_on_disk(const std::string& pattern);

/// The frames of a movie made of the files on disk: first to last found, stepping by the
/// smallest gap between found frames. Throws ErrorKind::Input naming the pattern if none is
/// found.
std::vector<int64_t> movie_frames(const std::string& pattern);

/// Where a sequence's movie goes unless told: the pattern's directory, its file name up to
/// the first '#' and "mp4" (out/sunset.####.exr -> out/sunset.mp4).
std::string default_movie_path(const std::string& pattern);

/// Writes the movie of options.frames (or movie_frames). Checks every frame exists before
/// encoding: ErrorKind::Input names the first missing one; a frame of another size is an input
/// error naming its file. Usage error (exit 2) if ffmpeg is not on PATH; the movie appears only
/// complete (MovieEncoder).
MovieSummary write_movie(const MovieOptions& options);

}  // namespace kasumi
