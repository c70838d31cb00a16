#include "volume/sky_luts.h"

#include "volume/sky_quadrature.h"
#include "volume/sky_reference.h"

namespace kasumi {

namespace {

/// Texel-centre coordinate u in [0, 1] for x in [0, 1] on n texels (Bruneton 2017).
double unit_to_texel(double x, int n) {
    return 0.5 / n + x * (1.0 - 1.0 / n);
}
double texel_to_unit(double u, int n) {
    return (u - 0.5 / n) / (1.0 - 1.0 / n);
}

/// Distance to the top of the atmosphere from radius r along cosine mu.
double distance_to_top(double r, double mu, double rt) {
    const double disc = r * r * (mu * mu - 1.0) + rt * rt;
    return std::max(0.0, -r * mu + std::sqrt(std::max(0.0, disc)));
}

}  // namespace

void SkyLuts::lookup(const std::vector<float>& table, int w, int h, double u, double v,
                     Bands& out) const {
    const double x = std::clamp(u * w - 0.5, 0.0, w - 1.0);
    const double y = std::clamp(v * h - 0.5, 0.0, h - 1.0);
    const int x0 = std::min(static_cast<int>(x), w - 2), y0 = std::min(static_cast<int>(y), h - 2);
    const double fx = x - x0, fy = y - y0;
    const auto at = [&](int xx, int yy) {
        return &table[(static_cast<size_t>(yy) * w + xx) * static_cast<size_t>(m_bands)];
    };
    const float* a = at(x0, y0);
    const float* b = at(x0 + 1, y0);
    const float* c = at(x0, y0 + 1);
    const float* d = at(x0 + 1, y0 + 1);
    for (int i = 0; i < m_bands; ++i) {
        out[i] = (1 - fy) * ((1 - fx) * a[i] + fx * b[i]) + fy * ((1 - fx) * c[i] + fx * d[i]);
    }
}

SkyLuts::SkyLuts(const SkyScene& sky) {
    const Atmosphere& a = sky.atmosphere;
    m_bands = a.bands;
    m_rg = a.ground_radius_m;
    m_rt = a.top_radius_m;
    const size_t nb = static_cast<size_t>(m_bands);
    const double big_h = std::sqrt(m_rt * m_rt - m_rg * m_rg);
    // Transmittance: x_r = rho / H, x_mu = (d - d_min) / (d_max - d_min) (Bruneton 2017).
    auto transmittance_table = std::make_shared<std::vector<float>>(
        static_cast<size_t>(kTransmittanceW * kTransmittanceH) * nb, 0.0f);
    for (int j = 0; j < kTransmittanceH; ++j) {
        for (int i = 0; i < kTransmittanceW; ++i) {
            const double x_mu = texel_to_unit((i + 0.5) / kTransmittanceW, kTransmittanceW);
            const double x_r = texel_to_unit((j + 0.5) / kTransmittanceH, kTransmittanceH);
            const double rho = big_h * x_r;
            const double r = std::sqrt(rho * rho + m_rg * m_rg);
            const double d_min = m_rt - r, d_max = rho + big_h;
            const double d = d_min + x_mu * (d_max - d_min);
            const double mu =
                d == 0.0
                    ? 1.0
                    : std::clamp((big_h * big_h - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
            const DVec3 p(0.0, r - m_rg, 0.0);
            const DVec3 dir(std::sqrt(std::max(0.0, 1.0 - mu * mu)), mu, 0.0);
            const Bands tau = atmosphere_optical_depth(a, p, dir, 0.0, d, 64);
            float* out =
                &(*transmittance_table)[(static_cast<size_t>(j) * kTransmittanceW + i) * nb];
            for (size_t b = 0; b < nb; ++b)
                out[b] = static_cast<float>(std::exp(-tau[b]));
        }
    }
    // Multiple scattering (Hillaire 2020 §5.5): 64 directions (8 x 8 stratified sphere), 20
    // nodes each, isotropic phase p_u = 1 / (4 pi).
    m_transmittance = transmittance_table;
    auto multiple_table = std::make_shared<std::vector<float>>(
        static_cast<size_t>(kMultipleW * kMultipleH) * nb, 0.0f);
    constexpr int kDirs = 8;
    constexpr double kPu = 1.0 / (4.0 * kPiD);
    for (int j = 0; j < kMultipleH; ++j) {
        for (int i = 0; i < kMultipleW; ++i) {
            const double mu_s = -1.0 + 2.0 * (i + 0.5) / kMultipleW;
            const double h = (m_rt - m_rg) * (j + 0.5) / kMultipleH;
            const DVec3 p(0.0, h, 0.0);
            SkyScene local = sky;
            local.sun_direction = DVec3(std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s)), mu_s, 0.0);
            Bands l2{}, fms{};
            for (int a1 = 0; a1 < kDirs; ++a1) {
                for (int a2 = 0; a2 < kDirs; ++a2) {
                    const double cos_t = 1.0 - 2.0 * (a1 + 0.5) / kDirs;
                    const double phi = 2.0 * kPiD * (a2 + 0.5) / kDirs;
                    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
                    const DVec3 d(sin_t * std::cos(phi), cos_t, sin_t * std::sin(phi));
                    double t0 = 0.0, t1 = 0.0;
                    bool ground = false;
                    if (!atmosphere_segment(a, p, d, t0, t1, ground))
                        continue;
                    Bands tau{};
                    const double dw = 4.0 * kPiD / (kDirs * kDirs);
                    for_each_sky_node(a, p, d, t0, t1, 20, [&](double t, double dt) {
                        const DVec3 x = p + t * d;
                        const AtmosphereCoefficients c =
                            atmosphere_coefficients(a, a.radius(x) - m_rg);
                        Bands ts;
                        sun_transmittance(local, x, ts);
                        for (size_t b = 0; b < nb; ++b) {
                            const double tr = std::exp(-(tau[b] + 0.5 * c.sigma_t[b] * dt));
                            const double s = c.sigma_s_rayleigh[b] + c.sigma_s_mie[b];
                            l2[b] += tr * s * kPu * ts[b] * dt * kPu * dw;
                            fms[b] += tr * s * dt * kPu * dw;
                            tau[b] += c.sigma_t[b] * dt;
                        }
                    });
                    if (ground) {
                        const DVec3 x = p + t1 * d;
                        const DVec3 n = glm::normalize(x - a.center());
                        Bands ts;
                        sun_transmittance(local, x, ts);
                        const double cos_s = std::max(0.0, glm::dot(n, local.sun_direction));
                        for (size_t b = 0; b < nb; ++b)
                            l2[b] += std::exp(-tau[b]) * a.ground_albedo[b] / kPiD * cos_s * ts[b] *
                                     kPu * dw;
                    }
                }
            }
            float* out = &(*multiple_table)[(static_cast<size_t>(j) * kMultipleW + i) * nb];
            for (size_t b = 0; b < nb; ++b)
                out[b] = static_cast<float>(l2[b] / std::max(1e-6, 1.0 - fms[b]));
        }
    }
    m_multiple = multiple_table;
}

void SkyLuts::transmittance(double r, double mu, Bands& out) const {
    const double big_h = std::sqrt(m_rt * m_rt - m_rg * m_rg);
    r = std::clamp(r, m_rg, m_rt);
    const double rho = std::sqrt(std::max(0.0, r * r - m_rg * m_rg));
    const double d = distance_to_top(r, mu, m_rt);
    const double d_min = m_rt - r, d_max = rho + big_h;
    const double x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
    lookup(*m_transmittance, kTransmittanceW, kTransmittanceH,
           unit_to_texel(std::clamp(x_mu, 0.0, 1.0), kTransmittanceW),
           unit_to_texel(rho / big_h, kTransmittanceH), out);
}

void SkyLuts::sun_transmittance(const SkyScene& sky, const DVec3& p, Bands& out) const {
    const DVec3 up_vec = p - sky.atmosphere.center();
    const double r = glm::length(up_vec);
    const DVec3 up = up_vec / r;
    const double horizon_elev = -std::acos(std::min(1.0, m_rg / r));
    const double mu_s = std::clamp(glm::dot(up, sky.sun_direction), -1.0, 1.0);
    const double sun_elev = std::asin(mu_s);
    const double fraction = disc_fraction_above(sun_elev - horizon_elev, sky.sun_radius_rad);
    if (fraction <= 0.0) {
        for (int i = 0; i < m_bands; ++i)
            out[i] = 0.0;
        return;
    }
    transmittance(r, std::max(mu_s, std::sin(horizon_elev)), out);
    for (int i = 0; i < m_bands; ++i)
        out[i] *= fraction;
}

void SkyLuts::multiple_scattering(double r, double mu_s, Bands& out) const {
    const double u = std::clamp(0.5 * (mu_s + 1.0), 0.0, 1.0);
    const double v = std::clamp((r - m_rg) / (m_rt - m_rg), 0.0, 1.0);
    lookup(*m_multiple, kMultipleW, kMultipleH, u, v, out);
}

void SkyLuts::march(const SkyScene& sky, const DVec3& p, const DVec3& d, double t_max, int steps,
                    Bands& radiance, Bands& transmittance_out) const {
    const Atmosphere& a = sky.atmosphere;
    const int n = m_bands;
    for (int i = 0; i < n; ++i) {
        radiance[i] = 0.0;
        transmittance_out[i] = 1.0;
    }
    double t_enter = 0.0, t_exit = 0.0;
    bool ground = false;
    if (!atmosphere_segment(a, p, d, t_enter, t_exit, ground))
        return;
    const double t_end = std::min(t_exit, t_max);
    const double mu = glm::dot(d, sky.sun_direction);
    const double p_r = rayleigh_phase(mu), p_m = eval_precise(a.mie_phase, mu);
    Bands tau{}, ts, ms;
    if (t_end - t_enter < kShortSegmentM && !(ground && t_max >= t_exit)) {
        // Short segment (aerial perspective over a scene): coefficients and light taken at its
        // middle, integrated in closed form as a homogeneous stretch,
        // L = S (1 - exp(-sigma_t L)) / sigma_t. Over 1 km the altitude changes by at most
        // 1 km and the relative error is O((1 km / H)^2) for scale height H.
        const double length = t_end - t_enter;
        const DVec3 x = p + (t_enter + 0.5 * length) * d;
        const DVec3 up_vec = x - a.center();
        const double r = glm::length(up_vec);
        const AtmosphereCoefficients c = atmosphere_coefficients(a, r - m_rg);
        sun_transmittance(sky, x, ts);
        multiple_scattering(r, glm::dot(up_vec / r, sky.sun_direction), ms);
        for (int i = 0; i < n; ++i) {
            const double tau_i = c.sigma_t[i] * length;
            // (1 - e^-tau) / sigma_t, written with expm1 and its limit `length` as tau -> 0.
            const double path = tau_i > 1e-12 ? -std::expm1(-tau_i) / c.sigma_t[i] : length;
            radiance[i] = path * ((c.sigma_s_rayleigh[i] * p_r + c.sigma_s_mie[i] * p_m) * ts[i] +
                                  (c.sigma_s_rayleigh[i] + c.sigma_s_mie[i]) * ms[i]);
            transmittance_out[i] = std::exp(-tau_i);
        }
        return;
    }
    for_each_sky_node(a, p, d, t_enter, t_end, steps, [&](double t, double dt) {
        const DVec3 x = p + t * d;
        const DVec3 up_vec = x - a.center();
        const double r = glm::length(up_vec);
        const AtmosphereCoefficients c = atmosphere_coefficients(a, r - m_rg);
        sun_transmittance(sky, x, ts);
        multiple_scattering(r, glm::dot(up_vec / r, sky.sun_direction), ms);
        for (int i = 0; i < n; ++i) {
            const double tr = std::exp(-(tau[i] + 0.5 * c.sigma_t[i] * dt));
            radiance[i] += tr * dt *
                           ((c.sigma_s_rayleigh[i] * p_r + c.sigma_s_mie[i] * p_m) * ts[i] +
                            (c.sigma_s_rayleigh[i] + c.sigma_s_mie[i]) * ms[i]);
            tau[i] += c.sigma_t[i] * dt;
        }
    });
    for (int i = 0; i < n; ++i)
        transmittance_out[i] = std::exp(-tau[i]);
    if (ground && t_max >= t_exit) {
        const DVec3 x = p + t_exit * d;
        const DVec3 nrm = glm::normalize(x - a.center());
        sun_transmittance(sky, x, ts);
        const double cos_s = std::max(0.0, glm::dot(nrm, sky.sun_direction));
        // Ground: direct sun plus the isotropic multiple-scattering radiance as sky light
        // (irradiance pi * Psi_ms), both reflected by the Lambertian albedo.
        multiple_scattering(m_rg, glm::dot(nrm, sky.sun_direction), ms);
        for (int i = 0; i < n; ++i) {
            radiance[i] +=
                transmittance_out[i] * a.ground_albedo[i] / kPiD * (cos_s * ts[i] + kPiD * ms[i]);
            transmittance_out[i] = 0.0;
        }
    }
}

void SkyLuts::build_sky_view(const SkyScene& sky, const DVec3& camera) {
    const size_t nb = static_cast<size_t>(m_bands);
    m_camera = camera;
    m_camera_r = sky.atmosphere.radius(camera);
    m_sky_view.assign(static_cast<size_t>(kSkyViewW * kSkyViewH) * nb, 0.0f);
    const DVec3 up = glm::normalize(camera - sky.atmosphere.center());
    // Frame: sun azimuth at u = 0. Projected sun direction (any if the sun is at the zenith).
    DVec3 forward = sky.sun_direction - glm::dot(sky.sun_direction, up) * up;
    if (glm::length(forward) < 1e-9)
        forward =
            std::abs(up.x) < 0.9 ? glm::cross(up, DVec3(1, 0, 0)) : glm::cross(up, DVec3(0, 0, 1));
    forward = glm::normalize(forward);
    const DVec3 side = glm::cross(up, forward);
    const double horizon = -std::acos(std::min(1.0, m_rg / m_camera_r));
    Bands radiance, transmittance_out;
    for (int j = 0; j < kSkyViewH; ++j) {
        const double v = (j + 0.5) / kSkyViewH;
        double elev = 0.0;
        if (v >= 0.5) {
            const double l = (2.0 * v - 1.0);
            elev = horizon + l * l * (0.5 * kPiD - horizon);
        } else {
            const double l = 1.0 - 2.0 * v;
            elev = horizon - l * l * (horizon + 0.5 * kPiD);
        }
        for (int i = 0; i < kSkyViewW; ++i) {
            const double az = 2.0 * kPiD * (i + 0.5) / kSkyViewW;
            const DVec3 d = std::cos(elev) * (std::cos(az) * forward + std::sin(az) * side) +
                            std::sin(elev) * up;
            march(sky, camera, glm::normalize(d), 1e30, 40, radiance, transmittance_out);
            float* out = &m_sky_view[(static_cast<size_t>(j) * kSkyViewW + i) * nb];
            for (size_t b = 0; b < nb; ++b)
                out[b] = static_cast<float>(radiance[b]);
        }
    }
}

void SkyLuts::sky_view(const SkyScene& sky, const DVec3& d, Bands& out) const {
    const DVec3 up = glm::normalize(m_camera - sky.atmosphere.center());
    DVec3 forward = sky.sun_direction - glm::dot(sky.sun_direction, up) * up;
    if (glm::length(forward) < 1e-9)
        forward =
            std::abs(up.x) < 0.9 ? glm::cross(up, DVec3(1, 0, 0)) : glm::cross(up, DVec3(0, 0, 1));
    forward = glm::normalize(forward);
    const DVec3 side = glm::cross(up, forward);
    const double horizon = -std::acos(std::min(1.0, m_rg / m_camera_r));
    const double elev = std::asin(std::clamp(glm::dot(d, up), -1.0, 1.0));
    double v = 0.0;
    if (elev >= horizon)
        v = 0.5 + 0.5 * std::sqrt((elev - horizon) / (0.5 * kPiD - horizon));
    else
        v = 0.5 - 0.5 * std::sqrt((horizon - elev) / (horizon + 0.5 * kPiD));
    double az = std::atan2(glm::dot(d, side), glm::dot(d, forward));
    if (az < 0.0)
        az += 2.0 * kPiD;
    double u = az / (2.0 * kPiD);
    // Wrap in azimuth: interpolate across u = 0 / 1 by looking up the nearer edge column.
    u = std::clamp(u, 0.5 / kSkyViewW, 1.0 - 0.5 / kSkyViewW);
    lookup(m_sky_view, kSkyViewW, kSkyViewH, u, std::clamp(v, 0.0, 1.0), out);
}

}  // namespace kasumi
