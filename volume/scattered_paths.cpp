#include "volume/scattered_paths.h"

#include "volume/decomposition_tracking.h"
#include "volume/guiding/guided_scattering.h"
#include "volume/scattered_direct.h"
#include "volume/spectral_mis_flight.h"
#include "volume/transmittance.h"
#include "volume/weight_window.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

/// Paths play Russian roulette from this many scattering events on.
constexpr int kRouletteDepth = 3;

/// render.volume.splitting "guided": at most this many window copies wait per camera path.
constexpr size_t kMaxWaitingCopies = 64;

/// The next path vertex after a scattering event at `position`: a direction from the media's
/// phase mixture, or, where `guiding` has a guide for the point (one medium there), from the
/// guided mixture (volume/guiding/guided_scattering.h); throughput times f / pdf, Russian
/// roulette from kRouletteDepth events on (unless `roulette` is false: the weight window plays
/// it), and the continued ray (ended at the environment's surface). The vertex goes to
/// `recorder`. False: the path ends.
bool scatter_onward(const MediumSet& media, const Vec3& position, uint32_t mask,
                    const PointCoefficients& k, const Vec3& wo, int depth,
                    const PathEnvironment* environment, const PathGuiding* guiding,
                    GuidingPathRecorder& recorder, Pcg32& rng, Rgb& throughput, Ray& ray,
                    bool roulette = true) {
    const DirectionalHistogram* guide = nullptr;
    if (guiding != nullptr && guiding->field != nullptr && mask != 0 && (mask & (mask - 1)) == 0)
        guide = guiding->field->find(position);
    const float u_pick = rng.next_float();
    const Vec2 u = rng.next_vec2();
    const MixtureSample next =
        guide != nullptr
            ? sample_guided_scattering(media, static_cast<uint32_t>(__builtin_ctz(mask)), *guide,
                                       guiding->mix, k, wo, u_pick, u)
            : media.sample_scattering(position, mask, wo, u_pick, u, &k);
    if (!(next.pdf > 0.0f))
        return false;
    throughput *= next.scattering / next.pdf;
    recorder.vertex(position, next.wi, next.pdf, throughput);
    if (roulette && depth >= kRouletteDepth) {
        const float survive = std::min(1.0f, max_component(throughput));
        if (!(rng.next_float() < survive))
            return false;
        throughput /= survive;
    }
    ray = Ray{position, next.wi, 0.0f, kInfinity};
    if (environment != nullptr)
        ray.t_max = environment->surface_distance(ray);
    return true;
}

/// A free flight by spectral MIS where render.volume.spectral_mis asks for it and the media are
/// chromatic, else by decomposition tracking where render.volume.free_flight asks for it, else
/// by spectral tracking: the same contract (FreeFlight), all unbiased.
FreeFlight free_flight(const MediumSet& media, const Ray& ray, const Rgb& throughput,
                       const VolumeSettings& settings, Pcg32& rng, VolumeCounters& counters) {
    if (settings.spectral_mis && !media.grey_extinction())
        return sample_free_flight_spectral_mis(media, ray, throughput, rng, counters);
    if (settings.free_flight == FreeFlightSampling::Decomposition)
        return sample_free_flight_decomposition(media, ray, throughput, rng, counters);
    return sample_free_flight(media, ray, throughput, rng, counters);
}

float mean(const Rgb& c) {
    return (c.r + c.g + c.b) * (1.0f / 3.0f);
}

/// The guiding a path's directions follow: `guiding` when render.volume.guiding is on; else a
/// copy in `storage` without the field (which may exist for the "guided" window alone) and
/// with the same records.
const PathGuiding* direction_guiding(const PathGuiding* guiding, const VolumeSettings& settings,
                                     PathGuiding& storage) {
    if (guiding == nullptr || settings.guiding.enabled)
        return guiding;
    storage = *guiding;
    storage.field = nullptr;
    return &storage;
}

/// A scattering vertex whose continuation waits: a copy made by the weight window.
struct PendingVertex {
    Vec3 position{0.0f};
    uint32_t mask = 0;
    PointCoefficients k;
    Vec3 wo{0.0f};
    int depth = 0;
    Rgb throughput{0.0f};
};

}  // namespace

