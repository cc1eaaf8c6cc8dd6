// tessera check: is an assembly interlocked, and does it stand under its own weight? Linear
// programs over its contact polygons (docs/check.md), in well under a second.
#include "io/input_error.h"
#include "levelset/assembly.h"
#include "levelset/bundle.h"
#include "levelset/rigid_block_analysis.h"
#include "tools/assembly_report.h"
#include "tools/commands.h"

#include <nlohmann/json.hpp>

#include <iostream>

namespace tessera::tools {

namespace {

struct CheckArguments {
  std::string bundle;
  double friction = kDefaultFriction;
  bool json = false;
};

nlohmann::json motionJson(const Bundle& bundle, const std::vector<BodyMotion>& motion) {
  nlohmann::json list = nlohmann::json::array();
  for (const BodyMotion& m : motion)
    list.push_back({{"body", bundle.bodies[m.body].name},
                    {"translation", {m.translation.x(), m.translation.y(), m.translation.z()}},
                    {"rotation", {m.rotation.x(), m.rotation.y(), m.rotation.z()}}});
  return list;
}

void runCheck(const CheckArguments& a) {
  const Bundle bundle = readBundle(a.bundle);
  if (!(a.friction >= 0)) throw InputError("--friction " + std::to_string(a.friction) + ": give a Coulomb coefficient >= 0");
  const AssemblyStatics statics = analyseAssembly(bundle, AssemblyLevelSets(bundle), a.friction);
  if (!a.json) {
    printAssemblyStatics(bundle, statics);
    return;
  }
  nlohmann::json out{{"bundle", a.bundle},
                     {"interlocked", statics.interlocking.interlocked},
                     {"stable", statics.stability.stable},
                     {"friction", statics.friction},
                     {"least_friction", statics.stability.leastFriction ? nlohmann::json(*statics.stability.leastFriction) : nlohmann::json(nullptr)},
                     {"free_motion", motionJson(bundle, statics.interlocking.motion)},
                     {"rigid_least_friction", statics.stability.rigidLeastFriction ? nlohmann::json(*statics.stability.rigidLeastFriction) : nlohmann::json(nullptr)},
                     {"falling_motion", motionJson(bundle, statics.stability.falling)},
                     {"sliding_modes", statics.interlocking.slidingModes},
                     {"sliding_motion", motionJson(bundle, statics.interlocking.sliding)},
                     {"contact_pairs", statics.pairs},
                     {"contact_polygons", statics.polygons},
                     {"contact_corners", statics.corners},
                     {"settled", statics.stability.settled},
                     {"contact_nodes", statics.stability.nodes},
                     {"seconds", statics.seconds}};
  std::cout << out.dump(2) << "\n";
}

}  // namespace

void addCheckCommand(CLI::App& app) {
  auto args = std::make_shared<CheckArguments>();
  CLI::App* cmd = app.add_subcommand("check", "Is the assembly interlocked, and does it stand under its own weight? (rigid blocks, linear programs)");
  cmd->add_option("bundle", args->bundle, "Bundle directory (from tile or assemble)")->required();
  cmd->add_option("--friction", args->friction, "Coulomb friction coefficient for the stability verdict")->capture_default_str();
  cmd->add_flag("--json", args->json, "Print the verdict as JSON (keys interlocked, stable, least_friction, free_motion, ...)");
  cmd->footer("Example: tessera check slab --friction 0.23");
  cmd->callback([args] { runCheck(*args); });
}

}  // namespace tessera::tools
