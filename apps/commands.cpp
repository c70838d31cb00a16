#include "apps/commands.h"

#include "apps/illuminance_command.h"
#include "apps/render_report.h"
#include "apps/scene_options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "gi/gi.h"
#include "render/frame_output.h"
#include "render/probe.h"
#include "render/probe_json.h"
#include "render/renderer.h"
#include "sequence/sequence_cache.h"
#include "volume/transmittance.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

namespace kasumi {

namespace {

int g_exit_code = 0;
std::atomic<bool> g_cancel{false};
volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int signal) {
    g_signal = signal;
    g_cancel.store(true);
}

void print_json(const Json& j) {
    std::cout << j.dump(2) << std::endl;
}

}  // namespace

int command_exit_code() {
    return g_exit_code;
}
void set_command_exit_code(int code) {
    g_exit_code = code;
}
std::string version_string() {
    return kKasumiVersion;
}

void check_output_writable(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw_output_error(path + ": is a directory, expected a file name");
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) {
        std::filesystem::create_directories(parent, ec);
        if (ec)
            throw_output_error(path + ": cannot create directory " + parent.string() + ": " +
                               ec.message());
    }
    const AtomicFile probe(path);  // creates and, unused, removes a temporary beside `path`
}

void add_render_command(CLI::App& root) {
    struct Options {
        SceneOptions scene;
        std::string output;
        std::string preview;
        bool no_preview = false;
        int spp = 0;
        int64_t seed = -1;
        int threads = 0;
        std::string res;
        int64_t frame = 0;
        std::string aovs = "all";
        std::string compression = "zip";
        std::string pixel_type;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = root.add_subcommand("render", "render a scene to EXR and a PNG preview");
    options->scene.add_to(*cmd);
    cmd->add_option("-o,--output", options->output, "EXR output (default out/<scene>.exr)");
    auto* preview = cmd->add_option("--preview", options->preview,
                                    "PNG preview through OpenColorIO (default: beside the EXR)");
    cmd->add_flag("--no-preview", options->no_preview, "write no PNG preview")->excludes(preview);
    cmd->add_option("--spp", options->spp, "samples per pixel (overrides film.spp)")
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--seed", options->seed, "random seed (overrides render.seed)")
        ->check(CLI::Range(int64_t{0}, std::numeric_limits<int64_t>::max()));
    cmd->add_option("--threads", options->threads, "worker threads (0: all)")
        ->check(CLI::Range(0, 1024));
    cmd->add_option("--res", options->res, "resolution WxH (overrides film.width/height)");
    cmd->add_option("--frame", options->frame,
                    "frame of an animated scene: keyframed values and random numbers (default 0)")
        ->check(CLI::Range(int64_t{0}, int64_t{4294967295}));
    cmd->add_option("--aovs", options->aovs,
                    "EXR channels beside R, G, B, A: all (default), none, or a list of "
                    "albedo, depth, surface, volume, transmittance");
    cmd->add_option("--compression", options->compression,
                    "EXR compression, all lossless: zip (default), piz, rle, none");
    cmd->add_option("--pixel-type", options->pixel_type,
                    "EXR pixel type of R, G, B, A (overrides film.pixel_type): float (default) "
                    "or half (AOVs stay float; beyond 65504 saturates, with a warning)")
        ->check(CLI::IsMember({"float", "half"}));
    cmd->callback([options] {
        SceneOptions scene_options = options->scene;
        if (options->spp > 0)
            scene_options.sets.push_back("/film/spp=" + std::to_string(options->spp));
        if (!options->pixel_type.empty())
            scene_options.sets.push_back("/film/pixel_type=\"" + options->pixel_type + "\"");
        if (options->seed >= 0)
            scene_options.sets.push_back("/render/seed=" + std::to_string(options->seed));
        if (!options->res.empty()) {
            const Resolution res = parse_resolution_arg(options->res);
            scene_options.sets.push_back("/film/width=" + std::to_string(res.width));
            scene_options.sets.push_back("/film/height=" + std::to_string(res.height));
        }
        StageTimes times;
        const auto load_start = std::chrono::steady_clock::now();
        SceneDesc desc = scene_options.load(options->frame);
        times.load_s = seconds_since(load_start);

        OutputPaths paths;
        parse_output_format(options->aovs, options->compression, paths.aovs, paths.compression);
        const std::string stem = std::filesystem::path(desc.file).stem().string();
        paths.exr = options->output.empty() ? "out/" + stem + ".exr" : options->output;
        if (!options->no_preview) {
            paths.preview =
                options->preview.empty()
                    ? std::filesystem::path(paths.exr).replace_extension(".png").string()
                    : options->preview;
        }

        if (!paths.preview.empty()) {
            check_distinct_outputs(
                paths.exr, paths.preview,
                options->preview.empty()
                    ? "-o " + paths.exr +
                          ": its preview PNG beside it would have the same name; name the EXR "
                          "*.exr, or give --preview FILE or --no-preview"
                    : "--preview " + paths.preview +
                          " is the EXR output (-o) too: give the preview another name");
        }
        // Before the work: a render must not end in "cannot write" hours later.
        check_output_writable(paths.exr);
        if (!paths.preview.empty())
            check_output_writable(paths.preview);

        const auto build_start = std::chrono::steady_clock::now();
        const SceneRuntime runtime(std::move(desc), make_gi_method);
        times.build_s = seconds_since(build_start);
        add_stage_parts(times, runtime);
        if (scene_options.verbose)
            std::fprintf(stderr, "plan:\n%s", plan_to_text(runtime.plan()).c_str());
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        RenderOptions render_options;
        render_options.threads = options->threads;
        render_options.frame = static_cast<uint32_t>(options->frame);
        render_options.progress = !scene_options.quiet;
        render_options.cancel = &g_cancel;
        render_options.aovs = paths.aovs;
        const RenderResult result = render_image(runtime, render_options);
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);

        times.render_s = result.seconds;
        const auto write_start = std::chrono::steady_clock::now();
        const ExrWriteReport written =
            write_render_outputs(runtime, result, paths, options->frame, times);
        times.write_s = seconds_since(write_start);
        if (scene_options.verbose) {
            std::fputs(format_stats(runtime, result, times).c_str(), stderr);
            std::fputs(format_write_stats(runtime, written).c_str(), stderr);
        }
        std::fputs(half_saturation_warning(written, paths.exr).c_str(), stderr);
        if (!scene_options.quiet) {
            std::fprintf(stderr, "wrote %s%s%s (%.2f s)\n", paths.exr.c_str(),
                         paths.preview.empty() ? "" : " and ", paths.preview.c_str(),
                         result.seconds);
        }
        if (result.counters.nonfinite_samples > 0) {
            std::fprintf(stderr, "kasumi: warning: %llu non-finite samples were dropped\n",
                         static_cast<unsigned long long>(result.counters.nonfinite_samples));
        }
        if (result.counters.bounded_marches > 0) {
            std::fprintf(
                stderr,
                "kasumi: warning: the march step (render.volume.step_m or step_voxels) "
                "%g m needed more than 65536 nodes on %llu camera rays: their step was "
                "lengthened to 1/65536 of their way through the media\n",
                static_cast<double>(march_step_m(runtime.media(), runtime.desc().render.volume)),
                static_cast<unsigned long long>(result.counters.bounded_marches));
        }
        if (result.interrupted) {
            std::fprintf(stderr, "kasumi: interrupted; partial image written\n");
            set_command_exit_code(g_signal == SIGTERM ? 143 : 130);
        }
    });
}

