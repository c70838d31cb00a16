// Fast-sky frame time (issue #6, "Performance"): the median time of a 1280x720, 1 spp frame of
// a sunset scene with aerial perspective in fast mode (scene load, sky tables, render; the EXR
// is not written), the time per frame of a whole sequence (kasumi sequence's own loop: reuse,
// render, EXR written), and the fast mode's error against the reference at the frame's sun
// elevation (relative luminance over the 36-direction dome of tests/sky/sky_fast_test.cpp).
// Wall time and the process's CPU time (user + system) are both reported: on a loaded machine
// only the CPU time is comparable between runs.
//   sky_bench [--scene S] [--sequence S] [--reps N] [--frames N] [--paths N] [--out DIR]
//             [--aovs all|none|LIST] [--compression zip|piz|rle|none] [--write-queue N]
#include "bench/bench_timing.h"
#include "gi/gi.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "sequence/sequence.h"
#include "sky/atmosphere_json.h"
#include "sky/sky_luts.h"
#include "sky/sky_reference.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace kasumi;

namespace {

/// Max and mean relative luminance error of the fast sky against the reference (6 orders,
/// `paths` Monte Carlo paths per direction) over 6 elevations x 6 azimuths from the sun.
void dome_error(double sun_elevation_deg, int paths, double& max_rel, double& mean_rel) {
    const std::vector<double> nm{680.0, 550.0, 440.0};
    SunDesc sun;
    sun.elevation_deg = sun_elevation_deg;
    SkySettings settings;
    settings.mode = SkyMode::Reference;
    settings.orders = 6;
    settings.view_steps = 64;
    settings.sun_steps = 24;
    const auto sky = make_sky_scene(default_earth_atmosphere(nm, nm), sun, settings);
    SkyLuts luts(*sky);
    const DVec3 camera(0.0, 1.5, 0.0);
    luts.build_sky_view(*sky, camera);
    max_rel = mean_rel = 0.0;
    int count = 0;
    for (const double elev : {2.0, 10.0, 20.0, 35.0, 55.0, 80.0}) {
        for (const double az : {0.0, 36.0, 72.0, 108.0, 144.0, 180.0}) {
            const DVec3 d = sun_direction(elev, az + sun.azimuth_deg);
            Bands fast{};
            luts.sky_view(*sky, d, fast);
            double sum = 0.0;
            for (int k = 0; k < paths; ++k) {
                Pcg32 rng(static_cast<uint64_t>(k) * 7919u + 17u, static_cast<uint64_t>(count));
                sum += luminance(sky->to_rgb(
                    reference_sky(*sky, camera, d, 1e30, false, settings.orders, rng).radiance));
            }
            const double y_ref = sum / paths, y_fast = luminance(sky->to_rgb(fast));
            const double rel = std::abs(y_fast - y_ref) / y_ref;
            max_rel = std::max(max_rel, rel);
            mean_rel += rel;
            ++count;
        }
    }
    mean_rel /= count;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene = "data/scenes/sunset.json", sequence = "data/scenes/sunset_sequence.json";
    std::string out = "/tmp/kasumi_sky_bench";
    int reps = 5, frames = 240, paths = 128;
    uint32_t aovs = kAovAll;
    ExrCompression compression = ExrCompression::Zip;
    std::string aovs_text = "all", compression_text = "zip";
    size_t write_queue = 1;
    const char* usage =
        "usage: sky_bench [--scene S] [--sequence S] [--reps N] [--frames N] [--paths N] "
        "[--out DIR] [--aovs all|none|LIST] [--compression zip|piz|rle|none] "
        "[--write-queue N (0: write each frame before the next)]\n";
    for (int i = 1; i < argc; i += 2) {
        const std::string key = argv[i];
        if (key == "--help" || key == "-h") {
            std::printf("%s", usage);
            return 0;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "%s needs a value\n%s", key.c_str(), usage);
            return 2;
        }
        const std::string value = argv[i + 1];
        if (key == "--aovs") {
            aovs_text = value;
            if (!parse_film_aovs(value, aovs)) {
                std::fprintf(stderr, "bad --aovs %s\n", value.c_str());
                return 2;
            }
        } else if (key == "--compression") {
            compression_text = value;
            if (!parse_exr_compression(value, compression)) {
                std::fprintf(stderr, "bad --compression %s\n", value.c_str());
                return 2;
            }
        } else if (key == "--write-queue")
            write_queue = static_cast<size_t>(std::max(0, std::atoi(value.c_str())));
        else if (key == "--scene")
            scene = value;
        else if (key == "--sequence")
            sequence = value;
        else if (key == "--reps")
            reps = std::max(1, std::atoi(value.c_str()));
        else if (key == "--frames")
            frames = std::max(0, std::atoi(value.c_str()));
        else if (key == "--paths")
            paths = std::max(0, std::atoi(value.c_str()));
        else if (key == "--out")
            out = value;
        else {
            std::fprintf(stderr, "unknown option %s\n%s", key.c_str(), usage);
            return 2;
        }
    }
    std::printf("scene %s, %d repetitions\n", scene.c_str(), reps);
    std::vector<double> wall, cpu, setup_wall, setup_cpu;
    double sun_elevation = 0.0;
    for (int r = 0; r < reps; ++r) {
        const double w0 = wall_seconds(), c0 = cpu_seconds();
        SceneDesc desc = load_scene(scene);
        if (desc.sky)
            sun_elevation = desc.sky->sun.elevation_deg;
        const SceneRuntime runtime(std::move(desc), make_gi_method);
        const double w1 = wall_seconds(), c1 = cpu_seconds();
        RenderOptions options;
        options.progress = false;
        const RenderResult result = render_image(runtime, options);
        const double w2 = wall_seconds(), c2 = cpu_seconds();
        setup_wall.push_back(w1 - w0);
        setup_cpu.push_back(c1 - c0);
        wall.push_back(w2 - w0);
        cpu.push_back(c2 - c0);
        std::printf("  frame %d: %.3f s wall (setup %.3f), %.3f s CPU (setup %.3f), %d threads\n",
                    r, w2 - w0, w1 - w0, c2 - c0, c1 - c0, result.threads);
    }
    std::printf("single frame median: %.3f s wall (setup %.3f), %.3f s CPU (setup %.3f)\n",
                median(wall), median(setup_wall), median(cpu), median(setup_cpu));

