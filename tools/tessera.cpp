// tessera: the command line of the Tessera toolkit. Subcommands live in *_command.cpp.
#include "io/input_error.h"
#include "levelset/bundle.h"
#include "tools/commands.h"

#include <cstdio>
#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"Tessera: load and failure of slabs of topologically interlocked blocks (LS-DEM).\n"
               "Lengths on the command line are in the unit given by --unit; files inside Tessera are SI."};
  app.set_version_flag("--version", tessera::generatorVersion());
  app.require_subcommand(1);
  tessera::tools::addPrepCommand(app);
  tessera::tools::addInspectCommand(app);
  tessera::tools::addBlockCommand(app);
  tessera::tools::addTileCommand(app);
  tessera::tools::addAssembleCommand(app);
  tessera::tools::addCheckCommand(app);
  tessera::tools::addExportCommand(app);
  tessera::tools::addRunCommand(app);
  tessera::tools::addSweepCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {  // a command's own exit status (its message is already printed)
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every other parse error is a user mistake: one line, exit 2
    // (docs: exit codes).
    if (e.get_exit_code() == 0) return app.exit(e);
    const bool number = dynamic_cast<const CLI::ConversionError*>(&e) != nullptr;
    std::string command = "COMMAND";
    for (const CLI::App* sub : app.get_subcommands()) command = sub->get_name();
    std::cerr << "tessera: error: " << e.what() << (number ? "; give a plain number, without a unit" : "") << "; see tessera "
              << command << " --help\n";
    return 2;
  } catch (const tessera::InputError& e) {
    std::cerr << "tessera: error: " << e.what() << "\n";
    return 2;
  } catch (const tessera::WriteError& e) {
    std::cerr << "tessera: error: " << e.what() << "\n";
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {  // a path that cannot be made, listed or read
    std::cerr << "tessera: error: " << (e.path1().empty() ? std::string() : e.path1().string() + ": ") << e.code().message()
              << "; check the path, or choose another (-o)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "tessera: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
