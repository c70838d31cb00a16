#include "render/air_and_media.h"

#include "render/integrator.h"
#include "render/sky_shafts.h"
#include "sky/sun_through_air.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace kasumi {

namespace {

constexpr double kMinPieceM = 250.0;    ///< shortest piece of the media's extent
constexpr double kPieceGrowth = 0.125;  ///< pieces lengthen with distance like the air's table
constexpr int kMaxPieces = 24;
constexpr float kRouletteBelow = 0.05f;  ///< media transmittance under which roulette starts

/// g(x) = (1 - e^{-x}) / x: the mean transmittance over a homogeneous stretch of optical depth
/// x; 1 at 0 (expm1 avoids the cancellation of 1 - e^{-x} there), 0 at +inf.
float mean_transmittance(float tau) {
    if (!(tau < kInfinity))
        return 0.0f;
    if (std::abs(tau) < 1e-6f)
        return 1.0f - 0.5f * tau;
    return -std::expm1(-tau) / tau;
}

/// -ln T (+inf for T = 0).
float optical_depth_of(float t) {
    return t > 0.0f ? -std::log(t) : kInfinity;
}

/// The shares of the air's and the media's own light in a piece where the two are mixed
/// homogeneously (render/air_and_media.h), per channel, from their transmittances over it.
void mixture_shares(const Rgb& t_air, const Rgb& t_media, Rgb& air_share, Rgb& media_share) {
    for (int c = 0; c < 3; ++c) {
        const float tau_a = optical_depth_of(t_air[c]), tau_m = optical_depth_of(t_media[c]);
        if (!(tau_m < kInfinity) && !(tau_a < kInfinity)) {
            air_share[c] = media_share[c] = 0.5f;  // both opaque: neither is behind the other
        } else if (!(tau_m < kInfinity)) {
            air_share[c] = 0.0f;
            media_share[c] = 1.0f;
        } else if (!(tau_a < kInfinity)) {
            air_share[c] = 1.0f;
            media_share[c] = 0.0f;
        } else {
            const float both = mean_transmittance(tau_a + tau_m);
            air_share[c] = both / mean_transmittance(tau_a);
            media_share[c] = both / mean_transmittance(tau_m);
        }
    }
}

/// The air along one camera ray, advanced piece by piece: the light it sends to the camera
/// from [a, b] (attenuated by the air in front, cd/m²) and T_air(0, b). Fast mode reads the
/// camera-referenced values L_air(0, t) (the table, or the march past it: deterministic, so
/// differences are exact); reference mode marches each piece from its start (its Monte Carlo
/// orders would make differences of two estimates noisy).
class AirAlongRay {
  public:
    AirAlongRay(const SkyRenderer& sky, const Ray& ray, Pcg32& rng)
        : m_sky(sky), m_ray(ray), m_rng(rng), m_cumulative(sky.luts() != nullptr) {}

    /// T_air(0, t) at the current end t.
    const Rgb& transmittance() const { return m_transmittance; }

    /// Moves the end to b (>= the current end); returns the air's light from the step.
    Rgb advance(double b) {
        if (!(b > m_t))
            return Rgb(0.0f);
        Rgb radiance(0.0f), transmittance(1.0f);
        Rgb step(0.0f);
        if (m_cumulative) {
            m_sky.aerial_perspective(m_ray, static_cast<float>(b), m_rng, radiance, transmittance);
            step = radiance - m_radiance;
            m_radiance = radiance;
            m_transmittance = transmittance;
        } else {
            const Ray piece{m_ray.at(static_cast<float>(m_t)), m_ray.direction, 0.0f, kInfinity};
            m_sky.aerial_perspective(piece, static_cast<float>(b - m_t), m_rng, radiance,
                                     transmittance);
            step = m_transmittance * radiance;
            m_transmittance *= transmittance;
        }
        m_t = b;
        return step;
    }

  private:
    const SkyRenderer& m_sky;
    const Ray& m_ray;
    Pcg32& m_rng;
    const bool m_cumulative;
    double m_t = 0.0;
    Rgb m_radiance{0.0f};  ///< L_air(0, m_t) (cumulative mode)
    Rgb m_transmittance{1.0f};
};

/// The air's light over [a, b] less its shadowed single scattering (render/sky_shafts.h),
/// both referred to the camera; `t_a` = T_air(0, a). Clamped at 0 as apply_sky_shafts is (two
/// quadratures of the same integral).
Rgb unshadowed_air(const SceneRuntime& scene, const Ray& ray, double a, double b,
                   const Rgb& air_light, const Rgb& t_a, Pcg32& rng, RenderCounters& counters) {
    const Ray from_a{ray.origin, ray.direction, static_cast<float>(a), kInfinity};
    const Rgb shadowed =
        shadowed_sun_scattering(scene, from_a, static_cast<float>(b), rng, counters);
    if (is_black(shadowed))
        return air_light;
    return glm::max(air_light - t_a * shadowed, Rgb(0.0f));
}

}  // namespace

