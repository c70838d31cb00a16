#pragma once
/// Frame sequences of an animated scene (docs/sequences.md). Each frame's document comes from
/// scene/animation.h, its random numbers are keyed by its frame number (core/rng.h pixel_rng),
/// it is written atomically under a name from a '#' pattern, and work that does not change
/// between frames is kept (sequence/sequence_cache.h). A frame rendered alone (--frame N) is
/// bit-identical to the same frame of a whole run.
#include "core/exr_io.h"
#include "core/film.h"
#include "scene/scene_loader.h"
#include "sequence/sequence_cache.h"

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace kasumi {

/// Frames first, first + step, ... up to last (inclusive).
struct FrameRange {
    int64_t first = 0;
    int64_t last = 0;
    int64_t step = 1;
    std::vector<int64_t> frames() const;
};

/// Parses "A-B", "A-B:step" or "N" (frames in [0, 2^32 - 1], A <= B, step >= 1); throws a
/// usage error naming `option` otherwise.
FrameRange parse_frame_range(const std::string& text, const std::string& option = "--frames");

/// `pattern` with every run of '#' replaced by `frame` zero-padded to the run's length (wider
/// numbers are written in full). Throws a usage error if the pattern has no '#'.
std::string frame_path(const std::string& pattern, int64_t frame);

/// The preview PNG of `frame`: DIR/<file name of frame_path, extension .png>.
std::string frame_preview_path(const std::string& pattern, const std::string& preview_dir,
                               int64_t frame);

/// Where the contact sheet goes unless told: <preview_dir or the outputs' directory>/<the
/// pattern's file name up to its first '#'>contact_sheet.png, e.g. out/sunset.contact_sheet.png
/// for out/sunset.####.exr.
std::string default_contact_sheet_path(const std::string& pattern, const std::string& preview_dir);

struct SequenceOptions {
    std::string scene_path;
    std::vector<Override> overrides;  ///< --set, --res, --spp, --seed: applied as render does
    std::vector<int64_t> frames;      ///< in the order they are rendered
    std::string output_pattern;       ///< EXR path with a '#' run
    std::string preview_dir;          ///< empty: no per-frame preview PNGs
    std::string contact_sheet;        ///< empty: none
    std::string movie;                ///< H.264 movie of the frames (sequence/movie.h); empty: none
    double movie_fps = 24.0;          ///< frames per second of the movie
    bool render = true;               ///< false: only the contact sheet, from the EXRs on disk
    bool skip_existing = true;        ///< a frame whose EXR exists is not rendered again
    bool reuse = true;                ///< false: parse and build everything every frame
    int threads = 0;                  ///< 0: the scene's render.threads
    bool progress = false;            ///< tile progress bar of each frame
    std::FILE* log = stderr;          ///< one line per frame and a summary; null: silent
    const std::atomic<bool>* cancel = nullptr;  ///< set asynchronously: stop, drop the frame
    uint32_t aovs = kAovAll;  ///< FilmAov bits: the AOV channels written beside R, G, B, A
    ExrCompression compression = ExrCompression::Zip;  ///< lossless, see core/exr_io.h
    /// Frames whose files may wait for the background writer while the next frame renders
    /// (sequence/sequence_writer.h); 0 writes each frame before rendering the next.
    size_t write_queue = 1;
};

struct SequenceSummary {
    size_t rendered = 0;
    size_t skipped = 0;           ///< outputs that existed
    size_t missing = 0;           ///< contact sheet cells without a frame on disk
    double seconds = 0.0;         ///< wall time of the whole run
    double frame_seconds = 0.0;   ///< sum over rendered frames (document to written file)
    double render_seconds = 0.0;  ///< sum of render_image times
    double write_seconds = 0.0;   ///< sum of the frames' write times (preview, EXR, thumbnail)
    bool interrupted = false;     ///< cancelled: the frame in flight was not written
    size_t meter_renders = 0;     ///< auto exposure's meter renders (sequence/auto_exposure.h)
    double meter_seconds = 0.0;   ///< their wall time
    size_t stored_meterings = 0;  ///< meterings read from the store (sequence/meter_store.h)
    std::string meter_store;      ///< the store's directory, or why it could not be written
    ReuseCounts reuse;
    std::string contact_sheet;  ///< written path, or empty
    std::string movie;          ///< written path, or empty
};

/// Renders (or skips) every frame of `options.frames`, then writes the contact sheet (through
/// the first frame's preview view and exposure, so brightness changes show) and the movie
/// (every frame required: a missing one is an input error naming it). Each
/// frame's preview is written before its EXR, so an existing EXR means a finished frame. A
/// frame's files are written on a background thread while the next frame renders; every
/// rendered frame is written before this returns (or unwinds), and after a failed write no
/// later frame is written. Throws input errors (scene, animation), usage errors (pattern) and
/// output errors (writing: the first failed frame's error).
SequenceSummary run_sequence(const SequenceOptions& options);

}  // namespace kasumi
