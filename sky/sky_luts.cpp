#include "sky/sky_luts.h"

#include "sky/sky_quadrature.h"
#include "sky/sky_reference.h"
#include "sky/sun_disc_fraction.h"

#include <tbb/parallel_for.h>
#include <array>

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
    const int x0 = std::max(0, std::min(static_cast<int>(x), w - 2));
    const int y0 = std::max(0, std::min(static_cast<int>(y), h - 2));
    const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
    const double fx = x - x0, fy = y - y0;
    const auto at = [&](int xx, int yy) {
        return &table[(static_cast<size_t>(yy) * w + xx) * static_cast<size_t>(m_bands)];
    };
    const float* a = at(x0, y0);
    const float* b = at(x1, y0);
    const float* c = at(x0, y1);
    const float* d = at(x1, y1);
    for (int i = 0; i < m_bands; ++i) {
        out[i] = (1 - fy) * ((1 - fx) * a[i] + fx * b[i]) + fy * ((1 - fx) * c[i] + fx * d[i]);
    }
}

SkyLuts::SkyLuts(const SkyScene& sky) {
    const Atmosphere& a = sky.atmosphere;
    m_bands = a.bands;
    m_rg = a.ground_radius_m;
    m_rt = a.top_radius_m;
    m_sun = SunDisc(sky.sun_radius_rad);
    const size_t nb = static_cast<size_t>(m_bands);
    const double big_h = std::sqrt(m_rt * m_rt - m_rg * m_rg);
    // Transmittance: x_r = rho / H, x_mu = (d - d_min) / (d_max - d_min) (Bruneton 2017).
    auto transmittance_table = std::make_shared<std::vector<float>>(
        static_cast<size_t>(kTransmittanceW * kTransmittanceH) * nb, 0.0f);
    tbb::parallel_for(0, kTransmittanceH, [&](int j) {
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
    });
    m_transmittance = transmittance_table;
    build_multiple_scattering(sky);
}

double SkyLuts::multiple_v(double r) const {
    return unit_to_texel(std::sqrt(std::clamp((r - m_rg) / (m_rt - m_rg), 0.0, 1.0)), kMultipleH);
}

SkyLuts::TransmittanceRow SkyLuts::transmittance_row(double r) const {
    const double big_h = std::sqrt(m_rt * m_rt - m_rg * m_rg);
    TransmittanceRow row;
    row.r = std::clamp(r, m_rg, m_rt);
    const double rho = std::sqrt(std::max(0.0, row.r * row.r - m_rg * m_rg));
    row.d_min = m_rt - row.r;
    row.d_max = rho + big_h;
    // lookup()'s row: y in texels, its lower row and weight.
    constexpr int h = kTransmittanceH;
    const double y = std::clamp(unit_to_texel(rho / big_h, h) * h - 0.5, 0.0, h - 1.0);
    row.y0 = std::max(0, std::min(static_cast<int>(y), h - 2));
    row.y1 = std::min(row.y0 + 1, h - 1);
    row.fy = y - row.y0;
    return row;
}

void SkyLuts::transmittance(const TransmittanceRow& row, double mu, double* out) const {
    const double d = distance_to_top(row.r, mu, m_rt);
    const double x_mu = row.d_max > row.d_min ? (d - row.d_min) / (row.d_max - row.d_min) : 0.0;
    constexpr int w = kTransmittanceW;
    const double x =
        std::clamp(unit_to_texel(std::clamp(x_mu, 0.0, 1.0), w) * w - 0.5, 0.0, w - 1.0);
    const int x0 = std::max(0, std::min(static_cast<int>(x), w - 2));
    const int x1 = std::min(x0 + 1, w - 1);
    const double fx = x - x0, fy = row.fy;
    const size_t nb = static_cast<size_t>(m_bands);
    const std::vector<float>& table = *m_transmittance;
    const float* a = &table[(static_cast<size_t>(row.y0) * w + x0) * nb];
    const float* b = &table[(static_cast<size_t>(row.y0) * w + x1) * nb];
    const float* c = &table[(static_cast<size_t>(row.y1) * w + x0) * nb];
    const float* e = &table[(static_cast<size_t>(row.y1) * w + x1) * nb];
    for (size_t i = 0; i < nb; ++i)
        out[i] = (1 - fy) * ((1 - fx) * a[i] + fx * b[i]) + fy * ((1 - fx) * c[i] + fx * e[i]);
}

