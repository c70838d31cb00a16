#pragma once
/// Writes a render's EXR and PNG preview with metadata.
#include "core/exr_io.h"
#include "core/film.h"
#include "render/renderer.h"
#include "render/stage_times.h"

#include <cstdint>
#include <string>

namespace kasumi {

struct OutputPaths {
    std::string exr;
    std::string preview;                               ///< empty: no preview
    uint32_t aovs = kAovAll;                           ///< FilmAov bits written beside R, G, B, A
    ExrCompression compression = ExrCompression::Zip;  ///< lossless, see core/exr_io.h
};

/// Parses the `--aovs` (all, none, or a list of albedo, depth, surface, volume, transmittance)
/// and `--compression` (zip, piz, rle, none) options of render and sequence; throws a usage
/// error naming the option and what it expects.
void parse_output_format(const std::string& aovs_text, const std::string& compression_text,
                         uint32_t& aovs, ExrCompression& compression);

/// Creates parent directories, then writes both files atomically (temporary name, rename).
/// The EXR metadata holds the stage times given (written as kasumi/time/<stage>_s: write_exr adds
/// the prefix) and the plan's stages that ran and were skipped. R, G, B, A are written as the
/// scene's film.pixel_type (AOVs as float); the report says what half saturated.
ExrWriteReport write_render_outputs(const SceneRuntime& scene, const RenderResult& result,
                                    const OutputPaths& paths, const StageTimes& times = {});

/// The -v lines on the EXR's pixel type (and, for half, the values saturated or flushed to 0).
std::string format_write_stats(const SceneRuntime& scene, const ExrWriteReport& report);

/// A one-line warning when half output saturated values (empty otherwise): how many, the
/// largest value, and that --pixel-type float keeps them.
std::string half_saturation_warning(const ExrWriteReport& report, const std::string& path);

/// Render statistics as lines for -v.
std::string format_stats(const SceneRuntime& scene, const RenderResult& result,
                         const StageTimes& times = {});

}  // namespace kasumi
