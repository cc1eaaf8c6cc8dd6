// tessera export: a bundle's assembly as ParaView files (VTU + PVD) and a layout file.
#include "levelset/assembly_export.h"
#include "levelset/bundle.h"
#include "tools/commands.h"

#include <cstdio>

namespace tessera::tools {

void addExportCommand(CLI::App& app) {
  struct Arguments {
    std::string bundle, output;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* cmd = app.add_subcommand(
      "export", "Write a bundle's assembly for ParaView (assembly.pvd: blocks.vtu + nodes.vtu) and as layout.json.");
  cmd->add_option("bundle", args->bundle, "Bundle directory")->required();
  cmd->add_option("-o,--output", args->output, "Directory to write into")->required();
  cmd->callback([args] {
    const Bundle bundle = readBundle(args->bundle);
    const ExportSummary s = exportAssembly(bundle, args->bundle, args->output);
    std::printf("exported %zu bodies: %zu triangles (blocks.vtu), %zu surface nodes (nodes.vtu)\n", bundle.bodies.size(),
                s.triangles, s.nodes);
    std::printf("written to %s: open assembly.pvd in ParaView; layout.json rebuilds it with tessera tile --layout\n",
                args->output.c_str());
  });
}

}  // namespace tessera::tools