void SkyLuts::transmittance(double r, double mu, Bands& out) const {
    transmittance(transmittance_row(r), mu, out.data());
}

void SkyLuts::sun_transmittance(const SkyScene& sky, const DVec3& p, Bands& out) const {
    const DVec3 up_vec = p - sky.atmosphere.center();
    const double r = glm::length(up_vec);
    const DVec3 up = up_vec / r;
    const double mu_s = std::clamp(glm::dot(up, sky.sun_direction), -1.0, 1.0);
    double sin_horizon = 0.0;
    const double fraction = sun_disc_fraction(r, mu_s, m_rg, m_sun, sin_horizon);
    if (fraction <= 0.0) {
        for (int i = 0; i < m_bands; ++i)
            out[i] = 0.0;
        return;
    }
    transmittance(r, std::max(mu_s, sin_horizon), out);
    for (int i = 0; i < m_bands; ++i)
        out[i] *= fraction;
}

void SkyLuts::multiple_scattering(double r, double mu_s, Bands& out) const {
    lookup(*m_multiple, kMultipleW, kMultipleH, multiple_u(mu_s), multiple_v(r), out);
}

void SkyLuts::ground_sky_irradiance(double mu_s, Bands& out) const {
    lookup(*m_ground_irradiance, kMultipleW, 1, multiple_u(mu_s), 0.5, out);
}

namespace {

/// The stretch [t_enter, t_end] of the ray p + t d inside the air and before t_max, and where
/// it leaves the air (t_exit; `ground`: by the ground). False when there is none, including a
/// stretch that ends before it enters the air (a camera in space looking at something outside
/// the atmosphere): no light, transmittance 1 (the closed forms would take a negative length).
bool air_stretch(const Atmosphere& a, const DVec3& p, const DVec3& d, double t_max, double& t_enter,
                 double& t_exit, double& t_end, bool& ground) {
    if (!atmosphere_segment(a, p, d, t_enter, t_exit, ground))
        return false;
    t_end = std::min(t_exit, t_max);
    return t_end > t_enter;
}

}  // namespace

