#include "sequence/sequence.h"

#include "core/color_management.h"
#include "core/content_hash.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "render/frame_output.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "sequence/auto_exposure.h"
#include "sequence/frame_record.h"
#include "sequence/frame_runtime.h"
#include "sequence/movie.h"
#include "sequence/sequence_contact_sheet.h"
#include "sequence/sequence_writer.h"

#include <chrono>
#include <cstdarg>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>

namespace kasumi {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int64_t kMaxFrame = 4294967295;  // the RNG keys frames by 32 bits

bool parse_int64(const std::string& text, int64_t& out) {
    if (text.empty() || text.size() > 12)
        return false;
    out = 0;
    for (const char c : text) {
        if (c < '0' || c > '9')
            return false;
        out = out * 10 + (c - '0');
    }
    return true;
}

void log_line(std::FILE* log, const char* format, ...) __attribute__((format(printf, 2, 3)));
void log_line(std::FILE* log, const char* format, ...) {
    if (log == nullptr)
        return;
    va_list args;
    va_start(args, format);
    std::vfprintf(log, format, args);
    va_end(args);
    std::fflush(log);
}

/// What stays fixed over a run: the scene file with its overrides and animation, the element
/// cache.
struct SequenceScene {
    SceneSource source;
    SequenceCache cache;

    explicit SequenceScene(const SequenceOptions& o)
        : source(o.scene_path, o.overrides),
          cache(o.reuse),
          scene_path(o.scene_path),
          meter_store(meter_store_dir(o.output_pattern)),
          reuse(o.reuse),
          threads(o.threads) {}

    Json document(int64_t frame) const {
        SceneDocument doc = source.frame_document(frame);
        return std::move(doc.json());
    }

    /// The scene of `frame`'s document; an input error says where the frame lies among the
    /// key frames, as `kasumi check` does (frame_context).
    SceneDesc parse(const Json& doc, int64_t frame) { return source.parse(doc, frame, &cache); }

    /// The preview settings of `frame` (scene `desc`): an "auto" exposure metered and smoothed
    /// over the frames before it (sequence/auto_exposure.h).
    PreviewSettings preview(const SceneDesc& desc, int64_t frame) {
        PreviewSettings settings = preview_settings(desc);
        if (desc.render.preview.exposure_auto) {
            if (auto_exposure == nullptr)
                auto_exposure =
                    std::make_unique<AutoExposure>(source, scene_path, reuse, threads, meter_store);
            settings.exposure_stops = auto_exposure->exposure_stops(frame);
        }
        return settings;
    }

    std::string scene_path;
    std::string meter_store;  ///< auto exposure's store of meterings (sequence/meter_store.h)
    bool reuse;
    int threads;
    std::unique_ptr<AutoExposure> auto_exposure;  ///< made at the first "auto" frame
};

}  // namespace

std::vector<int64_t> FrameRange::frames() const {
    std::vector<int64_t> out;
    for (int64_t f = first; f <= last; f += step)
        out.push_back(f);
    return out;
}

FrameRange parse_frame_range(const std::string& text, const std::string& option) {
    const auto usage = [&] {
        throw Error(ErrorKind::Usage, option + " expects A-B[:step] or N (frames 0 to " +
                                          std::to_string(kMaxFrame) +
                                          ", A <= B, step >= 1), got \"" + text + "\"");
    };
    FrameRange range;
    std::string span = text;
    const size_t colon = text.find(':');
    if (colon != std::string::npos) {
        span = text.substr(0, colon);
        if (!parse_int64(text.substr(colon + 1), range.step) || range.step < 1)
            usage();
    }
    const size_t dash = span.find('-');
    if (dash == std::string::npos) {
        if (colon != std::string::npos || !parse_int64(span, range.first))
            usage();
        range.last = range.first;
    } else if (!parse_int64(span.substr(0, dash), range.first) ||
               !parse_int64(span.substr(dash + 1), range.last)) {
        usage();
    }
    if (range.first > range.last || range.last > kMaxFrame)
        usage();
    return range;
}

std::string frame_path(const std::string& pattern, int64_t frame) {
    std::string out;
    bool found = false;
    for (size_t i = 0; i < pattern.size();) {
        if (pattern[i] != '#') {
            out += pattern[i++];
            continue;
        }
        size_t n = 0;
        while (i + n < pattern.size() && pattern[i + n] == '#')
            ++n;
        std::string digits = std::to_string(frame);
        if (digits.size() < n)
            digits.insert(0, n - digits.size(), '0');
        out += digits;
        i += n;
        found = true;
    }
    if (!found) {
        throw Error(ErrorKind::Usage, "-o \"" + pattern +
                                          "\": the output pattern needs a run of '#' for the "
                                          "frame number, e.g. out/sunset.####.exr");
    }
    return out;
}

std::string frame_preview_path(const std::string& pattern, const std::string& preview_dir,
                               int64_t frame) {
    fs::path name = fs::path(frame_path(pattern, frame)).filename();
    name.replace_extension(".png");
    return (fs::path(preview_dir) / name).string();
}

