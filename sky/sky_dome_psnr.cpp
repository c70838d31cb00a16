#include "sky/sky_dome_psnr.h"

#include "sky/atmosphere_json.h"
#include "sky/sky_luts.h"
#include "sky/sky_reference.h"

#include <tbb/parallel_for.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace kasumi {

namespace {

const DVec3 kCamera(0.0, 1.5, 0.0);

std::shared_ptr<const SkyScene> make_sky(const DomePsnrOptions& o, double sun_deg, int orders) {
    const std::vector<double> nm{680.0, 550.0, 440.0};
    SunDesc sun;
    sun.elevation_deg = sun_deg;
    sun.azimuth_deg = 0.0;
    SkySettings settings;
    settings.mode = SkyMode::Reference;
    settings.orders = orders;
    settings.view_steps = o.view_steps;
    settings.sun_steps = o.sun_steps;
    return make_sky_scene(default_earth_atmosphere(nm, nm), sun, settings);
}

/// Reference luminance per direction in two halves (A: paths [0, P/2), B: the rest), each
/// path's stream seeded by its index and the direction's: the same for any thread count.
void reference(const DomePsnrOptions& o, double sun_deg, const std::vector<DVec3>& dirs,
               std::vector<double>& half_a, std::vector<double>& half_b) {
    std::ostringstream name;
    name << o.cache << "/ref_sun" << sun_deg << "_r" << o.rings << "_a" << o.azimuths << "_p"
         << o.paths << "_o" << o.orders << "_v" << o.view_steps << "_s" << o.sun_steps << ".txt";
    half_a.assign(dirs.size(), 0.0);
    half_b.assign(dirs.size(), 0.0);
    if (!o.cache.empty()) {
        std::ifstream in(name.str());
        size_t k = 0;
        while (k < dirs.size() && in >> half_a[k] >> half_b[k])
            ++k;
        if (k == dirs.size())
            return;
    }
    const auto sky = make_sky(o, sun_deg, o.orders);
    const int half = std::max(1, o.paths / 2);
    tbb::parallel_for(0, static_cast<int>(dirs.size()), [&](int k) {
        double sum[2] = {0.0, 0.0};
        for (int p = 0; p < 2 * half; ++p) {
            Pcg32 rng(static_cast<uint64_t>(p) * 7919u + 17u, static_cast<uint64_t>(k));
            sum[p / half] +=
                luminance(sky->to_rgb(reference_sky(*sky, kCamera, dirs[static_cast<size_t>(k)],
                                                    1e30, false, o.orders, rng)
                                          .radiance));
        }
        half_a[static_cast<size_t>(k)] = sum[0] / half;
        half_b[static_cast<size_t>(k)] = sum[1] / half;
    });
    if (!o.cache.empty()) {
        std::filesystem::create_directories(o.cache);
        std::ofstream out(name.str());
        out.precision(17);
        for (size_t k = 0; k < dirs.size(); ++k)
            out << half_a[k] << ' ' << half_b[k] << '\n';
    }
}

double psnr(double peak, double mse) {
    return mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : 999.0;
}

}  // namespace

std::vector<DVec3> equal_area_dome(int rings, int azimuths) {
    std::vector<DVec3> dirs;
    for (int i = 0; i < rings; ++i) {
        const double elev_deg = std::asin((i + 0.5) / rings) * 180.0 / kPiD;
        for (int j = 0; j < azimuths; ++j)
            dirs.push_back(sun_direction(elev_deg, (j + 0.5) * 180.0 / azimuths));
    }
    return dirs;
}

DomePsnr dome_psnr(double sun_elevation_deg, const DomePsnrOptions& o) {
    const std::vector<DVec3> dirs = equal_area_dome(o.rings, o.azimuths);
    std::vector<double> a, b;
    reference(o, sun_elevation_deg, dirs, a, b);
    const auto sky = make_sky(o, sun_elevation_deg, o.orders);
    SkyLuts luts(*sky);
    luts.build_sky_view(*sky, kCamera);
    SkyLuts single(luts);
    single.disable_multiple_scattering();
    single.build_sky_view(*sky, kCamera);
    const auto sky_single = make_sky(o, sun_elevation_deg, 1);
    const size_t n = dirs.size();
    std::vector<double> fast(n), marched(n), fast_single(n), ref_single(n);
    tbb::parallel_for(0, static_cast<int>(n), [&](int kk) {
        const size_t k = static_cast<size_t>(kk);
        Bands l{}, t{};
        luts.sky_view(*sky, dirs[k], l);
        fast[k] = luminance(sky->to_rgb(l));
        luts.march(*sky, kCamera, dirs[k], 1e30, 160, l, t);
        marched[k] = luminance(sky->to_rgb(l));
        single.sky_view(*sky, dirs[k], l);
        fast_single[k] = luminance(sky->to_rgb(l));
        Pcg32 rng(1, 1);  // one order: no random numbers drawn
        ref_single[k] = luminance(sky->to_rgb(
            reference_sky(*sky_single, kCamera, dirs[k], 1e30, false, 1, rng).radiance));
    });
    double peak = 0.0, se = 0.0, noise = 0.0, se_single = 0.0, se_march = 0.0, signed_sum = 0.0;
    for (size_t k = 0; k < n; ++k) {
        const double ref = 0.5 * (a[k] + b[k]);
        peak = std::max(peak, ref);
        se += (fast[k] - ref) * (fast[k] - ref);
        se_march += (marched[k] - ref) * (marched[k] - ref);
        noise += (a[k] - b[k]) * (a[k] - b[k]) / 4.0;
        se_single += (fast_single[k] - ref_single[k]) * (fast_single[k] - ref_single[k]);
        if (ref > 0.0)
            signed_sum += (fast[k] - ref) / ref;
    }
    const double dn = static_cast<double>(n);
    DomePsnr out;
    out.psnr_db = psnr(peak, std::max(0.0, se - noise) / dn);
    out.raw_db = psnr(peak, se / dn);
    out.noise_db = psnr(peak, noise / dn);
    out.single_db = psnr(peak, se_single / dn);
    out.march_db = psnr(peak, std::max(0.0, se_march - noise) / dn);
    out.signed_rel = signed_sum / dn;
    return out;
}

}  // namespace kasumi