void SkyLuts::march(const SkyScene& sky, const DVec3& p, const DVec3& d, double t_max, int steps,
                    Bands& radiance, Bands& transmittance_out) const {
    const Atmosphere& a = sky.atmosphere;
    const int n = m_bands;
    for (int i = 0; i < n; ++i) {
        radiance[i] = 0.0;
        transmittance_out[i] = 1.0;
    }
    double t_enter = 0.0, t_exit = 0.0, t_end = 0.0;
    bool ground = false;
    if (!air_stretch(a, p, d, t_max, t_enter, t_exit, t_end, ground))
        return;
    const double mu = glm::dot(d, sky.sun_direction);
    Bands p_r{};
    rayleigh_phase_bands(a, mu, p_r);
    const double p_m = eval_precise(a.mie_phase, mu);
    Bands ts, ms;
    if (t_end - t_enter < kShortSegmentM && !(ground && t_max >= t_exit)) {
        // Short segment (aerial perspective over a scene) in one piece by Simpson's rule on
        // its ends and middle: optical depth tau = L (sigma_0 + 4 sigma_m + sigma_1) / 6, and
        // the light L_in = (1 - e^-tau) L / tau times the mean of the source S (scattering
        // coefficients times the phases and the sun and multiple-scattering light) over the
        // three nodes, each weighted by its transmittance from the start. Exact for
        // homogeneous air at any optical depth; for an exponential layer the relative error is
        // (L cos theta / H)^4 / 2880, 1.7e-4 for a vertical kilometre of the 1.2 km aerosol.
        // (The coefficients of the middle alone, as before, made that layer's depth 2.8% too
        // small, by the factor (L/2H) / sinh(L/2H); tests/sky/published_atmosphere_test.cpp.)
        const double length = t_end - t_enter;
        // Densities of the three species at the ends and the middle (no band arrays: this
        // runs per pixel).
        std::array<DVec3, 3> x;
        std::array<double, 3> r{}, d_r{}, d_m{}, d_o{};
        for (int k = 0; k < 3; ++k) {
            x[k] = p + (t_enter + 0.5 * k * length) * d;
            r[k] = glm::length(x[k] - a.center());
            const double h = r[k] - m_rg;
            d_r[k] = a.rayleigh.profile.density(h);
            d_m[k] = a.mie.profile.density(h);
            d_o[k] = a.ozone.profile.density(h);
        }
        const auto sigma_t = [&](int k, int i) {
            return d_r[k] * (a.rayleigh.scattering[i] + a.rayleigh.absorption[i]) +
                   d_m[k] * (a.mie.scattering[i] + a.mie.absorption[i]) +
                   d_o[k] * (a.ozone.scattering[i] + a.ozone.absorption[i]);
        };
        // The sun's and the multiple-scattering light are looked up at the ends too only where
        // the air changes along the segment: if its extinction differs by over 1.55% from end
        // to end (an exponential layer: altitude change > H / 64, 19 m for the aerosol).
        // Otherwise their change is as small and the middle's light serves the three nodes
        // (a third of the table lookups; near-horizontal segments over a scene).
        bool uniform = true;
        for (int i = 0; i < n; ++i)
            uniform = uniform && std::abs(sigma_t(2, i) - sigma_t(0, i)) <= 0.0155 * sigma_t(1, i);
        Bands ts_end[2], ms_end[2];
        sun_transmittance(sky, x[1], ts);
        multiple_scattering(r[1], glm::dot(x[1] - a.center(), sky.sun_direction) / r[1], ms);
        if (!uniform) {
            for (int e = 0; e < 2; ++e) {
                const int k = 2 * e;
                sun_transmittance(sky, x[k], ts_end[e]);
                multiple_scattering(r[k], glm::dot(x[k] - a.center(), sky.sun_direction) / r[k],
                                    ms_end[e]);
            }
        }
        for (int i = 0; i < n; ++i) {
            double source[3];
            for (int k = 0; k < 3; ++k) {
                const bool middle_light = k == 1 || uniform;
                const double t_sun = middle_light ? ts[i] : ts_end[k / 2][i];
                const double multiple = middle_light ? ms[i] : ms_end[k / 2][i];
                const double s_r = d_r[k] * a.rayleigh.scattering[i];
                const double s_m = d_m[k] * a.mie.scattering[i];
                source[k] = (s_r * p_r[i] + s_m * p_m) * t_sun + (s_r + s_m) * multiple;
            }
            const double s0 = sigma_t(0, i), sm = sigma_t(1, i), s1 = sigma_t(2, i);
            const double tau_i = length * (s0 + 4.0 * sm + s1) / 6.0;
            // Depth to the middle: the integral of the parabola through the three nodes over
            // the first half.
            const double tau_mid = std::max(0.0, length * (5.0 * s0 + 8.0 * sm - s1) / 24.0);
            const double w_mid = 4.0 * std::exp(-tau_mid), w_end = std::exp(-tau_i);
            const double mean_source =
                (source[0] + w_mid * source[1] + w_end * source[2]) / (1.0 + w_mid + w_end);
            // (1 - e^-tau) L / tau, written with expm1 and its limit `length` as tau -> 0.
            const double path = tau_i > 1e-12 ? -std::expm1(-tau_i) * length / tau_i : length;
            radiance[i] = path * mean_source;
            transmittance_out[i] = std::exp(-tau_i);
        }
        return;
    }
    ScatteringTerms terms;
    march_terms(sky, p, d, t_max, steps, terms);
    for (int i = 0; i < n; ++i) {
        radiance[i] = p_r[i] * terms.rayleigh[i] + p_m * terms.mie[i] + terms.rest[i];
        transmittance_out[i] = terms.transmittance[i];
    }
}

