#include "render/frame_output.h"

#include "core/error.h"
#include "core/exposure_meter.h"
#include "core/preview_metadata.h"

#include <cstdio>
#include <filesystem>

namespace kasumi {

void parse_output_format(const std::string& aovs_text, const std::string& compression_text,
                         uint32_t& aovs, ExrCompression& compression) {
    if (!parse_film_aovs(aovs_text, aovs))
        throw Error(ErrorKind::Usage,
                    "--aovs expects all, none or a comma-separated list of albedo, depth, "
                    "surface, volume, transmittance, samples, noisy; got \"" +
                        aovs_text + "\"");
    if (!parse_exr_compression(compression_text, compression))
        throw Error(ErrorKind::Usage, "--compression expects zip, piz, rle or none; got \"" +
                                          compression_text + "\"");
}

void make_parent_dirs(const std::string& path) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (parent.empty())
        return;
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec)
        throw_output_error(path + ": cannot create directory " + parent.string() + ": " +
                           ec.message());
}

PreviewSettings preview_settings(const SceneDesc& desc) {
    PreviewSettings preview;  // config_path empty: the default config, found when used
    preview.view = desc.render.preview.view;
    preview.exposure_stops = desc.render.preview.exposure_stops;
    return preview;
}

PreviewSettings metered_preview_settings(const SceneRuntime& scene, const RenderResult& result) {
    PreviewSettings preview = preview_settings(scene.desc());
    if (scene.desc().render.preview.exposure_auto) {
        const std::vector<FilmPlane> rgb = result.film.planes(0);  // R, G, B, A
        const size_t pixels =
            static_cast<size_t>(result.film.width()) * static_cast<size_t>(result.film.height());
        preview.exposure_stops = metered_exposure_stops(
            log2_average_luminance(rgb[0].data, rgb[1].data, rgb[2].data, pixels));
    }
    return preview;
}

std::vector<std::pair<std::string, std::string>> frame_metadata(const SceneRuntime& scene,
                                                                const RenderResult& result,
                                                                int64_t frame,
                                                                const StageTimes& times,
                                                                const PreviewSettings& preview) {
    const SceneDesc& desc = scene.desc();
    const RenderCounters& c = result.counters;
    std::vector<std::pair<std::string, std::string>> metadata = {
        {"version", kKasumiVersion},
        {"scene", desc.file},
        {"frame", std::to_string(frame)},
        {"spp", std::to_string(desc.film.spp)},
        {"seed", std::to_string(desc.render.seed)},
        {"render_seconds", std::to_string(result.seconds)},
        {"units", "scene-linear Rec.709, luminance in cd/m2"},
        {"interrupted", result.interrupted ? "true" : "false"},
        {"preview/view", preview.view},
        {"preview/exposure_stops", exposure_text(preview.exposure_stops)},
        {"preview/exposure", desc.render.preview.exposure_auto ? "auto" : "fixed"},
        {"stats/camera_rays", std::to_string(c.camera_rays)},
        {"stats/surface_shadow_rays", std::to_string(c.surface_shadow_rays)},
        {"stats/shadow_rays_avoided", std::to_string(c.shadow_rays_avoided)},
        {"stats/volume_steps", std::to_string(c.volume_steps)},
        {"stats/volume_shadow_rays", std::to_string(c.volume_shadow_rays)},
        {"stats/nonfinite_samples", std::to_string(c.nonfinite_samples)},
        {"stats/density_lookups", std::to_string(c.density_lookups)},
        {"stats/transmittance_rays", std::to_string(c.transmittance_rays)},
        {"stats/free_flights", std::to_string(c.free_flights)},
        {"stats/scattering_events", std::to_string(c.scattering_events)},
        {"stats/bounded_marches", std::to_string(c.bounded_marches)},
        {"stats/threads", std::to_string(result.threads)},
        {"stats/density_lookups_per_s_per_core",
         std::to_string(
             render_rates(c, result.seconds, result.threads).density_lookups_per_s_per_core)},
    };
    if (desc.film.noise_threshold > 0.0f) {
        metadata.emplace_back("noise_threshold", std::to_string(desc.film.noise_threshold));
        metadata.emplace_back("min_spp", std::to_string(desc.film.min_spp));
        metadata.emplace_back("noise_window", std::to_string(desc.film.noise_window));
    }
    const DenoiseSettings& denoise = desc.film.denoise;
    if (denoise.enabled && !result.interrupted) {
        // R, G, B are filtered (render/denoise/nlm_filter.h); noisy.R/G/B hold the raw means.
        metadata.emplace_back("denoise", "nlm radius " + std::to_string(denoise.radius) +
                                             " patch " + std::to_string(denoise.patch) + " k " +
                                             std::to_string(denoise.k) + " k_feature " +
                                             std::to_string(denoise.k_feature) +
                                             (denoise.select ? " select" : ""));
    }
    for (auto& kv : stage_metadata(times, scene.plan()))
        metadata.push_back(std::move(kv));
    return metadata;
}

