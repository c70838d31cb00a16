#include "apps/study_command.h"

#include "apps/scene_options.h"
#include "core/error.h"
#include "study/study.h"
#include "study/study_report.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

namespace kasumi {

namespace {

struct Options {
    SceneOptions scene;
    std::vector<std::string> vary;
    std::string reference = "auto";
    std::vector<std::string> reference_sets;
    int reference_spp = 0;
    int repeats = 3;
    std::string res;
    int spp = 0;
    int threads = 0;
    std::string output;
    std::string probe, from, to, origin, direction, exact;
    std::string time = "render";
};

/// The probe the options ask for (none without --probe); usage errors name the option.
std::optional<StudyProbe> study_probe(const Options& o) {
    const bool probe_options = !o.from.empty() || !o.to.empty() || !o.origin.empty() ||
                               !o.direction.empty() || !o.exact.empty();
    if (o.probe.empty()) {
        if (probe_options)
            throw Error(ErrorKind::Usage, "--from/--to/--origin/--direction/--exact need --probe");
        return std::nullopt;
    }
    if (o.reference != "auto")
        throw Error(ErrorKind::Usage, "--probe takes --exact, not --reference");
    StudyProbe probe;
    const bool transmittance = o.probe == "transmittance";
    probe.kind = transmittance ? StudyProbe::Kind::Transmittance : StudyProbe::Kind::Radiance;
    const std::string a_name = transmittance ? "--from" : "--origin";
    const std::string b_name = transmittance ? "--to" : "--direction";
    const std::string& a = transmittance ? o.from : o.origin;
    const std::string& b = transmittance ? o.to : o.direction;
    if (a.empty() || b.empty() || !(transmittance ? o.origin : o.from).empty() ||
        !(transmittance ? o.direction : o.to).empty()) {
        throw Error(ErrorKind::Usage,
                    "--probe " + o.probe + " needs exactly " + a_name + " and " + b_name);
    }
    probe.a = parse_vec3_arg(a, a_name);
    probe.b = parse_vec3_arg(b, b_name);
    if (!transmittance && !(glm::length(probe.b) > 0.0f))
        throw Error(ErrorKind::Usage, "--direction must be a non-zero vector");
    if (o.exact == "beer-lambert") {
        if (!transmittance)
            throw Error(ErrorKind::Usage, "--exact beer-lambert is for --probe transmittance");
        probe.exact_beer_lambert = true;
    } else if (!o.exact.empty()) {
        const Vec3 v = parse_vec3_arg(o.exact, "--exact");
        probe.exact = Rgb(v.x, v.y, v.z);
    }
    return probe;
}

}  // namespace

void add_study_command(CLI::App& root) {
    auto options = std::make_shared<Options>();
    CLI::App* cmd = root.add_subcommand(
        "study",
        "render every combination of varied settings; error against time, as a table "
        "and a plot");
    options->scene.add_to(*cmd);
    cmd->add_option("--vary", options->vary,
                    "KEY=V1,V2,...: a JSON pointer (or spp) and its values (repeatable)");
    cmd->add_option("--reference", options->reference,
                    "auto (render one with the most accurate values) or an EXR file");
    cmd->add_option("--reference-spp", options->reference_spp,
                    "spp of the automatic reference (default max(256, 16 x largest spp))")
        ->check(CLI::Range(2, 1 << 24));
    cmd->add_option("--reference-set", options->reference_sets,
                    "/json/pointer=VALUE for the automatic reference only (repeatable)");
    cmd->add_option("--repeats", options->repeats, "timed renders per configuration (median)")
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--res", options->res, "resolution WxH (overrides film.width/height)");
    cmd->add_option("--spp", options->spp, "samples per pixel unless spp is varied")
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--threads", options->threads, "worker threads (0: all)")
        ->check(CLI::Range(0, 1024));
    cmd->add_option("-o,--output", options->output, "directory for study.csv, .md and .svg")
        ->required();
    cmd->add_option("--probe", options->probe,
                    "study a probe instead of images: transmittance (--from, --to) or radiance "
                    "(--origin, --direction); spp = samples")
        ->check(CLI::IsMember({"transmittance", "radiance"}));
    cmd->add_option("--from", options->from, "transmittance probe: segment start X,Y,Z");
    cmd->add_option("--to", options->to, "transmittance probe: segment end X,Y,Z");
    cmd->add_option("--origin", options->origin, "radiance probe: ray origin X,Y,Z");
    cmd->add_option("--direction", options->direction, "radiance probe: ray direction X,Y,Z");
    cmd->add_option("--exact", options->exact,
                    "probe's exact value: R,G,B, or beer-lambert (transmittance through "
                    "homogeneous media); default: an automatic reference");
    cmd->add_option("--time", options->time,
                    "what is timed: render (render_image only) or build+render (also the "
                    "scene's set-up: BVH, shadow maps, tables; rebuilt every repeat)")
        ->check(CLI::IsMember({"render", "build+render"}));
    cmd->callback([options] {
        StudySpec spec;
        spec.scene_path = options->scene.scene_path;
        spec.sets = options->scene.sets;
        for (const std::string& v : options->vary)
            spec.axes.push_back(parse_vary(v));
        for (const std::string& s : options->reference_sets)
            (void)parse_override(s);
        if (options->reference != "auto") {
            if (!std::filesystem::exists(options->reference)) {
                throw Error(ErrorKind::Usage, "--reference expects auto or an EXR file; " +
                                                  options->reference + " does not exist");
            }
            spec.reference_file = options->reference;
        }
        spec.reference_sets = options->reference_sets;
        spec.reference_spp = options->reference_spp;
        spec.repeats = options->repeats;
        spec.spp = options->spp;
        spec.threads = options->threads;
        if (!options->res.empty()) {
            const Resolution res = parse_resolution_arg(options->res);
            spec.width = res.width;
            spec.height = res.height;
        }
        spec.probe = study_probe(*options);
        spec.timing =
            options->time == "build+render" ? StudyTiming::BuildRender : StudyTiming::Render;
        const bool quiet = options->scene.quiet;
        const StudyResult result = run_study(spec, [quiet](const std::string& line) {
            if (!quiet)
                std::fprintf(stderr, "%s\n", line.c_str());
        });
        write_study(result, options->output);
        if (!quiet) {
            std::fprintf(stderr, "wrote %s/study.csv, study.md and study.svg\n",
                         options->output.c_str());
        }
        if (options->scene.verbose)
            std::fputs(study_markdown(result).c_str(), stderr);
    });
}

}  // namespace kasumi
