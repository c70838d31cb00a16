// Fast sky: accuracy against the reference and frame time in one table (issue #22, part 3).
// Per sun elevation, the PSNRs of sky/sky_dome_psnr.h:
//   psnr_dB    PSNR of luminance over the dome, the reference's own noise taken out (two halves);
//   raw_dB     the same with the noise left in; noise_dB the reference noise's own PSNR (the
//              measurement is trustworthy where noise_dB is well above psnr_dB);
//   single_dB  single scattering alone (fast tables without multiple scattering against the
//              deterministic 1-order reference, the same peak);
//   march_dB   marched per direction (160 nodes) instead of read from the sky-view table;
//   signed_%   mean of (fast - reference) / reference over the dome (bias);
//   frame_s    median wall and CPU time of the 1280 x 720 frame of --scene with its sun at
//              that elevation (scene load, sky tables, render; no image written).
//   sky_accuracy [--suns LIST] [--rings N] [--azimuths N] [--paths N] [--orders N]
//                [--reps N] [--scene S] [--cache DIR|none] [--no-frame]
#include "bench/bench_timing.h"
#include "gi/gi.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "sky/sky_dome_psnr.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

using namespace kasumi;

namespace {

struct Options {
    std::vector<double> suns{2.0, 10.0, 30.0, 60.0, -2.0, -4.0};
    DomePsnrOptions dome;
    int reps = 3;
    std::string scene = "data/scenes/sunset.json";
    bool frame = true;
};

/// One sun elevation: the dome's accuracy and the frame's median times (seconds).
struct Row {
    DomePsnr dome;
    double frame_wall = 0.0, frame_cpu = 0.0;
};

Row measure(const Options& o, double sun_deg) {
    Row row;
    row.dome = dome_psnr(sun_deg, o.dome);
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
    o.dome.cache = "/tmp/kasumi_sky_accuracy";
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
            o.dome.rings = n;
        else if (key == "--azimuths")
            o.dome.azimuths = n;
        else if (key == "--paths")
            o.dome.paths = std::max(2, n);
        else if (key == "--orders")
            o.dome.orders = n;
        else if (key == "--view-steps")
            o.dome.view_steps = n;
        else if (key == "--sun-steps")
            o.dome.sun_steps = n;
        else if (key == "--reps")
            o.reps = n;
        else if (key == "--scene")
            o.scene = value;
        else if (key == "--cache")
            o.dome.cache = value == "none" ? "" : value;
        else {
            std::fprintf(stderr, "unknown option %s\n%s", key.c_str(), usage);
            return 2;
        }
    }
    std::printf(
        "dome: %d x %d directions (equal area, sun's half); reference: %d orders, %d "
        "paths in two halves, %d view x %d sun nodes; frame: %s\n",
        o.dome.rings, o.dome.azimuths, o.dome.orders, o.dome.paths, o.dome.view_steps,
        o.dome.sun_steps, o.frame ? o.scene.c_str() : "not timed");
    std::printf(
        "sun_deg  psnr_dB  raw_dB  noise_dB  single_dB  march_dB  signed_%%  "
        "frame_wall_s  frame_cpu_s\n");
    for (const double sun : o.suns) {
        const Row row = measure(o, sun);
        const DomePsnr& r = row.dome;
        std::printf("%7.1f  %7.2f  %6.2f  %8.2f  %9.2f  %8.2f  %+8.2f  %12.3f  %11.3f\n", sun,
                    r.psnr_db, r.raw_db, r.noise_db, r.single_db, r.march_db, 100.0 * r.signed_rel,
                    row.frame_wall, row.frame_cpu);
        std::fflush(stdout);
    }
    return 0;
}
