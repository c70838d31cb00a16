#include "apps/sequence_command.h"

#include "apps/commands.h"
#include "apps/scene_options.h"
#include "core/error.h"
#include "render/frame_output.h"
#include "sequence/sequence.h"
#include "sequence/sequence_verify.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>

namespace kasumi {

namespace {

std::atomic<bool> g_cancel{false};
volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_sequence_signal(int signal) {
    g_signal = signal;
    g_cancel.store(true);
}

struct Options {
    SceneOptions scene;
    std::string frames;
    int64_t frame = -1;
    std::string output;
    std::string preview_dir;
    std::string contact_sheet;
    std::string movie;
    double fps = 24.0;
    bool no_contact_sheet = false;
    bool contact_sheet_only = false;
    bool verify = false;
    bool skip_existing = true;
    bool no_reuse = false;
    int spp = 0;
    int64_t seed = -1;
    int threads = 0;
    std::string res;
    std::string aovs = "all";
    std::string compression = "zip";
};

std::vector<Override> render_overrides(const Options& o) {
    std::vector<std::string> sets = o.scene.sets;
    if (o.spp > 0)
        sets.push_back("/film/spp=" + std::to_string(o.spp));
    if (o.seed >= 0)
        sets.push_back("/render/seed=" + std::to_string(o.seed));
    if (!o.res.empty()) {
        const Resolution res = parse_resolution_arg(o.res);
        sets.push_back("/film/width=" + std::to_string(res.width));
        sets.push_back("/film/height=" + std::to_string(res.height));
    }
    std::vector<Override> overrides;
    for (const std::string& s : sets)
        overrides.push_back(parse_override(s));
    return overrides;
}

/// --verify: one line per frame that is not ok on stdout, a count of each status on stderr;
/// exit 5 (a validation check failed) unless every frame is ok.
void verify(const SequenceOptions& s) {
    const std::vector<FrameCheck> checks = verify_sequence(s);
    size_t counts[5] = {};
    for (const FrameCheck& c : checks) {
        ++counts[static_cast<int>(c.status)];
        if (c.status != FrameStatus::Ok)
            std::printf("frame %s  %-10s  %s\n", frame_path("######", c.frame).c_str(),
                        frame_status_name(c.status), c.detail.c_str());
    }
    std::fflush(stdout);
    std::fprintf(stderr,
                 "verify: %zu frames: %zu ok, %zu missing, %zu stale, %zu corrupt, %zu "
                 "unrecorded\n",
                 checks.size(), counts[0], counts[1], counts[2], counts[3], counts[4]);
    if (counts[0] != checks.size())
        set_command_exit_code(static_cast<int>(ErrorKind::Validation));
}

void run(const Options& o) {
    SequenceOptions s;
    s.scene_path = o.scene.scene_path;
    s.overrides = render_overrides(o);
    s.output_pattern = o.output;
    s.preview_dir = o.preview_dir;
    s.skip_existing = o.skip_existing;
    s.reuse = !o.no_reuse;
    s.threads = o.threads;
    s.progress = o.scene.verbose;
    s.log = o.scene.quiet ? nullptr : stderr;
    s.cancel = &g_cancel;
    parse_output_format(o.aovs, o.compression, s.aovs, s.compression);
    if (!o.preview_dir.empty()) {
        check_distinct_outputs(frame_path(o.output, 0),
                               frame_preview_path(o.output, o.preview_dir, 0),
                               "-o " + o.output + " and --preview-dir " + o.preview_dir +
                                   ": each frame's preview PNG would replace its EXR; name the "
                                   "EXRs *.exr or give another --preview-dir");
    }
    if (o.frames.empty() && o.frame < 0)
        throw Error(ErrorKind::Usage, "sequence needs --frames A-B[:step] or --frame N");
    if (o.frame >= 0) {
        // A farm task: one frame, no contact sheet (a final job builds it).
        if (!o.frames.empty()) {
            const std::vector<int64_t> all = parse_frame_range(o.frames).frames();
            if (std::find(all.begin(), all.end(), o.frame) == all.end())
                throw Error(ErrorKind::Usage, "--frame " + std::to_string(o.frame) +
                                                  " is not a frame of --frames " + o.frames);
        }
        s.frames = {o.frame};
        if (o.contact_sheet_only)
            throw Error(ErrorKind::Usage, "--contact-sheet-only needs --frames, not --frame");
    } else {
        s.frames = parse_frame_range(o.frames).frames();
        if (!o.no_contact_sheet) {
            s.contact_sheet = o.contact_sheet.empty()
                                  ? default_contact_sheet_path(o.output, o.preview_dir)
                                  : o.contact_sheet;
        }
    }
    if (!o.movie.empty()) {
        if (o.frame >= 0)
            throw Error(ErrorKind::Usage,
                        "--movie needs the whole --frames range, not one --frame (run `kasumi "
                        "movie` after the farm's tasks)");
        s.movie = o.movie;
        s.movie_fps = o.fps;
    }
    if (o.frame >= 0 && !o.contact_sheet.empty())
        s.contact_sheet = o.contact_sheet;
    s.render = !o.contact_sheet_only;
    if (o.verify) {
        verify(s);
        return;
    }

    g_cancel = false;
    std::signal(SIGINT, on_sequence_signal);
    std::signal(SIGTERM, on_sequence_signal);
    const SequenceSummary summary = run_sequence(s);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);