Rgb path_radiance(const MediumSet& media, const std::vector<Light>& lights,
                  const OcclusionQuery* occlusion, const PathEnvironment* environment,
                  const Ray& camera_segment, const VolumeSettings& settings, Pcg32& rng,
                  VolumeCounters& counters, Rgb* first_escape, const PathGuiding* guiding) {
    Rgb radiance(0.0f), throughput(1.0f);
    GuidingPathRecorder recorder(guiding);
    const auto gather = [&](const Rgb& contribution) {
        radiance += contribution;
        recorder.add(contribution);
    };
    // Training paths stay single (one record chain per path): the window runs when rendering.
    const bool rendering = guiding == nullptr || guiding->records == nullptr;
    const bool multiple = settings.integrator == VolumeIntegrator::Multiple;
    const GuidingField* learnt =
        settings.splitting == PathSplitting::Guided && multiple && rendering && guiding != nullptr
            ? guiding->field
            : nullptr;
    const bool window =
        (settings.splitting == PathSplitting::Sun && multiple && rendering) || learnt != nullptr;
    PathGuiding steer;
    const PathGuiding* directions = direction_guiding(guiding, settings, steer);
    // The copies the window made wait here; a nested call (the environment's own paths) works
    // above `base` and leaves the stack as it found it.
    thread_local std::vector<PendingVertex> pending;
    const size_t base = pending.size();
    // "guided": centred on the pixel's training estimate when the segment is a camera ray;
    // otherwise (and for "sun") on the path's expected contribution at its first vertex.
    float window_centre = learnt != nullptr ? learnt->pixel_estimates().at(camera_segment) : 0.0f;
    if (!(window_centre > 0.0f) || !std::isfinite(window_centre))
        window_centre = 0.0f;
    Ray ray = camera_segment;
    int depth = 0;
    // Continues the next waiting copy, if any, by its own direction; false: none is left.
    const auto resume = [&] {
        while (pending.size() > base) {
            const PendingVertex v = pending.back();
            pending.pop_back();
            throughput = v.throughput;
            depth = v.depth;
            if (scatter_onward(media, v.position, v.mask, v.k, v.wo, depth, environment, directions,
                               recorder, rng, throughput, ray, false))
                return true;
        }
        return false;
    };
    for (;;) {
        const FreeFlight flight = free_flight(media, ray, throughput, settings, rng, counters);
        gather(flight.emitted);
        throughput *= flight.weight;
        if (depth == 0 && first_escape != nullptr)
            *first_escape = flight.scattered ? Rgb(0.0f) : flight.weight;
        if (!flight.scattered) {
            // The camera segment's own escape is composited by the caller (T * L_surface).
            if (depth > 0 && environment != nullptr && !is_black(throughput))
                gather(throughput * environment->radiance(ray, rng));
            if (resume())
                continue;
            break;
        }
        ++counters.scattering_events;
        const Vec3 wo = -ray.direction;
        gather(throughput * scattered_direct(media, lights, occlusion, flight.position,
                                             flight.media_mask, wo, settings, rng, counters,
                                             &flight.k, mean(throughput)));
        if (settings.integrator == VolumeIntegrator::Single || ++depth >= settings.max_depth) {
            if (resume())
                continue;
            break;
        }
        if (window) {
            // Expected contribution beta I(x) against the window's centre.
            const float expected =
                learnt != nullptr
                    ? guided_expected(*learnt, flight.position, wo, mean(flight.k.sigma_s),
                                      mean(throughput))
                    : mean(throughput) * sun_importance(media, lights, flight.position);
            if (!(window_centre > 0.0f) && expected > 0.0f && std::isfinite(expected))
                window_centre = expected;
            float q = learnt != nullptr ? window_ratio(expected, window_centre)
                                        : expected / window_centre;
            // "guided": no splits while kMaxWaitingCopies copies wait (q decided from the past
            // alone, so still unbiased): a field that underestimates I somewhere can otherwise
            // roulette paths to large weights that split again and again.
            if (learnt != nullptr && pending.size() - base >= kMaxWaitingCopies)
                q = std::min(q, 1.0f);
            const SplitDecision split = split_decision(q, rng.next_float());
            throughput *= split.weight;
            for (int c = 1; c < split.copies; ++c)
                pending.push_back(
                    {flight.position, flight.media_mask, flight.k, wo, depth, throughput});
            if (split.copies == 0) {
                if (resume())
                    continue;
                break;
            }
        }
        if (!scatter_onward(media, flight.position, flight.media_mask, flight.k, wo, depth,
                            environment, directions, recorder, rng, throughput, ray, !window)) {
            if (resume())
                continue;
            break;
        }
    }
    return radiance;
}

