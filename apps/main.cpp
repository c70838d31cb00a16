/// kasumi: the command-line interface. Thin: parses arguments, calls the library, maps errors to
/// exit codes (0 ok, 1 runtime, 2 usage, 3 invalid input, 4 cannot write, 5 validation failed,
/// 130/143 interrupted).
#include "apps/cloud_command.h"
#include "apps/commands.h"
#include "apps/movie_command.h"
#include "apps/phase_command.h"
#include "apps/sequence_command.h"
#include "apps/study_command.h"
#include "core/error.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstring>
#include <new>

namespace {

/// Each subcommand by its name, with what declares it.
struct Subcommand {
    const char* name;
    void (*add)(CLI::App&);
};
constexpr Subcommand kSubcommands[] = {
    {"render", kasumi::add_render_command},     {"plan", kasumi::add_plan_command},
    {"check", kasumi::add_check_command},       {"probe", kasumi::add_probe_command},
    {"phase", kasumi::add_phase_command},       {"make-cloud", kasumi::add_make_cloud_command},
    {"sequence", kasumi::add_sequence_command}, {"movie", kasumi::add_movie_command},
    {"study", kasumi::add_study_command},
};

/// Declares the subcommand named by the first argument alone when there is one (declaring all
/// of them, their options and checks, was 3M instructions, 1.4% of a 1-spp 128x128 render),
/// else every subcommand (for --help, --version, a missing or an unknown name).
void add_subcommands(CLI::App& app, int argc, char** argv) {
    if (argc >= 2) {
        for (const Subcommand& sub : kSubcommands) {
            if (std::strcmp(argv[1], sub.name) == 0) {
                sub.add(app);
                return;
            }
        }
    }
    for (const Subcommand& sub : kSubcommands)
        sub.add(app);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"kasumi: a renderer of participating media"};
    app.require_subcommand(1);
    app.set_version_flag("--version", kasumi::version_string());
    add_subcommands(app, argc, argv);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : static_cast<int>(kasumi::ErrorKind::Usage);
    } catch (const kasumi::Error& e) {
        std::fprintf(stderr, "kasumi: %s\n", e.what());
        return e.exit_code();
    } catch (const std::bad_alloc&) {
        // Not a bug but a request too large for this machine (a 16384x16384 film, a huge grid).
        std::fprintf(stderr,
                     "kasumi: out of memory: the scene, its files or the film (--res) "
                     "need more memory than this machine has\n");
        return static_cast<int>(kasumi::ErrorKind::Runtime);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "kasumi: internal error: %s\n", e.what());
        return static_cast<int>(kasumi::ErrorKind::Runtime);
    }
    return kasumi::command_exit_code();
}