    if (!o.scene.quiet) {
        const size_t n = s.frames.size();
        if (s.render) {
            std::fprintf(stderr,
                         "sequence: %zu frame%s: %zu rendered, %zu skipped (existing)%s in %.2f s",
                         n, n == 1 ? "" : "s", summary.rendered, summary.skipped,
                         summary.interrupted ? ", interrupted" : "", summary.seconds);
            if (summary.rendered > 0) {
                // Frames are written while the next renders: the wall time per frame is less
                // than a frame's own time (scene + render + write).
                const double r = static_cast<double>(summary.rendered);
                std::fprintf(stderr,
                             "; %.3f s per rendered frame (own time %.3f s: render %.3f s, "
                             "write %.3f s)",
                             summary.seconds / r, summary.frame_seconds / r,
                             summary.render_seconds / r, summary.write_seconds / r);
            }
            std::fprintf(stderr, "\nsequence: over the run: %s\n",
                         reuse_text(summary.reuse).c_str());
            if (summary.meter_renders > 0 || summary.stored_meterings > 0) {
                std::fprintf(
                    stderr,
                    "sequence: auto exposure: %zu meter renders in %.2f s (%.3f s "
                    "each), %zu meterings read from the store; store: %s\n",
                    summary.meter_renders, summary.meter_seconds,
                    summary.meter_renders > 0
                        ? summary.meter_seconds / static_cast<double>(summary.meter_renders)
                        : 0.0,
                    summary.stored_meterings, summary.meter_store.c_str());
            }
        }
        if (!summary.contact_sheet.empty()) {
            std::fprintf(stderr, "contact sheet: %s (%zu frames, %zu missing)\n",
                         summary.contact_sheet.c_str(), n - summary.missing, summary.missing);
        }
    }
    if (summary.interrupted) {
        std::fprintf(stderr,
                     "kasumi: interrupted; finished frames are kept, the frame in "
                     "flight was dropped\n");
        set_command_exit_code(g_signal == SIGTERM ? 143 : 130);
    }
}

}  // namespace

void add_sequence_command(CLI::App& root) {
    auto o = std::make_shared<Options>();
    CLI::App* cmd = root.add_subcommand(
        "sequence", "render the frames of an animated scene (docs/sequences.md)");
    o->scene.add_to(*cmd);
    cmd->add_option("--frames", o->frames, "frames A-B[:step] (inclusive)");
    cmd->add_option("--frame", o->frame, "render only frame N (a farm task; no contact sheet)")
        ->check(CLI::Range(int64_t{0}, int64_t{4294967295}));
    cmd->add_option("-o,--output", o->output, "EXR pattern, '#' run = zero-padded frame number")
        ->required();
    cmd->add_option("--preview-dir", o->preview_dir, "write a preview PNG of each frame here");
    auto* sheet = cmd->add_option("--contact-sheet", o->contact_sheet,
                                  "contact sheet PNG (default: <preview dir or output dir>/"
                                  "<name>contact_sheet.png)");
    cmd->add_flag("--no-contact-sheet", o->no_contact_sheet, "write no contact sheet")
        ->excludes(sheet);
    cmd->add_option("--movie", o->movie,
                    "also encode the frames to this H.264 movie (.mp4) with ffmpeg, through the "
                    "previews' view and exposure");
    cmd->add_option("--fps", o->fps, "movie frames per second (default 24)")
        ->check(CLI::Range(0.001, 1000.0));
    cmd->add_flag("--verify", o->verify,
                  "render nothing: check every frame against its manifest record (missing, "
                  "stale, corrupt, unrecorded; exit 5 unless all are ok)");
    cmd->add_flag("--contact-sheet-only", o->contact_sheet_only,
                  "render nothing: build the contact sheet from the EXRs on disk");
    cmd->add_flag("--skip-existing,!--no-skip-existing", o->skip_existing,
                  "do not render frames whose EXR exists (default on)");
    cmd->add_flag("--no-reuse", o->no_reuse,
                  "parse and build everything every frame (to measure what reuse saves)");
    cmd->add_option("--spp", o->spp, "samples per pixel (overrides film.spp)")
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--seed", o->seed, "random seed (overrides render.seed)")
        ->check(CLI::Range(int64_t{0}, std::numeric_limits<int64_t>::max()));
    cmd->add_option("--threads", o->threads, "worker threads (0: all)")->check(CLI::Range(0, 1024));
    cmd->add_option("--res", o->res, "resolution WxH (overrides film.width/height)");
    cmd->add_option("--aovs", o->aovs,
                    "AOV channels written beside R,G,B,A: all (default), none, or a list of "
                    "albedo,depth,surface,volume,transmittance");
    cmd->add_option("--compression", o->compression,
                    "EXR compression, all lossless: zip (default), piz, rle, none");
    cmd->callback([o] { run(*o); });
}

}  // namespace kasumi
