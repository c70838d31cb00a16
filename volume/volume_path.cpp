#include "volume/volume_path.h"

#include "volume/debiased_march_single.h"
#include "volume/march_single.h"
#include "volume/transmittance.h"

namespace kasumi {

VolumeResult integrate_media(const MediumSet& media, const std::vector<Light>& lights,
                             const OcclusionQuery* occlusion, const PathEnvironment* environment,
                             const Ray& ray, const VolumeSettings& settings, bool in_scatter,
                             Pcg32& rng, VolumeCounters& counters, bool nothing_behind,
                             const PathGuiding* guiding) {
    // Emitting media add light along the ray even when nothing scatters.
    in_scatter = in_scatter || media.emits();
    const bool marched_single =
        settings.estimator == Estimator::March && settings.integrator == VolumeIntegrator::Single;
    if (in_scatter && marched_single) {
        if (media.all_homogeneous())
            return integrate_volume(media, lights, occlusion, ray, settings, true, rng, counters);
        return march_single(media, lights, occlusion, ray, settings, rng, counters);
    }
    if (in_scatter && settings.estimator == Estimator::DebiasedMarch &&
        settings.integrator == VolumeIntegrator::Single)
        if (const auto debiased =
                debiased_march_single(media, lights, occlusion, ray, settings, rng, counters))
            return *debiased;
    VolumeResult result;
    if (in_scatter && settings.nee_points > 0) {
        // One walk gives the segment's transmittance and its in-scattering.
        result.radiance =
            tracked_path_radiance(media, lights, occlusion, environment, ray, settings, rng,
                                  counters, &result.transmittance, guiding);
        return result;
    }
    if (in_scatter &&
        (nothing_behind || settings.camera_transmittance == CameraTransmittance::FirstFlight)) {
        // The first free flight's escape weight is an unbiased estimate of T, so no separate
        // walk through the media is needed: with nothing behind T only feeds the AOV; else
        // T L_surface stays unbiased because L_surface was estimated with other random numbers
        // (E[T^ L^] = T L for independent estimates; render.volume.camera_transmittance).
        result.radiance = path_radiance(media, lights, occlusion, environment, ray, settings, rng,
                                        counters, &result.transmittance, guiding);
        return result;
    }
    result.transmittance = estimate_transmittance(media, ray, settings.estimator,
                                                  march_step_m(media, settings), rng, counters);
    if (in_scatter) {
        result.radiance = path_radiance(media, lights, occlusion, environment, ray, settings, rng,
                                        counters, nullptr, guiding);
    }
    return result;
}

}  // namespace kasumi
