#include "render/sky_shafts.h"

#include "sky/sky_reference.h"
#include "sky/sun_through_air.h"
#include "volume/transmittance.h"

#include <algorithm>
#include <vector>

namespace kasumi {

namespace {

bool any_positive(const Bands& b, int n) {
    for (int i = 0; i < n; ++i) {
        if (b[i] > 0.0)
            return true;
    }
    return false;
}

}  // namespace

Rgb shadowed_sun_scattering(const SceneRuntime& scene, const Ray& ray, float t_end, Pcg32& rng,
                            RenderCounters& counters) {
    const SkyRenderer* renderer = scene.sky();
    if (renderer == nullptr || !renderer->sky().settings.shafts)
        return Rgb(0.0f);
    const SkyScene& sky = renderer->sky();
    const Atmosphere& a = sky.atmosphere;
    const SkySettings& settings = sky.settings;
    const DVec3 p(ray.origin);
    const DVec3 d = glm::normalize(DVec3(ray.direction));
    double t_enter = 0.0, t_exit = 0.0;
    bool ground = false;
    if (!atmosphere_segment(a, p, d, t_enter, t_exit, ground))
        return Rgb(0.0f);
    const double lo = std::max(t_enter, static_cast<double>(ray.t_min));
    const double hi = std::min({t_exit, static_cast<double>(t_end), settings.shaft_distance_m});
    if (!(hi > lo))
        return Rgb(0.0f);
    // The sun set for the whole segment (it is short against the Earth's curvature): nothing
    // to shadow.
    if (!any_positive(sun_transmittance_at(*renderer, p + 0.5 * (lo + hi) * d), a.bands))
        return Rgb(0.0f);

    const int n = settings.shaft_samples;
    const double stratum = (hi - lo) / n;
    const Vec3 to_sun(sky.sun_direction);
    const bool surfaces = scene.occlusion() != nullptr;
    const bool media = scene.plan().volume;
    const VolumeSettings& volume = scene.desc().render.volume;
    const float step = media ? march_step_m(scene.media(), volume) : 0.0f;

    // Visibility first: where every node sees the sun there is nothing to subtract and the
    // atmosphere is not evaluated.
    std::vector<double> s(static_cast<size_t>(n));
    std::vector<Rgb> hidden(static_cast<size_t>(n), Rgb(0.0f));  // 1 - V per node
    bool any_hidden = false;
    for (int k = 0; k < n; ++k) {
        const size_t i = static_cast<size_t>(k);
        s[i] = lo + (k + static_cast<double>(rng.next_float())) * stratum;
        const Vec3 x(p + s[i] * d);
        if (surfaces) {
            ++counters.surface_shadow_rays;
            if (scene.occlusion()->occluded_direction(x, to_sun)) {
                hidden[i] = Rgb(1.0f);
                any_hidden = true;
                continue;
            }
        }
        if (media) {
            VolumeCounters vc;
            const Rgb t = estimate_transmittance(scene.media(), Ray{x, to_sun, 0.0f, kInfinity},
                                                 volume.estimator, step, rng, vc);
            counters.density_lookups += vc.density_lookups;
            counters.transmittance_rays += vc.transmittance_estimates;
            hidden[i] = glm::clamp(Rgb(1.0f) - t, Rgb(0.0f), Rgb(1.0f));
            any_hidden = any_hidden || max_component(hidden[i]) > 0.0f;
        }
    }
    if (!any_hidden)
        return Rgb(0.0f);

    const double mu = glm::dot(d, sky.sun_direction);
    Bands p_rayleigh{};
    rayleigh_phase_bands(a, mu, p_rayleigh);
    const double p_mie = eval_precise(a.mie_phase, mu);
    const auto altitude = [&](double t) { return a.radius(p + t * d) - a.ground_radius_m; };
    Bands tau{};  // optical depth of the air from lo to the current node
    double previous = lo;
    glm::dvec3 sum(0.0);
    for (int k = 0; k < n; ++k) {
        const size_t i = static_cast<size_t>(k);
        // Midpoint rule between consecutive nodes for the optical depth from the camera.
        const AtmosphereCoefficients between =
            atmosphere_coefficients(a, altitude(0.5 * (previous + s[i])));
        for (int b = 0; b < a.bands; ++b)
            tau[b] += between.sigma_t[b] * (s[i] - previous);
        previous = s[i];
        if (max_component(hidden[i]) <= 0.0f)
            continue;
        const DVec3 x = p + s[i] * d;
        const AtmosphereCoefficients c = atmosphere_coefficients(a, altitude(s[i]));
        const Bands t_sun = sun_transmittance_at(*renderer, x);
        Bands scattered{};
        for (int b = 0; b < a.bands; ++b) {
            scattered[b] = stratum * std::exp(-tau[b]) *
                           (c.sigma_s_rayleigh[b] * p_rayleigh[b] + c.sigma_s_mie[b] * p_mie) *
                           t_sun[b];
        }
        sum += glm::dvec3(sky.to_rgb(scattered)) * glm::dvec3(hidden[i]);
    }
    return Rgb(sum);
}

void apply_sky_shafts(const SceneRuntime& scene, const Ray& ray, float t_end, Pcg32& rng,
                      PixelSample& sample, RenderCounters& counters) {
    const Rgb shadowed = shadowed_sun_scattering(scene, ray, t_end, rng, counters);
    if (is_black(shadowed))
        return;
    sample.radiance = glm::max(sample.radiance - shadowed, Rgb(0.0f));
    sample.volume = glm::max(sample.volume - shadowed, Rgb(0.0f));
}

}  // namespace kasumi
