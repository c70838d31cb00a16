// Fast sky: accuracy against the reference and frame time in one table (issue #22, part 3).
// Per sun elevation:
//   psnr_dB       PSNR of luminance over the dome: 10 log10(peak² / MSE), peak the largest
//                 reference luminance over the dome's directions (the sun's disc left out), MSE
//                 the mean squared difference fast - reference with the reference's own noise
//                 taken out: the reference is two independent halves A and B of its paths, and
//                 E[(fast - (A + B)/2)²] = error² + E[(A - B)²] / 4 (as bench/vdb_image_compare
//                 does for images), so MSE = raw MSE - mean((A - B)²) / 4.
//   raw_dB        the same without the noise taken out; noise_dB the reference noise's own
//                 PSNR (10 log10(peak² / (mean((A - B)²) / 4))): the measurement is trustworthy
//                 where noise_dB is well above psnr_dB.
//   single_dB     single scattering alone: the fast tables without multiple scattering against
//                 the deterministic 1-order reference (the same peak): the tables' and the
//                 quadrature's error without the multiple-scattering approximation.
//   march_dB      the fast sky marched per direction (SkyLuts::march, 160 nodes) instead of
//                 read from the sky-view table: the table's own interpolation error is the
//                 difference between march_dB and psnr_dB.
//   signed_%      mean of (fast - reference) / reference over the dome (bias).
//   frame_s       median wall time (and CPU time) of the 1280 x 720 frame of --scene with its
//                 sun at that elevation (scene load, sky tables, render; no image written).
// The dome: an equal-area grid over the upper hemisphere on the sun's side of its vertical plane
// (the sky is symmetric about it): `rings` rings with sin(elevation) = (i + 0.5) / rings and
// `azimuths` azimuths (j + 0.5) 180 / azimuths from the sun. Camera 1.5 m above the ground of
// the default (Bruneton 2017) atmosphere at 680, 550, 440 nm.
//   sky_accuracy [--suns LIST] [--rings N] [--azimuths N] [--paths N] [--orders N]
//                [--reps N] [--scene S] [--cache DIR|none] [--no-frame]
#include "gi/gi.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "sky/atmosphere_json.h"
#include "sky/sky_luts.h"
#include "sky/sky_reference.h"

#include <sys/resource.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace kasumi;

