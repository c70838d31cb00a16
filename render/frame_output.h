#pragma once
/// The files of one rendered frame, written the same way by `kasumi render`, `kasumi sequence`
/// and any other caller of the library: the EXR (scene-linear Rec.709, the kasumi/* metadata of
/// frame_metadata) and its preview PNG through OpenColorIO, each written atomically (temporary
/// name, then rename: core/exr_io.h, core/color_management.h).
#include "core/color_management.h"
#include "core/exr_io.h"
#include "core/film.h"
#include "render/renderer.h"
#include "render/stage_times.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace kasumi {

/// The program and version every EXR names in its kasumi/version attribute.
inline constexpr const char* kKasumiVersion = "kasumi 0.1.0";

/// Where a frame's files go and how the EXR is stored.
struct OutputPaths {
    std::string exr;
    std::string preview;  ///< empty: no preview
    /// FilmAov bits written beside R, G, B, A (if stored)
    uint32_t aovs = kAovAll | kAovSamples | kAovNoisy;
    ExrCompression compression = ExrCompression::Zip;  ///< lossless, see core/exr_io.h
};

/// Parses the `--aovs` (all, none, or a list of albedo, depth, surface, volume, transmittance,
/// samples: the last written only by adaptive renders)
/// and `--compression` (zip, piz, rle, none) options of render and sequence; throws a usage
/// error naming the option and what it expects.
void parse_output_format(const std::string& aovs_text, const std::string& compression_text,
                         uint32_t& aovs, ExrCompression& compression);

/// Creates the parent directories of `path`; throws an output error naming the directory.
void make_parent_dirs(const std::string& path);

/// The scene's render.preview view and exposure with the default OCIO config (exposure 0 when
/// it is "auto": the caller meters it, see metered_preview_settings and sequence/auto_exposure.h).
PreviewSettings preview_settings(const SceneDesc& desc);

/// preview_settings of `scene`, its "auto" exposure metered on the rendered frame itself
/// (core/exposure_meter.h; a single frame has no sequence to smooth over).
PreviewSettings metered_preview_settings(const SceneRuntime& scene, const RenderResult& result);

/// The EXR metadata of frame `frame` rendered from `scene` (keys without the kasumi/ prefix that
/// write_exr adds): version, scene, frame, spp, seed, render_seconds, units, interrupted, the
/// view and exposure of `preview` (preview/view, preview/exposure_stops: what `kasumi movie`
/// tone maps the frame with; preview/exposure: "auto" or "fixed"), the render counters as stats/*,
/// and stage_metadata(times, plan) (time/<stage>_s, plan/ran, plan/skipped). The same keys for
/// every command that renders.
std::vector<std::pair<std::string, std::string>> frame_metadata(const SceneRuntime& scene,
                                                                const RenderResult& result,
                                                                int64_t frame,
                                                                const StageTimes& times,
                                                                const PreviewSettings& preview);

/// What writing a frame's files needs once its runtime is gone (a sequence writes them on a
/// background thread while the next frame renders).
struct FrameFiles {
    std::string exr;
    std::string preview;  ///< empty: no preview
    ExrCompression compression = ExrCompression::Zip;
    PreviewSettings preview_settings;
    int threads = 0;  ///< threads compressing the EXR (0: one per hardware thread)
};

/// Creates parent directories, then writes, when files.preview is set, the preview PNG of R, G, B
/// (`header`'s own R, G, B channels if it has them, else copied from `channels`) and last the
/// EXR of `channels` (R, G, B, A first, then AOVs; `header` gives size and metadata), so an EXR
/// on disk means the frame is complete. Both atomic. Returns what the half conversion did.
ExrWriteReport write_frame_files(const Image& header, const std::vector<ExrChannelView>& channels,
                                 const FrameFiles& files);

/// Views of `image`'s channels for write_frame_files: the first four (R, G, B, A) as
/// `pixel_type`, the AOVs as float. Valid while `image` lives unchanged.
std::vector<ExrChannelView> image_channel_views(const Image& image, ExrPixelType pixel_type);

/// `kasumi render`'s files: the film's planes written straight (no copy) with frame_metadata
/// (`times` as measured so far), compressed with the render's own thread count. R, G, B, A are
/// written as the scene's film.pixel_type; the report says what half saturated.
ExrWriteReport write_render_outputs(const SceneRuntime& scene, const RenderResult& result,
                                    const OutputPaths& paths, int64_t frame,
                                    const StageTimes& times = {});

/// The preview PNG of a render alone, as write_render_outputs writes it beside the EXR: the
/// film's R, G, B through the scene's render.preview view and exposure, written atomically.
void write_render_preview(const SceneRuntime& scene, const RenderResult& result,
                          const std::string& path);

}  // namespace kasumi
