#include "apps/cloud_command.h"

#include "volume/grid/cloud_noise.h"
#include "volume/grid/vdb_io.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

namespace kasumi {

void add_make_cloud_command(CLI::App& root) {
    struct Options {
        int res = 256;
        uint64_t seed = 7;
        int octaves = 5;
        double size_m = 1000.0;
        std::string output;
        bool quiet = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = root.add_subcommand(
        "make-cloud", "write a procedural cumulus as an OpenVDB fog volume (float grid density)");
    cmd->add_option("--res", options->res, "voxels per edge (default 256)")
        ->check(CLI::Range(8, 2048));
    cmd->add_option("--seed", options->seed, "arranges puffs and noise (default 7)");
    cmd->add_option("--octaves", options->octaves, "fBm octaves (default 5)")
        ->check(CLI::Range(1, 12));
    cmd->add_option("--size-m", options->size_m,
                    "edge of the cloud's cube in metres (default 1000); the cube spans "
                    "x, z in [-size/2, size/2] and y in [0, size]")
        ->check(CLI::Validator(
            [](std::string& text) {  // PositiveNumber lets nan and 1e39 (inf as float) through
                const double v = std::strtod(text.c_str(), nullptr);
                return v > 0.0 && v <= 1e12 ? std::string() : "must be in (0, 1e12] m";
            },
            "(0, 1e12]"));
    cmd->add_option("-o,--output", options->output, "the .vdb to write")->required();
    cmd->add_flag("-q,--quiet", options->quiet, "no summary on stderr");
    cmd->callback([options] {
        const auto start = std::chrono::steady_clock::now();
        CloudParams params;
        params.res = options->res;
        params.seed = options->seed;
        params.octaves = options->octaves;
        const DenseVoxels voxels = make_cumulus(params);
        const double voxel = options->size_m / options->res;
        const std::filesystem::path parent = std::filesystem::path(options->output).parent_path();
        if (!parent.empty()) {
            std::error_code ignored;
            std::filesystem::create_directories(parent, ignored);
        }
        write_fog_volume(options->output, "density", voxels, voxel,
                         Vec3(static_cast<float>(-0.5 * options->size_m), 0.0f,
                              static_cast<float>(-0.5 * options->size_m)));
        if (!options->quiet) {
            size_t active = 0;
            for (float v : voxels.values)
                active += v > 0.0f ? 1 : 0;
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::fprintf(stderr, "wrote %s: %d^3 voxels of %.3g m, %zu active (%.2f s)\n",
                         options->output.c_str(), options->res, voxel, active, seconds);
        }
    });
}

}  // namespace kasumi