Rgb tracked_path_radiance(const MediumSet& media, const std::vector<Light>& lights,
                          const OcclusionQuery* occlusion, const PathEnvironment* environment,
                          const Ray& camera_segment, const VolumeSettings& settings, Pcg32& rng,
                          VolumeCounters& counters, Rgb* first_escape, const PathGuiding* guiding) {
    thread_local std::vector<TrackedCollision> points;
    const float k = static_cast<float>(settings.nee_points);
    const bool emits = media.emits();
    Rgb radiance(0.0f), throughput(1.0f);
    GuidingPathRecorder recorder(guiding);
    const auto gather = [&](const Rgb& contribution) {
        radiance += contribution;
        recorder.add(contribution);
    };
    PathGuiding steer;
    const PathGuiding* directions = direction_guiding(guiding, settings, steer);
    Ray ray = camera_segment;
    for (int depth = 0;;) {
        const bool last =
            settings.integrator == VolumeIntegrator::Single || depth + 1 >= settings.max_depth;
        const TrackedWalk walk =
            track_collisions(media, ray, last ? nullptr : &throughput, rng, counters, points);
        if (depth == 0 && first_escape != nullptr)
            *first_escape = walk.transmittance;
        float total = 0.0f;
        for (const TrackedCollision& p : points) {
            if (emits)
                gather(throughput * p.weight * media.emission(p.position, p.media_mask));
            total += std::max(0.0f, mean(throughput * p.weight * p.k.sigma_s));
        }
        const Vec3 wo = -ray.direction;
        if (total > 0.0f) {
            // Systematic sampling: picks at u + j (j = 0, 1, ...) in the running sum of k c_i.
            float next_pick = rng.next_float(), running = 0.0f;
            for (const TrackedCollision& p : points) {
                const float share = mean(throughput * p.weight * p.k.sigma_s);
                if (!(share > 0.0f))
                    continue;
                running += k * share;
                while (next_pick < running) {
                    next_pick += 1.0f;
                    ++counters.scattering_events;
                    const Rgb pick_weight = throughput * p.weight / (k * share);
                    gather(pick_weight * scattered_direct(media, lights, occlusion, p.position,
                                                          p.media_mask, wo, settings, rng, counters,
                                                          &p.k, mean(pick_weight)));
                }
            }
        }
        if (last) {
            // No flight on the last segment: T^ stands for its escape.
            if (depth > 0 && environment != nullptr && !is_black(throughput * walk.transmittance))
                gather(throughput * walk.transmittance * environment->radiance(ray, rng));
            break;
        }
        // The next vertex: the free flight drawn on the walk's collisions, continued past a
        // roulette stop by an ordinary free flight (memoryless: the same distribution).
        // A flight that leaves the media adds what it meets there (the camera segment's own
        // escape is composited by the caller, T * L_surface), as path_radiance does.
        Vec3 position;
        uint32_t mask = 0;
        PointCoefficients k_here;
        Rgb flight_weight = walk.flight_weight;
        bool scattered = walk.scatter >= 0;
        if (scattered) {
            position = points[static_cast<size_t>(walk.scatter)].position;
            mask = points[static_cast<size_t>(walk.scatter)].media_mask;
            k_here = points[static_cast<size_t>(walk.scatter)].k;
        } else if (walk.flight_open) {
            Ray rest = ray;
            rest.t_min = walk.stopped_at;
            const FreeFlight flight =
                free_flight(media, rest, throughput * flight_weight, settings, rng, counters);
            flight_weight *= flight.weight;
            scattered = flight.scattered;
            position = flight.position;
            mask = flight.media_mask;
            k_here = flight.k;
        }
        if (!scattered) {
            if (depth > 0 && environment != nullptr && !is_black(throughput * flight_weight))
                gather(throughput * flight_weight * environment->radiance(ray, rng));
            break;
        }
        ++depth;
        throughput *= flight_weight;
        if (!scatter_onward(media, position, mask, k_here, wo, depth, environment, directions,
                            recorder, rng, throughput, ray))
            break;
    }
    return radiance;
}

}  // namespace kasumi
