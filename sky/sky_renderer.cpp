#include "sky/sky_renderer.h"

#include "sky/atmosphere_json.h"
#include "sky/sky_reference.h"

#include <tbb/parallel_for.h>

namespace kasumi {

SkyRenderer::SkyRenderer(std::shared_ptr<const SkyScene> sky, const Vec3& camera_world,
                         std::shared_ptr<const SkyLuts> tables,
                         const std::optional<ViewFrustum>& frustum)
    : m_sky(std::move(sky)), m_camera(DVec3(camera_world)) {
    Bands ones{};
    for (int i = 0; i < m_sky->bands(); ++i)
        ones[i] = 1.0;
    m_white = m_sky->to_rgb(ones);
    if (m_sky->settings.mode == SkyMode::Fast) {
        m_tables_reused = tables != nullptr;
        m_tables = m_tables_reused ? std::move(tables) : std::make_shared<const SkyLuts>(*m_sky);
        m_luts = std::make_unique<SkyLuts>(*m_tables);  // shares the tables
        m_luts->build_sky_view(*m_sky, m_camera);
        if (frustum && m_sky->settings.aerial_table)
            m_aerial = std::make_unique<AerialPerspective>(*m_sky, *m_luts, *frustum, m_white);
    }
    build_irradiance();
}

Bands SkyRenderer::radiance_bands(const DVec3& p, const DVec3& d, double t_max, bool sun_disc,
                                  Pcg32& rng, Bands* transmittance_out) const {
    const SkyScene& sky = *m_sky;
    if (m_luts == nullptr) {
        const SkySample s = reference_sky(sky, p, d, t_max, sun_disc, sky.settings.orders, rng);
        if (transmittance_out != nullptr)
            *transmittance_out = s.transmittance;
        return s.radiance;
    }
    Bands radiance{}, t{};
    const double cos_sun = glm::dot(d, sky.sun_direction);
    const bool in_disc = sun_disc && cos_sun >= sky.sun_cos_radius;
    const bool from_camera = glm::length(p - m_camera) < 1e-3;
    if (from_camera && t_max >= 1e29) {
        m_luts->sky_view(sky, d, radiance);
        // The transmittance is needed only for the caller or behind the sun's disc.
        const bool need_t = transmittance_out != nullptr || in_disc;
        double t0 = 0.0, t1 = 0.0;
        bool ground = false;
        if (!need_t) {
            // t stays 0: the disc term below adds nothing.
        } else if (!atmosphere_segment(sky.atmosphere, p, d, t0, t1, ground)) {
            for (int i = 0; i < sky.bands(); ++i)
                t[i] = 1.0;
        } else if (!ground) {
            const double r = sky.atmosphere.radius(p + t0 * d);
            const DVec3 up = glm::normalize(p + t0 * d - sky.atmosphere.center());
            m_luts->transmittance(r, glm::dot(up, d), t);
        }
    } else {
        // Short segments (aerial perspective over a scene) need few nodes: the air changes
        // little over 250 m; open rays take 24.
        const int steps =
            t_max >= 1e29 ? 24 : std::clamp(static_cast<int>(2.0 + t_max / 250.0), 2, 24);
        m_luts->march(sky, p, d, t_max, steps, radiance, t);
    }
    // The disc adds nothing outside its radius (sun_disc is 0 there): no per-pixel spectrum.
    if (in_disc) {
        const Bands disc = sky.sun_disc(cos_sun);
        for (int i = 0; i < sky.bands(); ++i)
            radiance[i] += t[i] * disc[i];
    }
    if (transmittance_out != nullptr)
        *transmittance_out = t;
    return radiance;
}

Rgb SkyRenderer::background(const Ray& ray, Pcg32& rng) const {
    const Bands l = radiance_bands(DVec3(ray.origin), glm::normalize(DVec3(ray.direction)), 1e30,
                                   true, rng, nullptr);
    return m_sky->to_rgb(l);
}

Rgb SkyRenderer::environment(const Ray& ray, bool sun_disc, Pcg32& rng) const {
    const DVec3 origin(ray.origin);
    const DVec3 p = glm::length(origin - m_camera) <= kEnvironmentNearM ? m_camera : origin;
    return m_sky->to_rgb(
        radiance_bands(p, glm::normalize(DVec3(ray.direction)), 1e30, sun_disc, rng, nullptr));
}

Rgb SkyRenderer::transmittance_rgb(const Bands& t) const {
    const Rgb v = m_sky->to_rgb(t);
    return Rgb(m_white.r > 0 ? v.r / m_white.r : 1.0f, m_white.g > 0 ? v.g / m_white.g : 1.0f,
               m_white.b > 0 ? v.b / m_white.b : 1.0f);
}

void SkyRenderer::aerial_perspective(const Ray& ray, float t, Pcg32& rng, Rgb& radiance,
                                     Rgb& transmittance_out) const {
    Bands tb{};
    const DVec3 p(ray.origin), d = glm::normalize(DVec3(ray.direction));
    // A surface ends the segment, so the planet's ground is not seen even where the scene's
    // ground coincides with it: a quad at y = 0 touches the planet at the origin, and a hit
    // rounded to float can lie at or past the planet's surface (which would add the ground's
    // radiance and make the air opaque). Stop just short of the planet there.
    double t_air = static_cast<double>(t);
    double t0 = 0.0, t1 = 0.0;
    bool ground = false;
    if (atmosphere_segment(m_sky->atmosphere, p, d, t0, t1, ground) && ground)
        t_air = std::min(t_air, t1 * (1.0 - 1e-6));
    if (m_aerial != nullptr && glm::length(p - m_aerial->frustum().origin) < 1e-3 &&
        m_aerial->lookup(d, t_air, radiance, transmittance_out)) {
        constexpr double kDepth = AerialPerspective::kDepthM;
        if (t_air > kDepth) {
            // Beyond the table: march the rest from its far end and compose (continuous at
            // 32 km: the marched part starts from zero).
            Bands lb{};
            m_luts->march(*m_sky, p + kDepth * d, d, t_air - kDepth,
                          std::clamp(static_cast<int>(2.0 + (t_air - kDepth) / 250.0), 2, 24), lb,
                          tb);
            const Rgb t_far = transmittance_rgb(tb);
            radiance += transmittance_out * m_sky->to_rgb(lb);
            transmittance_out *= t_far;
        }
        transmittance_out = glm::clamp(transmittance_out, Rgb(0.0f), Rgb(1.0f));
        return;
    }
    const Bands l = radiance_bands(p, d, t_air, false, rng, &tb);
    radiance = m_sky->to_rgb(l);
    transmittance_out = glm::clamp(transmittance_rgb(tb), Rgb(0.0f), Rgb(1.0f));
}

void SkyRenderer::apply(const Ray& ray, float t_hit, Pcg32& rng, PixelSample& sample) const {
    if (!sample.hit) {
        sample.surface = background(ray, rng);
        sample.radiance = sample.volume + sample.transmittance * sample.surface;
        return;
    }
    Rgb l_air(0.0f), t_air(1.0f);
    aerial_perspective(ray, t_hit, rng, l_air, t_air);
    sample.radiance = l_air + t_air * sample.radiance;
    sample.volume = l_air + t_air * sample.volume;
    sample.transmittance *= t_air;
}

Rgb SkyRenderer::transmittance(const Vec3& from, const Vec3& to) const {
    const DVec3 a(from), b(to);
    const double length = glm::length(b - a);
    if (!(length > 0.0))
        return Rgb(1.0f);
    const DVec3 d = (b - a) / length;
    double t0 = 0.0, t1 = 0.0;
    bool ground = false;
    if (!atmosphere_segment(m_sky->atmosphere, a, d, t0, t1, ground))
        return Rgb(1.0f);
    const Bands tau = atmosphere_optical_depth(m_sky->atmosphere, a, d, t0, std::min(t1, length),
                                               std::max(64, m_sky->settings.view_steps));
    Bands t{};
    for (int i = 0; i < m_sky->bands(); ++i)
        t[i] = std::exp(-tau[i]);
    return transmittance_rgb(t);
}

void SkyRenderer::build_irradiance() {
    // Radiance over the sphere seen from 1 m above the origin (ground below, lit by sun and sky),
    // then E(n) = sum L(w) max(0, n.w) dw for a grid of normals.
    constexpr int kH = 24, kW = 48;
    std::vector<Rgb> radiance(static_cast<size_t>(kH * kW));
    std::vector<DVec3> dirs(radiance.size());
    std::vector<double> solid_angle(radiance.size());
    const DVec3 p(0.0, 1.0, 0.0);
    tbb::parallel_for(0, kH, [&](int j) {
        const double c0 = 1.0 - 2.0 * j / kH, c1 = 1.0 - 2.0 * (j + 1) / kH;
        const double cos_t = 0.5 * (c0 + c1);
        const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
        for (int i = 0; i < kW; ++i) {
            const double phi = 2.0 * kPiD * (i + 0.5) / kW;
            const size_t k = static_cast<size_t>(j * kW + i);
            dirs[k] = DVec3(sin_t * std::cos(phi), cos_t, sin_t * std::sin(phi));
            solid_angle[k] = (c0 - c1) * 2.0 * kPiD / kW;
            Pcg32 rng(0x5eedULL + k, 0xa11ULL);
            radiance[k] = m_sky->to_rgb(radiance_bands(p, dirs[k], 1e30, false, rng, nullptr));
        }
    });
    m_irradiance.assign(static_cast<size_t>(kIrrH * kIrrW), Rgb(0.0f));
    for (int j = 0; j < kIrrH; ++j) {
        const double elev = -0.5 * kPiD + kPiD * j / (kIrrH - 1);
        for (int i = 0; i < kIrrW; ++i) {
            const double az = 2.0 * kPiD * i / kIrrW;
            const DVec3 n(std::cos(elev) * std::cos(az), std::sin(elev),
                          std::cos(elev) * std::sin(az));
            glm::dvec3 e(0.0);
            for (size_t k = 0; k < dirs.size(); ++k) {
                const double c = glm::dot(n, dirs[k]);
                if (c > 0.0)
                    e += glm::dvec3(radiance[k]) * c * solid_angle[k];
            }
            m_irradiance[static_cast<size_t>(j * kIrrW + i)] = Rgb(e);
        }
    }
}

Rgb SkyRenderer::irradiance(const Vec3& n) const {
    const float elev = std::asin(std::clamp(n.y, -1.0f, 1.0f));
    float az = std::atan2(n.z, n.x);
    if (az < 0.0f)
        az += kTwoPi;
    const float y = (elev + 0.5f * kPi) / kPi * (kIrrH - 1);
    const float x = az / kTwoPi * kIrrW;
    const int y0 = std::clamp(static_cast<int>(y), 0, kIrrH - 2);
    const int x0 = static_cast<int>(x) % kIrrW, x1 = (x0 + 1) % kIrrW;
    const float fy = std::clamp(y - y0, 0.0f, 1.0f), fx = x - std::floor(x);
    const auto at = [&](int yy, int xx) {
        return m_irradiance[static_cast<size_t>(yy * kIrrW + xx)];
    };
    return (1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x1)) +
           fy * ((1 - fx) * at(y0 + 1, x0) + fx * at(y0 + 1, x1));
}

