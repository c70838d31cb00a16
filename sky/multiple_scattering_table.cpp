#include "sky/sky_luts.h"

#include "sky/sky_quadrature.h"
#include "sky/sky_reference.h"
#include "sky/sun_disc_fraction.h"

#include <tbb/parallel_for.h>

namespace kasumi {

namespace {

// Geometry per altitude row and direction zenith (sun independent): each node's radius,
// its up vector's components along the direction's horizontal part (a) and the vertical
// (b), T sigma_s dt per band split into Rayleigh and Mie (the first order's phases).
struct Node {
    double r, a, b;
    int y0;             ///< the table row below the node's radius (its bilinear tap in r, which
    double fy;          ///< stays for every order and sun cosine)
    HorizonAt horizon;  ///< the first order's sun lookups at this radius
    SkyLuts::TransmittanceRow sun_row;  ///< (sun_disc_fraction and transmittance, radius parts)
};
struct DirRay {
    std::vector<Node> nodes;
    std::vector<float> w_rayleigh, w_mie;  ///< [node][band] T sigma_s dt
    std::vector<float> w_sum;              ///< w_rayleigh + w_mie (orders 2 and up)
    bool ground = false;
    double ground_a = 0.0, ground_b = 1.0;
    std::vector<float> t_ground;  ///< [band]
    double cos_t = 0.0, sin_t = 0.0;
};

/// The light of one order above the first along a direction ray, per band: the sum over its
/// nodes of (T sigma_s dt) G_{n-1}(r, mu_y), G bilinear in the table `g` (W x H texels of nb
/// bands) at the node's sun cosine mu_y = sin_s a cos_phi + mu_s b. NB > 0: the band count at
/// compile time (RGB renders: 3), 0: `nb` at run time; the same sums either way.
template <size_t NB>
void add_order_light(const DirRay& ray, const float* g, size_t nb, double sin_s, double cos_phi,
                     double mu_s, double* l) {
    constexpr int W = SkyLuts::kMultipleW;
    if (NB > 0)
        nb = NB;
    const float* w_sum = ray.w_sum.data();
    for (const Node& node : ray.nodes) {
        const double mu_y = sin_s * node.a * cos_phi + mu_s * node.b;
        const double x = std::clamp(SkyLuts::multiple_u(mu_y) * W - 0.5, 0.0, W - 1.0);
        const int x0 = std::min(static_cast<int>(x), W - 2);
        const double fx = x - x0, fy = node.fy;
        const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy,
                     w11 = fx * fy;
        const float* t00 = g + (static_cast<size_t>(node.y0) * W + x0) * nb;
        const float* t10 = t00 + nb;
        const float* t01 = t00 + W * nb;
        const float* t11 = t01 + nb;
        for (size_t b = 0; b < nb; ++b) {
            double gy = 0.0;
            gy += w00 * t00[b];
            gy += w10 * t10[b];
            gy += w01 * t01[b];
            gy += w11 * t11[b];
            l[b] += w_sum[b] * gy;
        }
        w_sum += nb;
    }
}

}  // namespace

void SkyLuts::build_multiple_scattering(const SkyScene& sky) {
    // Multiple scattering, orders by iteration in an isotropic-phase approximation of the
    // higher orders (Hillaire 2020 §5.5 approximates every order above the second by the
    // geometric series 1 / (1 - f_ms) of the *local* transfer factor; in twilight the light
    // comes from lit air far above the shadowed point, where that series fails (33% error at
    // sun -4 deg), so the orders are iterated here as in Bruneton & Neyret 2008, with the
    // radiance of each order averaged over directions, which keeps the table 2D):
    //   G_1(x) = 1/(4 pi) Int L_1(x, w) dw, L_1 single scattering with the true phase plus the
    //            sun-lit ground;
    //   G_n(x) = 1/(4 pi) Int [Int T sigma_s G_{n-1}(y) dt + T albedo/pi E_{n-1}(ground)] dw,
    // E_n the irradiance of order n on the ground (E_0: the direct sun). The table holds
    // Psi_ms = sum_{n=1..N} G_n plus a geometric tail, the radiance (per unit sigma_s, with an
    // isotropic phase) scattered into orders 2 and up; the march adds single scattering with
    // the true phase. Table: (mu_s linear in [-1, 1]) x (sqrt of altitude), texel centres on
    // the ground and the top; directions: kDirCos x kDirAz around x, kNodes nodes per ray.
    const Atmosphere& a = sky.atmosphere;
    const size_t nb = static_cast<size_t>(m_bands);
    constexpr int W = kMultipleW, H = kMultipleH;
    // The first order (the sun's light, with the Mie forward peak) on kDirCos x kDirAz
    // directions; the orders above it (isotropic phase, smooth in azimuth) on kDirCos x
    // kDirAzHigh: half the work, dome PSNR within 0.02 dB at every sun of bench/sky_accuracy
    // (16 x 8 for them lost 0.36 dB at 30 deg: the zenith angle matters, not the azimuth).
    // Both azimuth counts even (symmetry below).
    constexpr int kDirCos = 32, kDirAz = 8, kDirAzHigh = 4, kNodes = 12;
    std::vector<DirRay> rays(static_cast<size_t>(H * kDirCos));
    std::vector<double> altitude(H);
    for (int j = 0; j < H; ++j) {
        const double x = static_cast<double>(j) / (H - 1);
        altitude[static_cast<size_t>(j)] = (m_rt - m_rg) * x * x;
    }
    tbb::parallel_for(0, H * kDirCos, [&](int k) {
        const int j = k / kDirCos, c = k % kDirCos;
        DirRay& ray = rays[static_cast<size_t>(k)];
        ray.cos_t = 1.0 - 2.0 * (c + 0.5) / kDirCos;
        ray.sin_t = std::sqrt(std::max(0.0, 1.0 - ray.cos_t * ray.cos_t));
        const double h = altitude[static_cast<size_t>(j)];
        const DVec3 p(0.0, h, 0.0), d(ray.sin_t, ray.cos_t, 0.0);
        double t0 = 0.0, t1 = 0.0;
        if (!atmosphere_segment(a, p, d, t0, t1, ray.ground))
            return;
        std::vector<double> tau(nb, 0.0);
        for_each_sky_node(a, p, d, t0, t1, kNodes, [&](double t, double dt) {
            const double r =
                std::sqrt(t * t + 2.0 * t * (m_rg + h) * ray.cos_t + (m_rg + h) * (m_rg + h));
            const AtmosphereCoefficients co = atmosphere_coefficients(a, r - m_rg);
            const double y = std::clamp(multiple_v(r) * H - 0.5, 0.0, H - 1.0);
            const int y0 = std::min(static_cast<int>(y), H - 2);
            ray.nodes.push_back({r, t * ray.sin_t / r, (m_rg + h + t * ray.cos_t) / r, y0, y - y0,
                                 horizon_at(r, m_rg, m_sun), transmittance_row(r)});
            for (size_t b = 0; b < nb; ++b) {
                const double tr = std::exp(-(tau[b] + 0.5 * co.sigma_t[b] * dt));
                ray.w_rayleigh.push_back(static_cast<float>(tr * co.sigma_s_rayleigh[b] * dt));
                ray.w_mie.push_back(static_cast<float>(tr * co.sigma_s_mie[b] * dt));
                ray.w_sum.push_back(ray.w_rayleigh.back() + ray.w_mie.back());
                tau[b] += co.sigma_t[b] * dt;
            }
        });
        if (ray.ground) {
            const double r = m_rg;
            ray.ground_a = t1 * ray.sin_t / r;
            ray.ground_b = (m_rg + h + t1 * ray.cos_t) / r;
            for (size_t b = 0; b < nb; ++b)
                ray.t_ground.push_back(static_cast<float>(std::exp(-tau[b])));
        }
    });
    // Sun transmittance at a node (its radius's parts precomputed), sun cosine mu_s there (disc
    // fraction above the horizon): SkyLuts::sun_transmittance's values, bit for bit.
    const HorizonAt ground_horizon = horizon_at(m_rg, m_rg, m_sun);
    const TransmittanceRow ground_row = transmittance_row(m_rg);
    const auto sun_t = [&](const HorizonAt& horizon, const TransmittanceRow& row, double mu_s,
                           double* out) {
        const double fraction = sun_disc_fraction(horizon, mu_s, m_sun);
        if (fraction <= 0.0) {
            for (size_t b = 0; b < nb; ++b)
                out[b] = 0.0;
            return;
        }
        transmittance(row, std::max(mu_s, horizon.sin_horizon), out);
        for (size_t b = 0; b < nb; ++b)
            out[b] *= fraction;
    };
    std::vector<float> g_prev(static_cast<size_t>(W * H) * nb, 0.0f), g_next = g_prev;
    std::vector<float> e_prev(static_cast<size_t>(W) * nb, 0.0f), e_next = e_prev;
    std::vector<double> g_sum(g_prev.size(), 0.0), e_sum(e_prev.size(), 0.0);
    std::vector<double> g_last(g_prev.size(), 0.0), e_last(e_prev.size(), 0.0);
    const auto e_at = [&](const std::vector<float>& e, double mu_s, int b) {
        const double x = std::clamp(multiple_u(mu_s) * W - 0.5, 0.0, W - 1.0);
        const int x0 = std::min(static_cast<int>(x), W - 2);
        const double fx = x - x0;
        return (1 - fx) * e[static_cast<size_t>(x0) * nb + b] +
               fx * e[static_cast<size_t>(x0 + 1) * nb + b];
    };
    const double albedo_over_pi = 1.0 / kPiD;
    const auto half_azimuth_cosines = [](int n_az) {
        std::vector<double> cos_phis(static_cast<size_t>(n_az / 2));
        for (int az = 0; az < n_az / 2; ++az)
            cos_phis[static_cast<size_t>(az)] = std::cos(2.0 * kPiD * (az + 0.5) / n_az);
        return cos_phis;
    };
    const std::vector<double> cos_phis_first = half_azimuth_cosines(kDirAz);
    const std::vector<double> cos_phis_high = half_azimuth_cosines(kDirAzHigh);
    for (int order = 1; order <= kMultipleOrders; ++order) {
        tbb::parallel_for(0, W * H, [&](int texel) {
            const int i = texel % W, j = texel / W;
            const double mu_s = -1.0 + 2.0 * i / (W - 1);
            const double sin_s = std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s));
            // The first order's light splits by its phase: l_r and l_m (Rayleigh and Mie, per
            // direction, without the phase) are weighted by the phases and normalised by the
            // quadrature's own integral of each phase over the sphere (q_r, q_m; 1 exactly),
            // so that the Mie forward peak, which the 16 x 8 directions sample coarsely,
            // carries its whole unit mass (the error of the raw sum, up to tens of percent at
            // some sun cosines, cost 1-2 dB of dome PSNR at the 30 deg sun). l holds the rest
            // (the ground; every later order, isotropic).
            Bands g{}, e{}, l{}, ts{}, l_r{}, l_m{}, g_r{}, g_m{}, e_r{}, e_m{}, q_r{}, p_r{};
            double q_m = 0.0;
            const std::vector<double>& cos_phis = order == 1 ? cos_phis_first : cos_phis_high;
            const double dw = 4.0 * kPiD / (kDirCos * (order == 1 ? kDirAz : kDirAzHigh));
            for (int c = 0; c < kDirCos; ++c) {
                const DirRay& ray = rays[static_cast<size_t>(j * kDirCos + c)];
                // Azimuths phi and 2 pi - phi see the same sun cosines and scattering angles:
                // half of them, counted twice.
                for (const double cos_phi : cos_phis) {
                    std::fill_n(l.begin(), nb, 0.0);
                    std::fill_n(l_r.begin(), nb, 0.0);
                    std::fill_n(l_m.begin(), nb, 0.0);
                    if (order == 1) {
                        for (size_t n = 0; n < ray.nodes.size(); ++n) {
                            const Node& node = ray.nodes[n];
                            const double mu_y = sin_s * node.a * cos_phi + mu_s * node.b;
                            sun_t(node.horizon, node.sun_row, mu_y, ts.data());
                            for (size_t b = 0; b < nb; ++b) {
                                l_r[b] += ray.w_rayleigh[n * nb + b] * ts[b];
                                l_m[b] += ray.w_mie[n * nb + b] * ts[b];
                            }
                        }
                    } else if (nb == 3) {
                        add_order_light<3>(ray, g_prev.data(), nb, sin_s, cos_phi, mu_s, l.data());
                    } else {
                        add_order_light<0>(ray, g_prev.data(), nb, sin_s, cos_phi, mu_s, l.data());
                    }
                    if (ray.ground) {
                        const double mu_g = sin_s * ray.ground_a * cos_phi + mu_s * ray.ground_b;
                        if (order == 1)
                            sun_t(ground_horizon, ground_row, mu_g, ts.data());
                        for (size_t b = 0; b < nb; ++b) {
                            const double e_in = order == 1
                                                    ? std::max(0.0, mu_g) * ts[b]
                                                    : e_at(e_prev, mu_g, static_cast<int>(b));
                            l[b] += ray.t_ground[b] * a.ground_albedo[b] * albedo_over_pi * e_in;
                        }
                    }
                    const double w = 2.0 * dw, w_up = ray.cos_t > 0.0 ? w * ray.cos_t : 0.0;
                    for (size_t b = 0; b < nb; ++b) {
                        g[b] += w * l[b] / (4.0 * kPiD);
                        e[b] += w_up * l[b];
                    }
                    if (order == 1) {
                        // Scattering angle of the first order: sun light (propagating along
                        // -s) turned toward x (along -d): cos = s . d.
                        const double nu = sin_s * ray.sin_t * cos_phi + mu_s * ray.cos_t;
                        rayleigh_phase_bands(a, nu, p_r);
                        const double p_m = eval_precise(a.mie_phase, nu);
                        q_m += w * p_m;
                        for (size_t b = 0; b < nb; ++b) {
                            q_r[b] += w * p_r[b];
                            g_r[b] += w * p_r[b] * l_r[b] / (4.0 * kPiD);
                            g_m[b] += w * p_m * l_m[b] / (4.0 * kPiD);
                            e_r[b] += w_up * p_r[b] * l_r[b];
                            e_m[b] += w_up * p_m * l_m[b];
                        }
                    }
                }
            }
            if (order == 1) {
                for (size_t b = 0; b < nb; ++b) {
                    g[b] += g_r[b] / q_r[b] + g_m[b] / q_m;
                    e[b] += e_r[b] / q_r[b] + e_m[b] / q_m;
                }
            }
            for (size_t b = 0; b < nb; ++b) {
                g_next[static_cast<size_t>(texel) * nb + b] = static_cast<float>(g[b]);
                if (j == 0)
                    e_next[static_cast<size_t>(i) * nb + b] = static_cast<float>(e[b]);
            }
        });
        g_last.assign(g_prev.begin(), g_prev.end());
        e_last.assign(e_prev.begin(), e_prev.end());
        std::swap(g_prev, g_next);
        std::swap(e_prev, e_next);
        for (size_t k = 0; k < g_sum.size(); ++k)
            g_sum[k] += g_prev[k];
        for (size_t k = 0; k < e_sum.size(); ++k)
            e_sum[k] += e_prev[k];
    }
    // Orders beyond the last: a geometric tail with the ratio of the last two orders per texel
    // and band, capped at 0.9 (the ratio tends to the medium's albedo-weighted transfer
    // fraction, well below 1 for the Earth's atmosphere).
    const auto tail = [](double last, double before) {
        if (!(before > 0.0) || !(last > 0.0))
            return 0.0;
        const double q = std::min(0.9, last / before);
        return last * q / (1.0 - q);
    };
    auto multiple_table = std::make_shared<std::vector<float>>(g_sum.size());
    for (size_t k = 0; k < g_sum.size(); ++k)
        (*multiple_table)[k] = static_cast<float>(g_sum[k] + tail(g_prev[k], g_last[k]));
    auto ground_table = std::make_shared<std::vector<float>>(e_sum.size());
    for (size_t k = 0; k < e_sum.size(); ++k)
        (*ground_table)[k] = static_cast<float>(e_sum[k] + tail(e_prev[k], e_last[k]));
    m_multiple = multiple_table;
    m_ground_irradiance = ground_table;
}

}  // namespace kasumi
