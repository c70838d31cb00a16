#include "apps/output_writer.h"

#include "apps/commands.h"
#include "core/color_management.h"
#include "core/error.h"
#include "core/exr_io.h"

#include <filesystem>
#include <sstream>

namespace kasumi {

namespace {

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

}  // namespace

void parse_output_format(const std::string& aovs_text, const std::string& compression_text,
                         uint32_t& aovs, ExrCompression& compression) {
    if (!parse_film_aovs(aovs_text, aovs))
        throw Error(ErrorKind::Usage,
                    "--aovs expects all, none or a comma-separated list of albedo, depth, "
                    "surface, volume, transmittance; got \"" +
                        aovs_text + "\"");
    if (!parse_exr_compression(compression_text, compression))
        throw Error(ErrorKind::Usage, "--compression expects zip, piz, rle or none; got \"" +
                                          compression_text + "\"");
}

ExrWriteReport write_render_outputs(const SceneRuntime& scene, const RenderResult& result,
                                    const OutputPaths& paths, const StageTimes& times) {
    const SceneDesc& desc = scene.desc();
    // The EXR is written straight from the film's planes; `image` carries size and metadata,
    // and R, G, B only if a preview is wanted.
    Image image(result.film.width(), result.film.height());
    const RenderCounters& c = result.counters;
    image.metadata = {
        {"version", version_string()},
        {"scene", desc.file},
        {"spp", std::to_string(desc.film.spp)},
        {"seed", std::to_string(desc.render.seed)},
        {"render_seconds", std::to_string(result.seconds)},
        {"units", "scene-linear Rec.709, luminance in cd/m2"},
        {"interrupted", result.interrupted ? "true" : "false"},
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
    for (auto& kv : stage_metadata(times, scene.plan()))
        image.metadata.push_back(std::move(kv));
    make_parent_dirs(paths.exr);
    std::vector<ExrChannelView> channels;
    for (const FilmPlane& plane : result.film.planes(paths.aovs)) {
        // The first four planes are R, G, B, A (Film::planes); AOVs stay float.
        channels.push_back({plane.name, plane.data,
                            channels.size() < 4 ? desc.film.pixel_type : ExrPixelType::Float});
    }
    // Compressed with the render's own thread count (--threads 1: on this thread alone).
    const ExrWriteReport report =
        write_exr(image, channels, paths.exr, paths.compression, result.threads);
    if (!paths.preview.empty()) {
        const size_t pixels = static_cast<size_t>(image.width) * image.height;
        for (size_t i = 0; i < 3; ++i) {  // R, G, B
            const float* from = channels[i].data;
            image.channels.push_back({channels[i].name, std::vector<float>(from, from + pixels)});
        }
        make_parent_dirs(paths.preview);
        PreviewSettings preview;
        preview.config_path = default_ocio_config_path();
        preview.view = desc.render.preview.view;
        preview.exposure_stops = desc.render.preview.exposure_stops;
        write_preview_png(image, paths.preview, preview);
    }
    return report;
}

std::string format_write_stats(const SceneRuntime& scene, const ExrWriteReport& report) {
    std::ostringstream out;
    const ExrPixelType type = scene.desc().film.pixel_type;
    out << "  exr pixel type      " << exr_pixel_type_name(type) << " (R, G, B, A)\n";
    if (type == ExrPixelType::Half) {
        out << "  half saturated      " << report.half_saturated << " (|value| > 65504, written as "
            << "65504; largest |value| " << report.half_max_abs << ")\n";
        out << "  half flushed to 0   " << report.half_flushed_to_zero
            << " (non-zero |value| < 2^-25)\n";
    }
    return out.str();
}

std::string half_saturation_warning(const ExrWriteReport& report, const std::string& path) {
    if (report.half_saturated == 0)
        return "";
    std::ostringstream out;
    out << "kasumi: warning: " << path << ": " << report.half_saturated
        << " values of R, G, B, A exceed the half-float range (largest " << report.half_max_abs
        << ") and were written as 65504; --pixel-type float keeps them\n";
    return out.str();
}

std::string format_stats(const SceneRuntime& scene, const RenderResult& result,
                         const StageTimes& times) {
    const RenderCounters& c = result.counters;
    std::ostringstream out;
    out << "plan:\n" << plan_to_text(scene.plan());
    out << "stats:\n";
    out << format_stage_times(times);
    out << "  skipped stages      " << skipped_stage_names(scene.plan()) << "\n";
    out << "  time                " << result.seconds << " s\n";
    out << "  camera rays         " << c.camera_rays << "\n";
    out << "  surface hits        " << c.surface_hits << "\n";
    out << "  surface shadow rays " << c.surface_shadow_rays << "\n";
    out << "  shadow rays avoided " << c.shadow_rays_avoided << " (shadow photons)\n";
    out << "  volume rays         " << c.volume_rays << "\n";
    out << "  volume steps        " << c.volume_steps << "\n";
    out << "  volume shadow rays  " << c.volume_shadow_rays << "\n";
    out << "  bvh built           " << (scene.surfaces() != nullptr ? "yes" : "no") << "\n";
    if (scene.gi() != nullptr)
        out << "  global illumination " << scene.gi()->summary() << "\n";
    out << "  non-finite samples  " << c.nonfinite_samples << "\n";
    out << "  density lookups     " << c.density_lookups << "\n";
    out << "  transmittance rays  " << c.transmittance_rays << "\n";
    out << "  free flights        " << c.free_flights << "\n";
    out << "  scattering events   " << c.scattering_events << "\n";
    out << "  bounded marches     " << c.bounded_marches
        << " (step lengthened to 1/65536 of the way)\n";
    const RenderRates r = render_rates(c, result.seconds, result.threads);
    out << "  threads             " << result.threads << "\n";
    out << "  lookups/s/core      " << r.density_lookups_per_s_per_core << "\n";
    out << "  camera rays/s       " << r.camera_rays_per_s << "\n";
    out << "  all rays/s          " << r.all_rays_per_s
        << " (camera + transmittance + free flights)\n";
    return out.str();
}

}  // namespace kasumi