std::vector<ExrChannelView> image_channel_views(const Image& image, ExrPixelType pixel_type) {
    std::vector<ExrChannelView> views;
    for (const ImageChannel& channel : image.channels)
        views.push_back({channel.name, channel.data.data(),
                         views.size() < 4 ? pixel_type : ExrPixelType::Float});
    return views;
}

namespace {

/// The preview PNG of `header` (its own R, G, B channels if it has them, else copied from
/// `channels`), its directories created first.
void write_preview(const Image& header, const std::vector<ExrChannelView>& channels,
                   const std::string& path, const PreviewSettings& settings) {
    make_parent_dirs(path);
    if (!header.channels.empty()) {
        write_preview_png(header, path, settings);
        return;
    }
    Image rgb(header.width, header.height);
    const size_t pixels = static_cast<size_t>(header.width) * header.height;
    for (size_t i = 0; i < 3 && i < channels.size(); ++i) {  // R, G, B
        const float* from = channels[i].data;
        rgb.channels.push_back({channels[i].name, std::vector<float>(from, from + pixels)});
    }
    write_preview_png(rgb, path, settings);
}

}  // namespace

ExrWriteReport write_frame_files(const Image& header, const std::vector<ExrChannelView>& channels,
                                 const FrameFiles& files) {
    // The preview first, the EXR last: an EXR on disk means the whole frame was written
    // (`sequence --skip-existing` and the Slurm scripts skip frames by their EXR).
    if (!files.preview.empty())
        write_preview(header, channels, files.preview, files.preview_settings);
    make_parent_dirs(files.exr);
    return write_exr(header, channels, files.exr, files.compression, files.threads);
}

ExrWriteReport write_render_outputs(const SceneRuntime& scene, const RenderResult& result,
                                    const OutputPaths& paths, int64_t frame,
                                    const StageTimes& times) {
    const SceneDesc& desc = scene.desc();
    // The EXR is written straight from the film's planes; `header` carries size and metadata.
    Image header(result.film.width(), result.film.height());
    const PreviewSettings preview = metered_preview_settings(scene, result);
    header.metadata = frame_metadata(scene, result, frame, times, preview);
    std::vector<ExrChannelView> channels;
    for (const FilmPlane& plane : result.film.planes(paths.aovs)) {
        // The first four planes are R, G, B, A (Film::planes); AOVs stay float.
        channels.push_back({plane.name, plane.data,
                            channels.size() < 4 ? desc.film.pixel_type : ExrPixelType::Float});
    }
    FrameFiles files;
    files.exr = paths.exr;
    files.preview = paths.preview;
    files.compression = paths.compression;
    files.preview_settings = preview;
    // Compressed with the render's own thread count (--threads 1: on this thread alone).
    files.threads = result.threads;
    return write_frame_files(header, channels, files);
}

void write_render_preview(const SceneRuntime& scene, const RenderResult& result,
                          const std::string& path) {
    std::vector<ExrChannelView> channels;
    for (const FilmPlane& plane : result.film.planes(kAovNone))  // R, G, B, A
        channels.push_back({plane.name, plane.data, ExrPixelType::Float});
    write_preview(Image(result.film.width(), result.film.height()), channels, path,
                  preview_settings(scene.desc()));
}

}  // namespace kasumi