void SkyLuts::march_terms(const SkyScene& sky, const DVec3& p, const DVec3& d, double t_max,
                          int steps, ScatteringTerms& out) const {
    const Atmosphere& a = sky.atmosphere;
    const int n = m_bands;
    out = ScatteringTerms{};
    for (int i = 0; i < n; ++i)
        out.transmittance[i] = 1.0;
    double t_enter = 0.0, t_exit = 0.0, t_end = 0.0;
    bool ground = false;
    if (!air_stretch(a, p, d, t_max, t_enter, t_exit, t_end, ground))
        return;
    Bands tau{}, ts, ms;
    AtmosphereCoefficients c;
    for_each_sky_node(a, p, d, t_enter, t_end, steps, [&](double t, double dt) {
        const DVec3 x = p + t * d;
        const DVec3 up_vec = x - a.center();
        const double r = glm::length(up_vec);
        atmosphere_coefficients(a, r - m_rg, c);
        sun_transmittance(sky, x, ts);
        multiple_scattering(r, glm::dot(up_vec / r, sky.sun_direction), ms);
        for (int i = 0; i < n; ++i) {
            const double w = std::exp(-(tau[i] + 0.5 * c.sigma_t[i] * dt)) * dt;
            out.rayleigh[i] += w * c.sigma_s_rayleigh[i] * ts[i];
            out.mie[i] += w * c.sigma_s_mie[i] * ts[i];
            out.rest[i] += w * (c.sigma_s_rayleigh[i] + c.sigma_s_mie[i]) * ms[i];
            tau[i] += c.sigma_t[i] * dt;
        }
    });
    for (int i = 0; i < n; ++i)
        out.transmittance[i] = std::exp(-tau[i]);
    if (ground && t_max >= t_exit) {
        const DVec3 x = p + t_exit * d;
        const DVec3 nrm = glm::normalize(x - a.center());
        sun_transmittance(sky, x, ts);
        const double cos_s = std::max(0.0, glm::dot(nrm, sky.sun_direction));
        // Ground: direct sun plus the sky's irradiance (all orders, from the table built with
        // the multiple-scattering table), reflected by the Lambertian albedo.
        ground_sky_irradiance(glm::dot(nrm, sky.sun_direction), ms);
        for (int i = 0; i < n; ++i) {
            out.rest[i] +=
                out.transmittance[i] * a.ground_albedo[i] / kPiD * (cos_s * ts[i] + ms[i]);
            out.transmittance[i] = 0.0;
        }
    }
}