namespace {

double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double wall_seconds() {
    using Clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Options {
    std::vector<double> suns{2.0, 10.0, 30.0, 60.0, -2.0, -4.0};
    int rings = 12, azimuths = 16, paths = 1024, orders = 6, reps = 3;
    int view_steps = 64, sun_steps = 24;
    std::string scene = "data/scenes/sunset.json";
    std::string cache = "/tmp/kasumi_sky_accuracy";
    bool frame = true;
};

std::vector<DVec3> dome(const Options& o) {
    std::vector<DVec3> dirs;
    for (int i = 0; i < o.rings; ++i) {
        const double elev_deg = std::asin((i + 0.5) / o.rings) * 180.0 / kPiD;
        for (int j = 0; j < o.azimuths; ++j)
            dirs.push_back(sun_direction(elev_deg, (j + 0.5) * 180.0 / o.azimuths));
    }
    return dirs;
}

std::shared_ptr<const SkyScene> make_sky(const Options& o, double sun_deg, int orders) {
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

const DVec3 kCamera(0.0, 1.5, 0.0);

/// Reference luminance per direction, the two halves of the paths (A: paths [0, P/2), B: the
/// rest); read from / written to the cache (its name holds every parameter of the reference).
void reference(const Options& o, double sun_deg, const std::vector<DVec3>& dirs,
               std::vector<double>& half_a, std::vector<double>& half_b) {
    std::ostringstream name;
    name << o.cache << "/ref_sun" << sun_deg << "_r" << o.rings << "_a" << o.azimuths << "_p"
         << o.paths << "_o" << o.orders << "_v" << o.view_steps << "_s" << o.sun_steps << ".txt";
    half_a.assign(dirs.size(), 0.0);
    half_b.assign(dirs.size(), 0.0);
    if (o.cache != "none") {
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
    if (o.cache != "none") {
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

struct Row {
    double psnr_db = 0.0, raw_db = 0.0, noise_db = 0.0, single_db = 0.0, march_db = 0.0;
    double signed_rel = 0.0, frame_wall = 0.0, frame_cpu = 0.0;
};

Row measure(const Options& o, double sun_deg) {
    const std::vector<DVec3> dirs = dome(o);
    std::vector<double> a, b;
    reference(o, sun_deg, dirs, a, b);
    const auto sky = make_sky(o, sun_deg, o.orders);
    SkyLuts luts(*sky);
    luts.build_sky_view(*sky, kCamera);
    SkyLuts single(luts);
    single.disable_multiple_scattering();
    single.build_sky_view(*sky, kCamera);
    const auto sky_single = make_sky(o, sun_deg, 1);
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
        Pcg32 rng(1, 1);
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
    Row row;
    row.psnr_db = psnr(peak, std::max(0.0, se - noise) / dn);
    row.raw_db = psnr(peak, se / dn);
    row.noise_db = psnr(peak, noise / dn);
    row.single_db = psnr(peak, se_single / dn);
    row.march_db = psnr(peak, std::max(0.0, se_march - noise) / dn);
    row.signed_rel = signed_sum / dn;
    if (o.frame) {
        std::vector<double> wall, cpu;
        std::ostringstream value;
        value << sun_deg;
        for (int r = 0; r < o.reps; ++r) {
            const double w0 = wall_seconds(), c0 = cpu_seconds();
            SceneDesc desc = load_scene(o.scene, {{"/sun/elevation_deg", value.str()}});
            const SceneRuntime runtime(std::move(desc), make_gi_method);
            RenderOptions options;
            options.progress = false;
            render_image(runtime, options);
            wall.push_back(wall_seconds() - w0);
            cpu.push_back(cpu_seconds() - c0);
        }
        row.frame_wall = median(wall);
        row.frame_cpu = median(cpu);
    }
    return row;
}

std::vector<double> parse_list(const std::string& text) {
    std::vector<double> out;
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ','))
        out.push_back(std::atof(item.c_str()));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    const char* usage =
        "usage: sky_accuracy [--suns LIST] [--rings N] [--azimuths N] [--paths N] [--orders N] "
        "[--view-steps N] [--sun-steps N] [--reps N] [--scene S] [--cache DIR|none] "
        "[--no-frame]\n";
    for (int i = 1; i < argc; ++i) {
        const std::string key = argv[i];
        if (key == "--help" || key == "-h") {
            std::printf("%s", usage);
            return 0;
        }
        if (key == "--no-frame") {
            o.frame = false;
            continue;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "%s needs a value\n%s", key.c_str(), usage);
            return 2;
        }
        const std::string value = argv[++i];
        const int n = std::max(1, std::atoi(value.c_str()));
        if (key == "--suns")
            o.suns = parse_list(value);
        else if (key == "--rings")
            o.rings = n;
        else if (key == "--azimuths")
            o.azimuths = n;
        else if (key == "--paths")
            o.paths = std::max(2, n);
        else if (key == "--orders")
            o.orders = n;
        else if (key == "--view-steps")
            o.view_steps = n;
        else if (key == "--sun-steps")
            o.sun_steps = n;
        else if (key == "--reps")
            o.reps = n;
        else if (key == "--scene")
            o.scene = value;
        else if (key == "--cache")
            o.cache = value;
        else {
            std::fprintf(stderr, "unknown option %s\n%s", key.c_str(), usage);
            return 2;
        }
    }
    std::printf(
        "dome: %d x %d directions (equal area, sun's half); reference: %d orders, %d "
        "paths in two halves, %d view x %d sun nodes; frame: %s\n",
        o.rings, o.azimuths, o.orders, o.paths, o.view_steps, o.sun_steps,
        o.frame ? o.scene.c_str() : "not timed");
    std::printf(
        "sun_deg  psnr_dB  raw_dB  noise_dB  single_dB  march_dB  signed_%%  "
        "frame_wall_s  frame_cpu_s\n");
    for (const double sun : o.suns) {
        const Row r = measure(o, sun);
        std::printf("%7.1f  %7.2f  %6.2f  %8.2f  %9.2f  %8.2f  %+8.2f  %12.3f  %11.3f\n", sun,
                    r.psnr_db, r.raw_db, r.noise_db, r.single_db, r.march_db, 100.0 * r.signed_rel,
                    r.frame_wall, r.frame_cpu);
        std::fflush(stdout);
    }
    return 0;
}