void compose_air_and_media(const SceneRuntime& scene, const Ray& ray, float t_end, Pcg32& rng,
                           RenderCounters& counters, const PathGuiding* guiding,
                           PixelSample& sample) {
    const SkyRenderer& sky = *scene.sky();
    thread_local std::vector<MajorantSegment> majorants;
    scene.media().majorants(Ray{ray.origin, ray.direction, ray.t_min, t_end}, majorants);
    const auto non_empty = [](const MajorantSegment& s) {
        return max_component(s.sigma_max) > 0.0f;
    };
    const auto first = std::find_if(majorants.begin(), majorants.end(), non_empty);
    if (first == majorants.end()) {
        // No media on this ray: exactly the composition of a scene without media.
        sample.radiance = sample.surface;
        sample.volume = Rgb(0.0f);
        sample.transmittance = Rgb(1.0f);
        sky.apply(ray, t_end, rng, sample);
        apply_sky_shafts(scene, ray, t_end, rng, sample, counters);
        return;
    }
    const auto last = std::find_if(majorants.rbegin(), majorants.rend(), non_empty);
    const double t_in = first->t0;
    const double t_media_end = last->t1;
    // The pieces stop where the air does: at the surface, else at the atmosphere's end (or the
    // planet's ground); media beyond it are integrated in the last piece.
    double t_air_end = t_end;
    if (!(t_end < kInfinity)) {
        double t0 = 0.0, t1 = 0.0;
        bool ground = false;
        t_air_end = atmosphere_segment(sky.sky().atmosphere, DVec3(ray.origin),
                                       glm::normalize(DVec3(ray.direction)), t0, t1, ground)
                        ? t1
                        : t_in;
    }
    const double t_out = std::max(t_in, std::min(t_media_end, t_air_end));

    // The scene's lights, with the sun's illuminance replaced piece by piece.
    thread_local std::vector<Light> lights;
    lights = scene.desc().lights;
    const std::optional<size_t> sun = find_sun_light(sky.sky(), lights);

    AirAlongRay air(sky, ray, rng);
    Rgb volume =
        unshadowed_air(scene, ray, ray.t_min, t_in, air.advance(t_in), Rgb(1.0f), rng, counters);
    Rgb media_transmittance(1.0f);  // M_k
    double a = t_in;
    for (int k = 0; k < kMaxPieces && a < t_out; ++k) {
        double b = std::min(t_out, a + std::max(kMinPieceM, kPieceGrowth * a));
        if (k == kMaxPieces - 1 || t_out - b < 0.5 * kMinPieceM)
            b = t_out;
        const Vec3 middle = ray.at(static_cast<float>(0.5 * (a + b)));
        if (sun) {
            std::get<DirectionalLight>(lights[*sun].emitter).illuminance =
                sun_illuminance_at(sky, DVec3(middle));
        }
        const float media_end = static_cast<float>(b < t_out ? b : std::max(b, t_media_end));
        const VolumeResult media = trace_volume_segment(
            scene, Ray{ray.origin, ray.direction, static_cast<float>(a), media_end}, rng, counters,
            guiding, &lights);
        const Rgb t_a = air.transmittance();
        const Rgb air_light = unshadowed_air(scene, ray, a, b, air.advance(b), t_a, rng, counters);
        const Rgb t_b = air.transmittance();
        Rgb t_air_piece(1.0f);
        for (int c = 0; c < 3; ++c)
            t_air_piece[c] = t_a[c] > 0.0f ? t_b[c] / t_a[c] : 1.0f;
        Rgb air_share(1.0f), media_share(1.0f);
        mixture_shares(t_air_piece, media.transmittance, air_share, media_share);
        volume +=
            media_transmittance * (air_share * air_light + t_a * media_share * media.radiance);
        media_transmittance *= media.transmittance;
        a = b;
        const float m = max_component(media_transmittance);
        if (!(m > 0.0f))
            break;
        if (m < kRouletteBelow) {
            const float survive = m / kRouletteBelow;
            if (rng.next_float() >= survive) {
                media_transmittance = Rgb(0.0f);
                break;
            }
            media_transmittance /= survive;
        }
    }

    if (is_black(media_transmittance)) {
        // Nothing behind the media reaches the camera.
        sample.transmittance = Rgb(0.0f);
    } else if (sample.hit) {
        const Rgb t_a = air.transmittance();
        volume += media_transmittance *
                  unshadowed_air(scene, ray, t_out, t_end, air.advance(t_end), t_a, rng, counters);
        sample.transmittance = media_transmittance * air.transmittance();
    } else {
        // The sky beyond the media: the rest of the air, the planet's ground and the sun's disc
        // seen from where the media end (within SkyRenderer::kEnvironmentNearM of the camera,
        // the camera's own sky view: the same sky as the pixels beside the media, at the cost
        // of counting up to 100 m of air twice).
        sample.surface =
            sky.environment(Ray{ray.at(static_cast<float>(t_out)), ray.direction, 0.0f, kInfinity},
                            /*sun_disc=*/true, rng);
        sample.transmittance = media_transmittance * air.transmittance();
    }
    sample.volume = volume;
    sample.radiance = volume + sample.transmittance * sample.surface;
}

}  // namespace kasumi
