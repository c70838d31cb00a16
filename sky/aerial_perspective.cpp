#include "sky/aerial_perspective.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace kasumi {

namespace {

/// Midpoint nodes per slice: about one per 250 m (the per-pixel march's density), at least one.
int nodes_in(double length_m) {
    return std::clamp(static_cast<int>(std::ceil(length_m / 250.0)), 1, 16);
}

}  // namespace

bool ViewFrustum::film_coordinates(const DVec3& d, double& u, double& v) const {
    const double along = glm::dot(d, forward);
    if (!(along > 1e-6))
        return false;
    // Solve corner + u du + v dv = d / along in the image plane (du, dv need not be orthogonal).
    const DVec3 q = d / along - corner;
    const double a = glm::dot(du, du), b = glm::dot(du, dv), c = glm::dot(dv, dv);
    const double ru = glm::dot(q, du), rv = glm::dot(q, dv);
    const double det = a * c - b * b;
    if (!(std::abs(det) > 0.0))
        return false;
    u = (ru * c - rv * b) / det;
    v = (rv * a - ru * b) / det;
    return true;
}

ViewFrustum make_view_frustum(const Camera& camera, int width, int height) {
    const auto plane_point = [&](float px, float py, const DVec3& forward) {
        const DVec3 d = glm::normalize(DVec3(camera.generate_ray(px, py).direction));
        return d / glm::dot(d, forward);
    };
    ViewFrustum f;
    f.origin = DVec3(camera.position());
    f.forward = glm::normalize(DVec3(camera.forward()));
    const auto w = static_cast<float>(width), h = static_cast<float>(height);
    f.corner = plane_point(0.0f, 0.0f, f.forward);
    f.du = plane_point(w, 0.0f, f.forward) - f.corner;
    f.dv = plane_point(0.0f, h, f.forward) - f.corner;
    return f;
}

AerialPerspective::AerialPerspective(const SkyScene& sky, const SkyLuts& luts,
                                     const ViewFrustum& frustum, const Rgb& white)
    : m_frustum(frustum),
      m_sun_direction(sky.sun_direction),
      m_mie_phase(sky.atmosphere.mie_phase),
      m_froxels(static_cast<size_t>(kSlices + 1) * kWidth * kHeight) {
    const Atmosphere& a = sky.atmosphere;
    const int nb = a.bands;
    const auto to_rgb3 = [&](const Bands& b, float out[3]) {
        const Rgb c = sky.to_rgb(b);
        out[0] = c.r;
        out[1] = c.g;
        out[2] = c.b;
    };
    const auto transmittance_rgb3 = [&](const Bands& t, float out[3]) {
        const Rgb c = sky.to_rgb(t);
        out[0] = white.r > 0.0f ? c.r / white.r : 1.0f;
        out[1] = white.g > 0.0f ? c.g / white.g : 1.0f;
        out[2] = white.b > 0.0f ? c.b / white.b : 1.0f;
    };
    // The Rayleigh phase of each band as c0 + c2 mu².
    Bands phase_c0{}, phase_c2{};
    for (int b = 0; b < nb; ++b) {
        phase_c0[b] = rayleigh_phase(a, b, 0.0);
        phase_c2[b] = rayleigh_phase(a, b, 1.0) - phase_c0[b];
    }
    tbb::parallel_for(0, kWidth * kHeight, [&](int ray) {
        const int x = ray % kWidth, y = ray / kWidth;
        const DVec3 p = m_frustum.origin;
        const DVec3 d = m_frustum.direction(static_cast<double>(x) / (kWidth - 1),
                                            static_cast<double>(y) / (kHeight - 1));
        double t_enter = 0.0, t_exit = 0.0;
        bool ground = false;
        const bool inside = atmosphere_segment(a, p, d, t_enter, t_exit, ground);
        // Running integrals from the camera, per band: single scattering without phase
        // (Rayleigh, Mie), multiple scattering, optical depth.
        Bands s_r{}, s_m{}, s_ms{}, tau{}, ts{}, ms{}, t{}, s_r0{}, s_r2{};
        AtmosphereCoefficients co;
        Froxel& first = m_froxels[static_cast<size_t>(y) * kWidth + x];
        first = Froxel{};
        for (int c = 0; c < 3; ++c)
            first.v[Froxel::kTransmittance + c] = 1.0f;
        for (int k = 1; k <= kSlices; ++k) {
            // The slice's part inside the atmosphere. Past the planet's ground (no surface lies
            // there, but lookups between this ray and a neighbour that meets the ground farther
            // away interpolate across it) the air is continued as it is at the ground point, so
            // the values stay smooth in depth instead of stopping at the ground.
            const double t0 = inside ? std::max(slice_distance(k - 1), t_enter) : 0.0;
            const double t1 =
                inside ? (ground ? slice_distance(k) : std::min(slice_distance(k), t_exit)) : 0.0;
            const double t_last = ground ? t_exit * (1.0 - 1e-9) : t_exit;
            if (t1 > t0) {
                const int n = nodes_in(t1 - t0);
                const double dt = (t1 - t0) / n;
                for (int i = 0; i < n; ++i) {
                    // The per-pixel march's integrand (SkyLuts::march) with the phases left out.
                    const DVec3 xk = p + std::min(t0 + (i + 0.5) * dt, t_last) * d;
                    const DVec3 up_vec = xk - a.center();
                    const double r = glm::length(up_vec);
                    atmosphere_coefficients(a, r - a.ground_radius_m, co);
                    luts.sun_transmittance(sky, xk, ts);
                    luts.multiple_scattering(r, glm::dot(up_vec / r, sky.sun_direction), ms);
                    for (int b = 0; b < nb; ++b) {
                        const double w = std::exp(-(tau[b] + 0.5 * co.sigma_t[b] * dt)) * dt;
                        s_r[b] += w * co.sigma_s_rayleigh[b] * ts[b];
                        s_m[b] += w * co.sigma_s_mie[b] * ts[b];
                        s_ms[b] += w * (co.sigma_s_rayleigh[b] + co.sigma_s_mie[b]) * ms[b];
                        tau[b] += co.sigma_t[b] * dt;
                    }
                }
            }
            for (int b = 0; b < nb; ++b) {
                t[b] = std::exp(-tau[b]);
                s_r0[b] = phase_c0[b] * s_r[b];
                s_r2[b] = phase_c2[b] * s_r[b];
            }
            Froxel& f = m_froxels[(static_cast<size_t>(k) * kHeight + y) * kWidth + x];
            to_rgb3(s_r0, &f.v[Froxel::kRayleigh]);
            to_rgb3(s_r2, &f.v[Froxel::kRayleighMu2]);
            to_rgb3(s_m, &f.v[Froxel::kMie]);
            to_rgb3(s_ms, &f.v[Froxel::kMultiple]);
            transmittance_rgb3(t, &f.v[Froxel::kTransmittance]);
        }
    });
}

