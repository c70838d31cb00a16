#include "sequence/movie.h"

#include "core/color_management.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "render/frame_output.h"
#include "sequence/movie_encoder.h"
#include "sequence/sequence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

namespace kasumi {

namespace {

namespace fs = std::filesystem;

/// The view and exposure the frame's preview was written with (kasumi/preview/* metadata);
/// frames without them (written before the keys existed) get the config's default view and 0.
PreviewSettings frame_preview(const Image& frame, const std::string& path) {
    PreviewSettings preview;  // the default OCIO config
    if (const std::string* view = frame.find_metadata("preview/view"))
        preview.view = *view;
    if (const std::string* stops = frame.find_metadata("preview/exposure_stops")) {
        char* end = nullptr;
        const float value = std::strtof(stops->c_str(), &end);
        if (end == stops->c_str() || *end != '\0' || !std::isfinite(value))
            throw_input_error(path + ": kasumi/preview/exposure_stops = \"" + *stops +
                              "\": expected a finite number of stops");
        preview.exposure_stops = value;
    }
    return preview;
}

}  // namespace

std::vector<int64_t> frames_on_disk(const std::string& pattern) {
    const fs::path p(pattern);
    const std::string dir = p.parent_path().string();
    const std::string file = p.filename().string();
    if (dir.find('#') != std::string::npos || file.find('#') == std::string::npos) {
        throw Error(ErrorKind::Usage, "\"" + pattern +
                                          "\": the frame pattern needs a run of '#' in its file "
                                          "name (and none in its directory), e.g. "
                                          "out/sunset.####.exr");
    }
    const size_t run = file.find('#');
    const std::string prefix = file.substr(0, run);
    std::vector<int64_t> frames;
    std::error_code ec;
    for (const fs::directory_entry& entry :
         fs::directory_iterator(dir.empty() ? fs::path(".") : fs::path(dir), ec)) {
        const std::string name = entry.path().filename().string();
        if (name.compare(0, prefix.size(), prefix) != 0)
            continue;
        size_t digits = prefix.size();
        while (digits < name.size() && digits - prefix.size() < 10 && name[digits] >= '0' &&
               name[digits] <= '9')
            ++digits;
        if (digits == prefix.size())
            continue;
        const int64_t frame = std::stoll(name.substr(prefix.size(), digits - prefix.size()));
        // The name must be exactly the one the pattern gives this frame (padding included).
        if (frame <= 4294967295 && fs::path(frame_path(pattern, frame)).filename() == name)
            frames.push_back(frame);
    }
    std::sort(frames.begin(), frames.end());
    return frames;
}

std::vector<int64_t> movie_frames(const std::string& pattern) {
    const std::vector<int64_t> found = frames_on_disk(pattern);
    if (found.empty())
        throw_input_error(pattern + ": no frame found (no file matches the pattern)");
    int64_t step = 0;
    for (size_t i = 1; i < found.size(); ++i) {
        const int64_t gap = found[i] - found[i - 1];
        step = step == 0 ? gap : std::min(step, gap);
    }
    std::vector<int64_t> frames;
    for (int64_t f = found.front(); f <= found.back(); f += std::max<int64_t>(step, 1))
        frames.push_back(f);
    return frames;
}

std::string default_movie_path(const std::string& pattern) {
    const fs::path p(pattern);
    const std::string file = p.filename().string();
    return (p.parent_path() / (file.substr(0, file.find('#')) + "mp4")).string();
}

MovieSummary write_movie(const MovieOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<int64_t> frames =
        options.frames.empty() ? movie_frames(options.pattern) : options.frames;
    // Every frame must be there before ffmpeg starts: a movie with a hole is never begun.
    for (const int64_t frame : frames) {
        const std::string path = frame_path(options.pattern, frame);
        if (!fs::exists(path)) {
            throw_input_error(options.pattern + ": frame " + std::to_string(frame) +
                              " is missing (" + path + "); the movie needs frames " +
                              std::to_string(frames.front()) + " to " +
                              std::to_string(frames.back()) + ", every one");
        }
    }
    MovieSummary summary;
    summary.path = options.path;
    make_parent_dirs(options.path);
    std::unique_ptr<MovieEncoder> encoder;
    int width = 0, height = 0;  // of the first frame
    for (const int64_t frame : frames) {
        const std::string path = frame_path(options.pattern, frame);
        const Image image = read_exr(path);
        if (encoder == nullptr) {
            width = image.width;
            height = image.height;
            encoder = std::make_unique<MovieEncoder>(options.path, width, height, options.fps);
        } else if (image.width != width || image.height != height) {
            throw_input_error(path + ": " + std::to_string(image.width) + "x" +
                              std::to_string(image.height) + ", but the movie's first frame is " +
                              std::to_string(width) + "x" + std::to_string(height) +
                              ": every frame needs the same size");
        }
        encoder->add_frame(display_rgb8(image, frame_preview(image, path), path));
    }
    encoder->finish();
    summary.width = encoder->movie_width();
    summary.height = encoder->movie_height();
    summary.frames = encoder->frames();
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (options.log != nullptr) {
        std::fprintf(options.log, "movie: %s (%zu frames, %dx%d, %g fps, H.264) in %.2f s\n",
                     summary.path.c_str(), summary.frames, summary.width, summary.height,
                     options.fps, summary.seconds);
    }
    return summary;
}

}  // namespace kasumi
