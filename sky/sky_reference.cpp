#include "sky/sky_reference.h"

#include "sky/sky_quadrature.h"

namespace kasumi {

namespace {

double altitude(const Atmosphere& a, const DVec3& x) {
    return a.radius(x) - a.ground_radius_m;
}

double mean_of(const Bands& b, int n) {
    double s = 0.0;
    for (int i = 0; i < n; ++i)
        s += b[i];
    return s / n;
}

/// Cosine-weighted direction about unit n.
DVec3 sample_cosine(const DVec3& n, double u1, double u2) {
    const double r = std::sqrt(u1), phi = 2.0 * kPiD * u2;
    const Frame frame{Vec3(n)};
    const Vec3 local(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                     static_cast<float>(std::sqrt(std::max(0.0, 1.0 - u1))));
    return glm::normalize(DVec3(frame.to_world(local)));
}

}  // namespace

Bands atmosphere_optical_depth(const Atmosphere& a, const DVec3& p, const DVec3& d, double t0,
                               double t1, int steps) {
    Bands tau{};
    AtmosphereCoefficients c;
    for_each_sky_node(a, p, d, t0, t1, steps, [&](double t, double dt) {
        atmosphere_coefficients(a, altitude(a, p + t * d), c);
        for (int i = 0; i < a.bands; ++i)
            tau[i] += c.sigma_t[i] * dt;
    });
    return tau;
}

double disc_fraction_above(double offset_rad, double radius_rad) {
    const double x = std::clamp(offset_rad / radius_rad, -1.0, 1.0);
    return (std::acos(-x) + x * std::sqrt(std::max(0.0, 1.0 - x * x))) / kPiD;
}

Bands sun_transmittance(const SkyScene& sky, const DVec3& p, int steps) {
    const Atmosphere& a = sky.atmosphere;
    Bands t{};
    const DVec3 up_vec = p - a.center();
    const double r = glm::length(up_vec);
    const DVec3 up = up_vec / r;
    // Angle of the sun above the geometric horizon of a sphere of ground radius seen from r.
    const double sin_horizon = std::min(1.0, a.ground_radius_m / r);
    const double horizon_elev = -std::acos(sin_horizon);  // <= 0: dip of the horizon
    const double sun_elev = std::asin(std::clamp(glm::dot(up, sky.sun_direction), -1.0, 1.0));
    const double fraction = disc_fraction_above(sun_elev - horizon_elev, sky.sun_radius_rad);
    if (fraction <= 0.0)
        return t;
    // Below the horizon but partly visible: take the grazing ray just above the horizon.
    DVec3 dir = sky.sun_direction;
    if (sun_elev < horizon_elev + 1e-7) {
        const DVec3 tangent =
            glm::normalize(sky.sun_direction - glm::dot(sky.sun_direction, up) * up);
        const double e = horizon_elev + 1e-7;
        dir = std::cos(e) * tangent + std::sin(e) * up;
    }
    double t0 = 0.0, t1 = 0.0;
    if (!intersect_sphere(a, p, dir, a.top_radius_m, t0, t1) || t1 <= 0.0) {
        for (int i = 0; i < a.bands; ++i)
            t[i] = fraction;
        return t;
    }
    const Bands tau = atmosphere_optical_depth(a, p, dir, std::max(0.0, t0), t1, steps);
    for (int i = 0; i < a.bands; ++i)
        t[i] = fraction * std::exp(-tau[i]);
    return t;
}

SkySample reference_sky(const SkyScene& sky, const DVec3& p, const DVec3& d, double t_max,
                        bool sun_disc, int orders, Pcg32& rng) {
    const Atmosphere& a = sky.atmosphere;
    const int n = a.bands;
    const int steps = sky.settings.view_steps;
    const int sun_steps = sky.settings.sun_steps;
    SkySample out;
    out.transmittance.fill(0.0);
    for (int i = 0; i < n; ++i)
        out.transmittance[i] = 1.0;
    double t_enter = 0.0, t_exit = 0.0;
    bool hits_ground = false;
    if (!atmosphere_segment(a, p, d, t_enter, t_exit, hits_ground)) {
        if (sun_disc)
            out.radiance = sky.sun_disc(glm::dot(d, sky.sun_direction));
        return out;
    }
    const bool reaches_end = t_max >= t_exit;
    const double t_end = std::min(t_exit, t_max);
    const double mu_sun = glm::dot(d, sky.sun_direction);
    Bands p_r_sun{};  // per band: the depolarisation may depend on the wavelength
    rayleigh_phase_bands(a, mu_sun, p_r_sun);
    const double p_m_sun = eval_precise(a.mie_phase, mu_sun);

    // Reservoir of one scattering vertex for the higher orders, drawn in proportion to the
    // band-mean of T sigma_s dt (one pass, no storage of the nodes).
    const bool continue_path = orders > 1;
    double reservoir_sum = 0.0;
    double chosen_t = 0.0, chosen_weight = 0.0;
    Bands chosen_t_r{}, chosen_t_m{};  // T sigma_s,R dt and T sigma_s,M dt at the chosen node

    Bands tau{};
    for_each_sky_node(a, p, d, t_enter, t_end, steps, [&](double t, double dt) {
        const DVec3 x = p + t * d;
        const AtmosphereCoefficients c = atmosphere_coefficients(a, altitude(a, x));
        Bands weight_r{}, weight_m{};
        for (int i = 0; i < n; ++i) {
            const double transmittance = std::exp(-(tau[i] + 0.5 * c.sigma_t[i] * dt));
            weight_r[i] = transmittance * c.sigma_s_rayleigh[i] * dt;
            weight_m[i] = transmittance * c.sigma_s_mie[i] * dt;
            tau[i] += c.sigma_t[i] * dt;
        }
        const Bands t_sun = sun_transmittance(sky, x, sun_steps);
        for (int i = 0; i < n; ++i)
            out.radiance[i] += (weight_r[i] * p_r_sun[i] + weight_m[i] * p_m_sun) * t_sun[i];
        if (continue_path) {
            const double w = mean_of(weight_r, n) + mean_of(weight_m, n);
            reservoir_sum += w;
            if (w > 0.0 && rng.next_float() * reservoir_sum < w) {
                chosen_t = t;
                chosen_weight = w;
                chosen_t_r = weight_r;
                chosen_t_m = weight_m;
            }
        }
    });
    for (int i = 0; i < n; ++i)
        out.transmittance[i] = std::exp(-tau[i]);

    // Higher orders from the chosen vertex: one direction from the phase mixture (Rayleigh
    // with the bands' mean depolarisation; each band weights by its own phase over the pdf).
    if (continue_path && chosen_weight > 0.0) {
        const double pick_prob = chosen_weight / reservoir_sum;
        const double mean_r = mean_of(chosen_t_r, n), mean_m = mean_of(chosen_t_m, n);
        const double c_m = mean_m / (mean_r + mean_m);
        const Vec3 wo = Vec3(-d);
        const Rayleigh sampling_rayleigh = rayleigh_sampling_phase(a);
        const Vec2 u = rng.next_vec2();
        const PhaseSample s =
            rng.next_float() < c_m ? sample(a.mie_phase, wo, u) : sample(sampling_rayleigh, wo, u);
        const DVec3 wi = glm::normalize(DVec3(s.wi));
        const double mu = glm::dot(d, wi);
        Bands p_r{};
        rayleigh_phase_bands(a, mu, p_r);
        const double p_m = eval_precise(a.mie_phase, mu);
        const double pdf = (1.0 - c_m) * eval_precise(sampling_rayleigh, mu) + c_m * p_m;
        if (pdf > 0.0) {
            const SkySample in =
                reference_sky(sky, p + chosen_t * d, wi, 1e30, false, orders - 1, rng);
            for (int i = 0; i < n; ++i) {
                out.radiance[i] += (chosen_t_r[i] * p_r[i] + chosen_t_m[i] * p_m) * in.radiance[i] /
                                   (pick_prob * pdf);
            }
        }
    }

    // A black ground reflects nothing: no sun and no path from it. (Its path used to be traced
    // anyway and multiplied by the albedo 0: every downward ray forked a second subtree, so a
    // path's cost grew as ~1.5^orders instead of in proportion to them; DISORT's slab over a
    // black surface, 200 paths at 8 orders: 2.5 s -> 0.5 s, tests/sky/sky_slab_test.cpp.)
    bool ground_reflects = false;
    for (int i = 0; i < n; ++i)
        ground_reflects = ground_reflects || a.ground_albedo[i] > 0.0;
    if (hits_ground && reaches_end && !ground_reflects) {
        for (int i = 0; i < n; ++i)
            out.transmittance[i] = 0.0;
    } else if (hits_ground && reaches_end) {
        // Lambertian ground: direct sun (one event) and, with orders left, one cosine-sampled
        // path for the light from the sky (the weight albedo/pi * cos / (cos/pi) = albedo).
        const DVec3 x = p + t_exit * d;
        const DVec3 normal = glm::normalize(x - a.center());
        const double cos_sun = glm::dot(normal, sky.sun_direction);
        Bands lit{};
        if (cos_sun > -sky.sun_radius_rad) {
            const Bands t_sun = sun_transmittance(sky, x, sun_steps);
            for (int i = 0; i < n; ++i)
                lit[i] = std::max(0.0, cos_sun) * t_sun[i] / kPiD;
        }
        if (orders > 1) {
            const DVec3 wi = sample_cosine(normal, rng.next_float(), rng.next_float());
            const SkySample in =
                reference_sky(sky, x + 1e-3 * normal, wi, 1e30, false, orders - 1, rng);
            for (int i = 0; i < n; ++i)
                lit[i] += in.radiance[i];  // albedo/pi * L_in * cos / (cos/pi), albedo below
        }
        for (int i = 0; i < n; ++i)
            out.radiance[i] += out.transmittance[i] * a.ground_albedo[i] * lit[i];
        for (int i = 0; i < n; ++i)
            out.transmittance[i] = 0.0;
    } else if (!hits_ground && reaches_end && sun_disc) {
        const Bands disc = sky.sun_disc(mu_sun);
        for (int i = 0; i < n; ++i)
            out.radiance[i] += out.transmittance[i] * disc[i];
    }
    return out;
}

}  // namespace kasumi