    {
        // The sky's own share of the setup: sun-independent tables, then per-frame tables.
        SceneDesc desc = load_scene(scene);
        if (desc.sky && desc.sky->settings.mode == SkyMode::Fast) {
            std::vector<double> tables_wall, tables_cpu, frame_wall, frame_cpu;
            std::shared_ptr<const SkyLuts> tables;
            for (int r = 0; r < reps; ++r) {
                const double w0 = wall_seconds(), c0 = cpu_seconds();
                tables = std::make_shared<const SkyLuts>(*desc.sky);
                const double w1 = wall_seconds(), c1 = cpu_seconds();
                const SkyRenderer frame_sky(desc.sky, desc.camera.position, tables);
                const double w2 = wall_seconds(), c2 = cpu_seconds();
                tables_wall.push_back(w1 - w0);
                tables_cpu.push_back(c1 - c0);
                frame_wall.push_back(w2 - w1);
                frame_cpu.push_back(c2 - c1);
            }
            std::printf(
                "sky tables median: transmittance + multiple scattering %.3f s wall, "
                "%.3f s CPU; per frame (sky view + irradiance) %.3f s wall, %.3f s CPU\n",
                median(tables_wall), median(tables_cpu), median(frame_wall), median(frame_cpu));
        }
    }

    if (frames > 0) {
        std::filesystem::remove_all(out);
        SequenceOptions options;
        options.scene_path = sequence;
        for (int f = 0; f < frames; ++f)
            options.frames.push_back(f);
        options.output_pattern = out + "/sky.####.exr";
        options.skip_existing = false;
        options.log = nullptr;
        options.aovs = aovs;
        options.compression = compression;
        options.write_queue = write_queue;
        const double c0 = cpu_seconds();
        const SequenceSummary s = run_sequence(options);
        const double c1 = cpu_seconds();
        const double n = static_cast<double>(std::max<size_t>(1, s.rendered));
        std::printf(
            "sequence %s, %zu frames (aovs %s, compression %s, write queue %zu): %.3f s wall "
            "per frame (%.3f rendering, %.3f writing), %.3f s CPU per "
            "frame\n",
            sequence.c_str(), s.rendered, aovs_text.c_str(), compression_text.c_str(), write_queue,
            s.seconds / n, s.render_seconds / n, s.write_seconds / n, (c1 - c0) / n);
        std::filesystem::remove_all(out);
    }
    if (paths > 0) {
        double max_rel = 0.0, mean_rel = 0.0;
        dome_error(sun_elevation, paths, max_rel, mean_rel);
        std::printf(
            "fast vs reference at sun %.1f deg (%d paths per direction): max %.1f%%, "
            "mean %.1f%% relative luminance error over the dome\n",
            sun_elevation, paths, 100.0 * max_rel, 100.0 * mean_rel);
    }
    return 0;
}
