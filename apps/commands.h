#pragma once
/// Subcommands of the kasumi CLI. Each registers itself on the root app; its callback runs the
/// work and throws kasumi::Error on failure (main maps the kind to the exit code).
#include <CLI/CLI.hpp>

#include <string>

namespace kasumi {

void add_render_command(CLI::App& root);
void add_plan_command(CLI::App& root);
void add_check_command(CLI::App& root);
void add_probe_command(CLI::App& root);

/// The exit code a command set without throwing (e.g. 130 after an interrupted render).
int command_exit_code();
void set_command_exit_code(int code);

std::string version_string();

/// Fails with ErrorKind::Output, before any work, if `path` cannot be written: it is a
/// directory, or its directory cannot be created or take a new file. Creates the directory.
void check_output_writable(const std::string& path);

}  // namespace kasumi
