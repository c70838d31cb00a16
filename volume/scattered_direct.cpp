#include "volume/scattered_direct.h"

#include "volume/light_cache.h"
#include "volume/transmittance.h"

#include <cmath>

namespace kasumi {

namespace {

/// render.volume.nee_roulette: the smallest probability with which a shadow ray is traced.
constexpr float kNeeSurvivalFloor = 0.1f;

/// nee_survival for the largest phase value p (1/sr) among the media.
float nee_survival_of_phase(float p) {
    return std::min(1.0f, std::max(kNeeSurvivalFloor, 4.0f * kPi * p));
}

/// The probability with which next-event estimation at a scattering event traces its shadow
/// ray (render.volume.nee_roulette): q = min(1, max(kNeeSurvivalFloor, p(mu) / p_iso)), p the
/// largest phase value at cosine mu among the media in `mask` and p_iso = 1/(4 pi) the
/// isotropic one. Russian roulette with the contribution weighted 1/q is unbiased for any q > 0
/// (Arvo & Kirk 1990); the light an event sends toward the eye is sigma_s p(mu) E T, so this
/// q traces every event whose phase sends at least the isotropic share and the others in
/// proportion to it: the shadow rays left out are those whose contributions are small (a
/// front-lit cloud with HG g = 0.8 backscatters with p/p_iso down to 0.06). The floor bounds
/// the variance added where the phase value says little about the transmittance.
float nee_survival(const MediumSet& media, uint32_t mask, float mu) {
    float p = 0.0f;
    for (uint32_t m = mask; m != 0; m &= m - 1)
        p = std::max(p, media.phase_value(static_cast<uint32_t>(__builtin_ctz(m)), mu));
    return nee_survival_of_phase(p);
}

float mean(const Rgb& c) {
    return (c.r + c.g + c.b) * (1.0f / 3.0f);
}

/// Next-event estimation by Russian roulette with survival q: light_term / q or nothing.
Rgb roulette_light_term(float q, const MediumSet& media, const Light& light,
                        const OcclusionQuery* occlusion, const Vec3& x, const IncidentLight& in,
                        const Rgb& f, const VolumeSettings& settings, float step, Pcg32& rng,
                        VolumeCounters& counters) {
    if (q >= 1.0f)
        return light_term(media, light, occlusion, x, in, f, std::nullopt, settings, step, rng,
                          counters);
    if (!(rng.next_float() < q))
        return Rgb(0.0f);
    return light_term(media, light, occlusion, x, in, f, std::nullopt, settings, step, rng,
                      counters) /
           q;
}

}  // namespace

float contribution_survival(float expected, float share) {
    const float q = 4.0f * kPi * expected / share;
    // NaN (a 0/0 path weight) traces: the roulette never decides on an undefined value.
    if (!(q < 1.0f))
        return 1.0f;
    return std::max(kShadowSurvivalFloor, q);
}

bool light_blocked(const OcclusionQuery* occlusion, const Vec3& x, const IncidentLight& in,
                   VolumeCounters& counters) {
    if (occlusion == nullptr)
        return false;
    ++counters.shadow_rays;
    return in.distance >= kInfinity ? occlusion->occluded_direction(x, in.wi)
                                    : occlusion->occluded(x, in.light_position);
}

Rgb light_term(const MediumSet& media, const Light& light, const OcclusionQuery* occlusion,
               const Vec3& x, const IncidentLight& in, const Rgb& f,
               const std::optional<Rgb>& cached, const VolumeSettings& settings, float step,
               Pcg32& rng, VolumeCounters& counters) {
    if (is_black(f) ||
        (light.shadows != ShadowMode::None && light_blocked(occlusion, x, in, counters)))
        return Rgb(0.0f);
    if (cached)
        return f * in.irradiance * *cached;
    const Ray shadow{x, in.wi, 0.0f, in.distance >= kInfinity ? kInfinity : in.distance};
    return f * in.irradiance *
           estimate_transmittance(media, shadow, settings.estimator, step, rng, counters);
}

Rgb scattered_direct_one(const MediumSet& media, const Light& light, size_t light_index,
                         const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                         const Vec3& wo, const VolumeSettings& settings, float step, Pcg32& rng,
                         VolumeCounters& counters, const PointCoefficients* known,
                         float path_weight) {
    // One sample per light: exact for delta lights, unbiased for extended ones (irradiance at
    // normal incidence over the pdf; no cosine inside a medium).
    const IncidentLight in = sample_incident(light, x, rng);
    if (is_black(in.irradiance))
        return Rgb(0.0f);
    const bool one = media_mask != 0 && (media_mask & (media_mask - 1)) == 0;
    const float mu = scattering_cosine(wo, in.wi);
    Rgb f;
    // One medium: its phase value at mu, kept for the roulette (nee_survival would look it up
    // again); negative when not looked up.
    float phase_one = -1.0f;
    if (known != nullptr && one) {
        // MediumSet::scattering(*known, ...) for one medium, no lookup.
        if (is_black(known->sigma_s)) {
            f = Rgb(0.0f);
        } else {
            phase_one = media.phase_value(static_cast<uint32_t>(__builtin_ctz(media_mask)), mu);
            f = known->sigma_s * phase_one;
        }
    } else {
        f = media.scattering(x, media_mask, mu);
        ++counters.density_lookups;
    }
    std::optional<Rgb> cached;
    if (settings.light_cache && !is_black(f)) {
        if (const LightTransmittanceCache* cache = media.light_cache(light_index, light))
            cached = cache->transmittance(x);
    }
    // A cached transmittance costs no walk: no roulette then.
    if (settings.shadow_roulette > 0.0f && !cached && !is_black(f)) {
        if (const LightTransmittanceCache* cache = media.light_cache(light_index, light)) {
            // Outside the lattice is only the grid's rim: taken as lit.
            const Rgb t = cache->transmittance(x).value_or(Rgb(1.0f));
            const float q =
                contribution_survival(path_weight * mean(f * t), settings.shadow_roulette);
            return roulette_light_term(q, media, light, occlusion, x, in, f, settings, step, rng,
                                       counters);
        }
    }
    if (settings.nee_roulette && !cached && !is_black(f)) {
        const float q = phase_one >= 0.0f ? nee_survival_of_phase(std::max(0.0f, phase_one))
                                          : nee_survival(media, media_mask, mu);
        return roulette_light_term(q, media, light, occlusion, x, in, f, settings, step, rng,
                                   counters);
    }
    return light_term(media, light, occlusion, x, in, f, cached, settings, step, rng, counters);
}

Rgb scattered_direct(const MediumSet& media, const std::vector<Light>& lights,
                     const OcclusionQuery* occlusion, const Vec3& x, uint32_t media_mask,
                     const Vec3& wo, const VolumeSettings& settings, Pcg32& rng,
                     VolumeCounters& counters, const PointCoefficients* known, float path_weight) {
    const float step = march_step_m(media, settings);
    Rgb total(0.0f);
    for (size_t light_index = 0; light_index < lights.size(); ++light_index)
        total +=
            scattered_direct_one(media, lights[light_index], light_index, occlusion, x, media_mask,
                                 wo, settings, step, rng, counters, known, path_weight);
    return total;
}

}  // namespace kasumi