bool AerialPerspective::lookup(const DVec3& d, double t, Rgb& radiance, Rgb& transmittance) const {
    double u = 0.0, v = 0.0;
    if (!m_frustum.film_coordinates(d, u, v))
        return false;
    // Camera rays span [0, 1]² up to float rounding of their directions.
    constexpr double kSlack = 1e-4;
    if (!(u >= -kSlack && u <= 1.0 + kSlack && v >= -kSlack && v <= 1.0 + kSlack))
        return false;
    const double fx = std::clamp(u, 0.0, 1.0) * (kWidth - 1);
    const double fy = std::clamp(v, 0.0, 1.0) * (kHeight - 1);
    const int x0 = std::min(static_cast<int>(fx), kWidth - 2);
    const int y0 = std::min(static_cast<int>(fy), kHeight - 2);
    const float wx = static_cast<float>(fx - x0), wy = static_cast<float>(fy - y0);
    // Depth: slice k ends at kDepthM (k / kSlices)²; linear in t between slice ends.
    const double tc = std::clamp(t, 0.0, kDepthM);
    const int k0 = std::min(static_cast<int>(std::sqrt(tc / kDepthM) * kSlices), kSlices - 1);
    const double ta = slice_distance(k0), tb = slice_distance(k0 + 1);
    const float wz = static_cast<float>(std::clamp((tc - ta) / (tb - ta), 0.0, 1.0));
    // Each float of the row accumulates over the corners in the same order as a per-value
    // loop would (no fused operations: the same sums, bit for bit).
    float sum[Froxel::kFloats] = {};
    for (int corner = 0; corner < 8; ++corner) {
        const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
        const float w = (dx ? wx : 1.0f - wx) * (dy ? wy : 1.0f - wy) * (dz ? wz : 1.0f - wz);
        const float* f = at(k0 + dz, y0 + dy, x0 + dx).v;
        for (int k = 0; k < Froxel::kFloats; ++k)
            sum[k] += w * f[k];
    }
    const float* r = &sum[Froxel::kRayleigh];
    const float* r2 = &sum[Froxel::kRayleighMu2];
    const float* m = &sum[Froxel::kMie];
    const float* ms = &sum[Froxel::kMultiple];
    const float* tr = &sum[Froxel::kTransmittance];
    const double mu = glm::dot(d, m_sun_direction);
    const auto mu2 = static_cast<float>(mu * mu);
    const auto p_m = static_cast<float>(eval_precise(m_mie_phase, mu));
    radiance = Rgb(r[0] + mu2 * r2[0] + p_m * m[0] + ms[0], r[1] + mu2 * r2[1] + p_m * m[1] + ms[1],
                   r[2] + mu2 * r2[2] + p_m * m[2] + ms[2]);
    transmittance = Rgb(tr[0], tr[1], tr[2]);
    return true;
}

}  // namespace kasumi
