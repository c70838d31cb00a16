#include "apps/movie_command.h"

#include "sequence/movie.h"
#include "sequence/sequence.h"

#include <memory>
#include <string>

namespace kasumi {

namespace {

struct Options {
    std::string pattern;
    std::string output;
    std::string frames;
    double fps = 24.0;
    bool quiet = false;
};

}  // namespace

void add_movie_command(CLI::App& root) {
    auto o = std::make_shared<Options>();
    CLI::App* cmd = root.add_subcommand(
        "movie", "encode a sequence's EXRs to an H.264 movie with ffmpeg (docs/sequences.md)");
    cmd->add_option("pattern", o->pattern, "EXR pattern, '#' run = zero-padded frame number")
        ->required();
    cmd->add_option("-o,--output", o->output,
                    "movie file (default: <pattern's directory>/<name up to '#'>mp4)");
    cmd->add_option("--fps", o->fps, "frames per second (default 24)")
        ->check(CLI::Range(0.001, 1000.0));
    cmd->add_option("--frames", o->frames,
                    "frames A-B[:step] (default: first to last on disk, every one required)");
    cmd->add_flag("-q,--quiet", o->quiet, "no summary line");
    cmd->callback([o] {
        MovieOptions m;
        m.pattern = o->pattern;
        m.path = o->output.empty() ? default_movie_path(o->pattern) : o->output;
        m.fps = o->fps;
        m.log = o->quiet ? nullptr : stderr;
        if (!o->frames.empty())
            m.frames = parse_frame_range(o->frames).frames();
        write_movie(m);
    });
}

}  // namespace kasumi