void add_plan_command(CLI::App& root) {
    struct Options {
        SceneOptions scene;
        bool json = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd =
        root.add_subcommand("plan", "print the stages a scene calls for and those it skips");
    options->scene.add_to(*cmd);
    cmd->add_flag("--json", options->json, "one JSON object on stdout");
    cmd->callback([options] {
        const SceneDesc desc = options->scene.load();
        const Plan plan = make_plan(desc);
        if (options->json) {
            print_json(plan_to_json(plan));
        } else {
            std::cout << desc.file << ":\n" << plan_to_text(plan);
        }
    });
}

void add_check_command(CLI::App& root) {
    auto options = std::make_shared<SceneOptions>();
    CLI::App* cmd =
        root.add_subcommand("check", "validate a scene and resolve its files; render nothing");
    options->add_to(*cmd);
    cmd->callback([options] {
        // Frame 0, then every key frame, or `sequence` would fail midway; files are read once.
        const SceneSource source = options->source();
        const SceneDesc desc = source.scene(0);
        SequenceCache cache;
        for (const int64_t frame : source.key_frames()) {
            if (frame != 0)
                (void)source.scene(frame, &cache);
        }
        if (!options->quiet) {
            std::cout << desc.file << ": ok (" << desc.shapes.size() << " shapes, "
                      << desc.lights.size() << " lights, " << desc.media.size() << " media, "
                      << desc.materials.size() << " materials)\n";
        }
    });
}

void add_probe_command(CLI::App& root) {
    CLI::App* probe = root.add_subcommand("probe", "measure one quantity; JSON on stdout");
    probe->require_subcommand(1);
    add_illuminance_command(*probe);

    struct RadianceOptions {
        SceneOptions scene;
        std::string origin, direction;
        int spp = 0;
    };
    auto options = std::make_shared<RadianceOptions>();
    CLI::App* cmd = probe->add_subcommand("radiance", "radiance seen along one camera ray");
    options->scene.add_to(*cmd);
    cmd->add_option("--origin", options->origin, "ray origin X,Y,Z (metres)")->required();
    cmd->add_option("--direction", options->direction, "ray direction X,Y,Z")->required();
    cmd->add_option("--spp", options->spp, "samples (default: film.spp)")
        ->check(CLI::Range(1, 1 << 24));
    cmd->callback([options] {
        const Vec3 origin = parse_vec3_arg(options->origin, "--origin");
        const Vec3 direction = parse_vec3_arg(options->direction, "--direction");
        if (!(glm::length(direction) > 0.0f)) {
            throw Error(ErrorKind::Usage, "--direction must be a non-zero vector");
        }
        const SceneRuntime runtime(options->scene.load(), make_gi_method);
        const int spp = options->spp > 0 ? options->spp : runtime.desc().film.spp;
        const RadianceProbe p = probe_radiance(runtime, origin, direction, spp);
        print_json(probe_json(p));
    });

    struct TransmittanceOptions {
        SceneOptions scene;
        std::string from, to, estimator;
        int samples = 1000;
    };
    auto t_options = std::make_shared<TransmittanceOptions>();
    CLI::App* t_cmd = probe->add_subcommand(
        "transmittance", "transmittance of all media between two points (surfaces ignored)");
    t_options->scene.add_to(*t_cmd);
    t_cmd->add_option("--from", t_options->from, "segment start X,Y,Z (metres)")->required();
    t_cmd->add_option("--to", t_options->to, "segment end X,Y,Z (metres)")->required();
    t_cmd->add_option(
        "--estimator", t_options->estimator,
        "march | delta | ratio | residual-ratio | unbiased-march | debiased-march (the last is "
        "unbiased-march for a transmittance; default: the scene's)");
    t_cmd->add_option("--samples", t_options->samples, "estimates averaged (default 1000)")
        ->check(CLI::Range(1, 1 << 24));
    t_cmd->callback([t_options] {
        const Vec3 from = parse_vec3_arg(t_options->from, "--from");
        const Vec3 to = parse_vec3_arg(t_options->to, "--to");
        std::optional<Estimator> estimator;
        if (!t_options->estimator.empty()) {
            estimator = estimator_from_name(t_options->estimator);
            if (!estimator) {
                throw Error(ErrorKind::Usage,
                            "--estimator expects march, delta, ratio, residual-ratio, "
                            "unbiased-march or debiased-march, got \"" +
                                t_options->estimator + "\"");
            }
        }
        const SceneRuntime runtime(t_options->scene.load(), make_gi_method);
        const Estimator chosen = estimator ? *estimator : runtime.desc().render.volume.estimator;
        const TransmittanceProbe p =
            probe_transmittance(runtime, from, to, chosen, t_options->samples);
        print_json(probe_json(p, chosen));
    });
}

}  // namespace kasumi