std::string default_contact_sheet_path(const std::string& pattern, const std::string& preview_dir) {
    const fs::path p(pattern);
    const std::string file = p.filename().string();
    const std::string name = file.substr(0, file.find('#')) + "contact_sheet.png";
    const fs::path dir = preview_dir.empty() ? p.parent_path() : fs::path(preview_dir);
    return (dir / name).string();
}

SequenceSummary run_sequence(const SequenceOptions& options) {
    const auto run_start = Clock::now();
    for (const int64_t f : options.frames) {
        if (f < 0 || f > kMaxFrame)
            throw Error(ErrorKind::Usage, "frame " + std::to_string(f) + " is out of range");
    }
    (void)frame_path(options.output_pattern, 0);  // a pattern without '#' is a usage error
    SequenceScene scene(options);
    SequenceSummary summary;
    const bool want_sheet = !options.contact_sheet.empty();

    // Touched by the writer's tasks only, until writer.finish() (declared before the writer,
    // whose destructor may still run tasks while an exception unwinds).
    std::map<int64_t, Image> thumbnails;
    size_t written = 0;
    double frame_seconds_sum = 0.0, write_seconds_sum = 0.0;
    // Images the writer is done with, refilled by the next frames (no allocation per frame).
    std::mutex spare_mutex;
    std::vector<Image> spare_images;

    std::unique_ptr<SequenceWriter> writer;
    if (options.write_queue > 0)
        writer = std::make_unique<SequenceWriter>(options.write_queue);
    // Runs `task` on the writer thread, after the earlier frames' files (or here and now).
    const auto dispatch = [&](std::function<void()> task) {
        if (writer != nullptr)
            writer->submit(std::move(task));
        else
            task();
    };
    const auto log_later = [&](std::string line) {
        dispatch(
            [log = options.log, line = std::move(line)] { log_line(log, "%s", line.c_str()); });
    };

    for (const int64_t frame : options.frames) {
        if (!options.render)
            break;
        if (writer != nullptr)
            writer->check();  // a failed write stops the run before rendering more
        if (options.cancel != nullptr && options.cancel->load()) {
            summary.interrupted = true;
            break;
        }
        const std::string path = frame_path(options.output_pattern, frame);
        const std::string preview_path =
            options.preview_dir.empty()
                ? std::string()
                : frame_preview_path(options.output_pattern, options.preview_dir, frame);
        const std::string frame_name = frame_path("######", frame);
        if (options.skip_existing && fs::exists(path)) {
            ++summary.skipped;
            if (!preview_path.empty() && !fs::exists(preview_path)) {
                const PreviewSettings own =
                    scene.preview(scene.parse(scene.document(frame), frame), frame);
                dispatch([=, log = options.log] {
                    make_parent_dirs(preview_path);
                    write_preview_png(read_exr(path), preview_path, own);
                    log_line(log, "frame %s  exists, skipped (preview %s written)\n",
                             frame_name.c_str(), preview_path.c_str());
                });
            } else {
                log_later("frame " + frame_name + "  exists, skipped: " + path + "\n");
            }
            continue;
        }

        const auto frame_start = Clock::now();
        StageTimes times;
        const Json doc = scene.document(frame);
        SceneDesc desc = scene.parse(doc, frame);
        times.load_s = seconds_since(frame_start);
        const auto build_start = Clock::now();
        const std::unique_ptr<SceneRuntime> runtime_owner = build_frame_runtime(
            scene.cache, doc, options.scene_path, std::move(desc), options.reuse);
        const SceneRuntime& runtime = *runtime_owner;
        times.build_s = seconds_since(build_start);
        add_stage_parts(times, runtime);
        const double setup_seconds = seconds_since(frame_start);

        RenderOptions render_options;
        render_options.threads = options.threads;
        render_options.frame = static_cast<uint32_t>(frame);
        render_options.progress = options.progress;
        render_options.cancel = options.cancel;
        render_options.aovs = options.aovs;
        RenderResult result = render_image(runtime, render_options);
        const ReuseCounts reuse = scene.cache.end_frame();
        if (result.interrupted) {
            summary.interrupted = true;
            log_later("frame " + frame_name + "  interrupted: dropped, nothing written\n");
            break;
        }
        summary.render_seconds += result.seconds;
        times.render_s = result.seconds;

        const auto image_start = Clock::now();
        Image image;
        {
            std::lock_guard<std::mutex> lock(spare_mutex);
            if (!spare_images.empty()) {
                image = std::move(spare_images.back());
                spare_images.pop_back();
            }
        }
        result.film.to_image(image, options.aovs);
        FrameFiles files;
        files.exr = path;
        files.preview = preview_path;
        files.compression = options.compression;
        files.preview_settings = scene.preview(runtime.desc(), frame);
        FrameRecord record;
        record.frame = frame;
        record.file = fs::path(path).filename().string();
        record.scene = options.scene_path;
        record.scene_hash = text_content_hash(doc.dump());
        record.settings = frame_settings(runtime.desc(), doc, options.aovs, options.compression);
        record.seed = runtime.desc().render.seed;
        record.render_seconds = result.seconds;
        record.host = host_name();
        record.version = kKasumiVersion;
        image.metadata = frame_metadata(runtime, result, frame, times, files.preview_settings);
        // Time spent on this frame here; the writer adds its own.
        const double main_seconds = seconds_since(frame_start);
        const double image_seconds = seconds_since(image_start);
        const double render_seconds = result.seconds;
        const uint64_t nonfinite = result.counters.nonfinite_samples;
        const std::string reuse_line = reuse_text(reuse);
        const ExrPixelType pixel_type = runtime.desc().film.pixel_type;

        dispatch([&, frame, path, files, frame_name, main_seconds, setup_seconds, image_seconds,
                  render_seconds, nonfinite, reuse_line, pixel_type, record = std::move(record),
                  image = std::move(image)]() mutable {
            const auto write_start = Clock::now();
            const ExrWriteReport half_report =
                write_frame_files(image, image_channel_views(image, pixel_type), files);
            // The record after the EXR, hashed as written: it vouches for those bytes.
            record.exr_hash = file_content_hash(path);
            write_frame_record(record, frame_record_path(path));
            if (want_sheet)
                thumbnails.emplace(frame, make_thumbnail(image));
            const double write_seconds = image_seconds + seconds_since(write_start);
            const double frame_seconds = main_seconds + seconds_since(write_start);
            ++written;
            frame_seconds_sum += frame_seconds;
            write_seconds_sum += write_seconds;
            log_line(options.log,
                     "frame %s  %.3f s (scene %.3f s, render %.3f s, write %.3f s)  %s  -> %s\n",
                     frame_name.c_str(), frame_seconds, setup_seconds, render_seconds,
                     write_seconds, reuse_line.c_str(), path.c_str());
            if (nonfinite > 0) {
                log_line(options.log, "frame %s  warning: %llu non-finite samples were dropped\n",
                         frame_name.c_str(), static_cast<unsigned long long>(nonfinite));
            }
            if (half_report.half_saturated > 0) {
                log_line(options.log,
                         "frame %s  warning: %llu values of R, G, B, A beyond the half range "
                         "(largest %g) written as 65504 (film.pixel_type half)\n",
                         frame_name.c_str(),
                         static_cast<unsigned long long>(half_report.half_saturated),
                         static_cast<double>(half_report.half_max_abs));
            }
            image.metadata.clear();
            std::lock_guard<std::mutex> lock(spare_mutex);
            if (spare_images.size() < 2)
                spare_images.push_back(std::move(image));
        });
    }
    if (writer != nullptr)
        writer->finish();  // every rendered frame is on disk, or the first failure is thrown
    summary.rendered = written;
    summary.frame_seconds = frame_seconds_sum;
    summary.write_seconds = write_seconds_sum;
    summary.reuse = scene.cache.total();

    if (want_sheet && !summary.interrupted && !options.frames.empty()) {
        std::vector<Image> loaded;
        loaded.reserve(options.frames.size());
        std::vector<const Image*> cells;
        for (const int64_t frame : options.frames) {
            const auto it = thumbnails.find(frame);
            if (it != thumbnails.end()) {
                cells.push_back(&it->second);
                continue;
            }
            const std::string path = frame_path(options.output_pattern, frame);
            if (!fs::exists(path)) {
                ++summary.missing;
                cells.push_back(nullptr);
                continue;
            }
            loaded.push_back(make_thumbnail(read_exr(path)));
            cells.push_back(&loaded.back());
        }
        // One view and exposure for the whole sheet (the first frame's), so it shows how the
        // frames' brightness changes.
        const int64_t first = options.frames.front();
        const PreviewSettings sheet_preview =
            scene.preview(scene.parse(scene.document(first), first), first);
        make_parent_dirs(options.contact_sheet);
        write_preview_png(make_contact_sheet(cells), options.contact_sheet, sheet_preview);
        summary.contact_sheet = options.contact_sheet;
    }
    if (!options.movie.empty() && !summary.interrupted && !options.frames.empty()) {
        MovieOptions movie;
        movie.pattern = options.output_pattern;
        movie.frames = options.frames;
        movie.path = options.movie;
        movie.fps = options.movie_fps;
        movie.log = options.log;
        summary.movie = write_movie(movie).path;
    }
    if (scene.auto_exposure != nullptr) {
        summary.meter_renders = scene.auto_exposure->meter_renders();
        summary.meter_seconds = scene.auto_exposure->meter_seconds();
        summary.stored_meterings = scene.auto_exposure->stored_meterings();
        summary.meter_store = scene.auto_exposure->store_problem().empty()
                                  ? scene.meter_store
                                  : "not written: " + scene.auto_exposure->store_problem();
    }
    summary.seconds = seconds_since(run_start);
    return summary;
}

}  // namespace kasumi