Light make_sun_light(const SkyScene& sky, bool through_atmosphere) {
    Bands t{};
    if (through_atmosphere) {
        t = sun_transmittance(sky, DVec3(0.0, 1.0, 0.0), std::max(64, sky.settings.sun_steps));
    } else {
        for (int i = 0; i < sky.bands(); ++i)
            t[i] = sky.sun.elevation_deg > -90.0 ? 1.0 : 0.0;
    }
    Light light;
    light.name = "sun";
    light.emitter = DirectionalLight{Vec3(-sky.sun_direction), sky.to_rgb(t)};
    return light;
}

void parse_sky_keys(JsonObjectReader& scene, const SkySettings& settings,
                    std::shared_ptr<const SkyScene>& sky, std::vector<Light>& lights) {
    const auto atmosphere = scene.optional("atmosphere");
    const auto sun = scene.optional("sun");
    if (atmosphere) {
        sky = make_sky_scene(*atmosphere, sun, settings);
        lights.push_back(make_sun_light(*sky, true));
    } else if (sun) {
        // A sun in vacuum: a directional light of its illuminance, with no sky.
        const std::vector<double> nm = sky_wavelengths_nm(settings);
        Atmosphere none = default_earth_atmosphere(nm, settings.rgb_wavelengths_nm);
        const auto vacuum = make_sky_scene(std::move(none), parse_sun(*sun), settings);
        lights.push_back(make_sun_light(*vacuum, false));
    }
}

}  // namespace kasumi