void SkyLuts::build_sky_view(const SkyScene& sky, const DVec3& camera) {
    const size_t nb = static_cast<size_t>(m_bands);
    m_camera = camera;
    m_camera_r = sky.atmosphere.radius(camera);
    m_sky_view.assign(static_cast<size_t>(kSkyViewW * kSkyViewH) * 3 * nb, 0.0f);
    m_up = glm::normalize(camera - sky.atmosphere.center());
    // Frame: sun azimuth at u = 0. Projected sun direction (any if the sun is at the zenith).
    DVec3 forward = sky.sun_direction - glm::dot(sky.sun_direction, m_up) * m_up;
    if (glm::length(forward) < 1e-9)
        forward = std::abs(m_up.x) < 0.9 ? glm::cross(m_up, DVec3(1, 0, 0))
                                         : glm::cross(m_up, DVec3(0, 0, 1));
    m_forward = glm::normalize(forward);
    m_side = glm::cross(m_up, m_forward);
    m_horizon = -std::acos(std::min(1.0, m_rg / m_camera_r));
    tbb::parallel_for(0, kSkyViewH, [&](int j) {
        ScatteringTerms terms;
        const double v = (j + 0.5) / kSkyViewH;
        double elev = 0.0;
        if (v >= 0.5) {
            const double l = (2.0 * v - 1.0);
            elev = m_horizon + l * l * (0.5 * kPiD - m_horizon);
        } else {
            const double l = 1.0 - 2.0 * v;
            elev = m_horizon - l * l * (m_horizon + 0.5 * kPiD);
        }
        for (int i = 0; i < kSkyViewW; ++i) {
            // Azimuth from the sun over [0, pi]: the other half is its mirror image.
            const double az = kPiD * (i + 0.5) / kSkyViewW;
            const DVec3 d = std::cos(elev) * (std::cos(az) * m_forward + std::sin(az) * m_side) +
                            std::sin(elev) * m_up;
            march_terms(sky, camera, glm::normalize(d), 1e30, kSkyViewSteps, terms);
            float* out = &m_sky_view[(static_cast<size_t>(j) * kSkyViewW + i) * 3 * nb];
            for (size_t b = 0; b < nb; ++b) {
                out[b] = static_cast<float>(terms.rayleigh[b]);
                out[nb + b] = static_cast<float>(terms.mie[b]);
                out[2 * nb + b] = static_cast<float>(terms.rest[b]);
            }
        }
    });
}

void SkyLuts::sky_view(const SkyScene& sky, const DVec3& d, Bands& out) const {
    const double elev = std::asin(std::clamp(glm::dot(d, m_up), -1.0, 1.0));
    double v = 0.0;
    if (elev >= m_horizon)
        v = 0.5 + 0.5 * std::sqrt((elev - m_horizon) / (0.5 * kPiD - m_horizon));
    else
        v = 0.5 - 0.5 * std::sqrt((m_horizon - elev) / (m_horizon + 0.5 * kPiD));
    // |azimuth| from the sun: the table covers [0, pi] (mirror symmetry); at both ends the
    // sky's derivative in azimuth is zero, so the edge texels serve the half texel beyond.
    const double az = std::abs(std::atan2(glm::dot(d, m_side), glm::dot(d, m_forward)));
    const double u = std::clamp(az / kPiD, 0.5 / kSkyViewW, 1.0 - 0.5 / kSkyViewW);
    const int nb = m_bands;
    Bands terms[3];
    const double x = std::clamp(u * kSkyViewW - 0.5, 0.0, kSkyViewW - 1.0);
    const double y = std::clamp(std::clamp(v, 0.0, 1.0) * kSkyViewH - 0.5, 0.0, kSkyViewH - 1.0);
    const int x0 = std::min(static_cast<int>(x), kSkyViewW - 2);
    const int y0 = std::min(static_cast<int>(y), kSkyViewH - 2);
    const double fx = x - x0, fy = y - y0;
    const size_t stride = 3 * static_cast<size_t>(nb);
    const float* t00 = &m_sky_view[(static_cast<size_t>(y0) * kSkyViewW + x0) * stride];
    const float* t10 = t00 + stride;
    const float* t01 = t00 + kSkyViewW * stride;
    const float* t11 = t01 + stride;
    for (int part = 0, k = 0; part < 3; ++part) {
        for (int i = 0; i < nb; ++i, ++k) {
            terms[part][i] = (1 - fy) * ((1 - fx) * t00[k] + fx * t10[k]) +
                             fy * ((1 - fx) * t01[k] + fx * t11[k]);
        }
    }
    const double mu = glm::dot(d, sky.sun_direction);
    Bands p_r;  // bands [0, nb) written below
    rayleigh_phase_bands(sky.atmosphere, mu, p_r);
    const double p_m = eval_precise(sky.atmosphere.mie_phase, mu);
    for (int i = 0; i < nb; ++i)
        out[i] = p_r[i] * terms[0][i] + p_m * terms[1][i] + terms[2][i];
}

}  // namespace kasumi
