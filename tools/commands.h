#pragma once
#include <CLI/CLI.hpp>

namespace tessera::tools {

/// Each command adds its subcommand, flags and callback to the application.
/// Callbacks throw InputError for bad input; main() prints it and exits with status 2.
void addPrepCommand(CLI::App& app);
void addInspectCommand(CLI::App& app);
void addBlockCommand(CLI::App& app);
void addTileCommand(CLI::App& app);
void addAssembleCommand(CLI::App& app);
void addCheckCommand(CLI::App& app);
void addExportCommand(CLI::App& app);
void addRunCommand(CLI::App& app);
void addSweepCommand(CLI::App& app);  // also adds report

}  // namespace tessera::tools
