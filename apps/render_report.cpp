#include "apps/render_report.h"

#include <sstream>

namespace kasumi {

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
