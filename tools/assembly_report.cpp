#include "tools/assembly_report.h"

#include "geometry/length_unit.h"
#include "levelset/assembly.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

namespace tessera::tools {

void printAssemblySummary(const Bundle& bundle, const AssemblySummary& summary, const std::string& command) {
  for (const std::string& w : summary.warnings) std::cerr << command << ": warning: " << w << "\n";
  for (const std::string& n : summary.notes) std::cerr << command << ": note: " << n << "\n";
  int fixedCount = 0;
  for (const Body& b : bundle.bodies) fixedCount += b.fixed;
  std::printf("slab: %zu bodies (%d fixed, %zu free), %zu distinct shape(s)\n", bundle.bodies.size(), fixedCount,
              bundle.bodies.size() - fixedCount, bundle.shapes.size());
  double deepest = 0.0;
  for (const BodyPair& c : summary.check.contacts) deepest = std::max(deepest, -c.separation);
  std::printf("  contacts      %zu touching pairs, deepest initial overlap %s\n", summary.check.contacts.size(),
              formatMillimetres(deepest).c_str());
  std::printf("  interlocking  %d of %zu free bodies held both up and down by their neighbours\n", summary.locked,
              summary.free);
  if (bundle.spanInterfaces > 0)
    std::printf("  span          L = %s free span, M = %d interfaces across it (k_n = E M / L)\n",
                formatMillimetres(bundle.spanLength).c_str(), bundle.spanInterfaces);
}

namespace {
std::string format3(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", value);
  return text;
}
}  // namespace

void printAssemblyStatics(const Bundle& bundle, const AssemblyStatics& s) {
  std::printf("  faces         %zu pairs with a free body touch face to face, over %zu polygons (%zu corners)\n", s.pairs, s.polygons, s.corners);
  const auto printMotion = [&](const std::vector<BodyMotion>& motion) {
    for (std::size_t i = 0; i < motion.size() && i < 5; ++i)
      std::printf("                %s: translation (%.2f, %.2f, %.2f), rotation (%.2f, %.2f, %.2f)\n", bundle.bodies[motion[i].body].name.c_str(),
                  motion[i].translation.x(), motion[i].translation.y(), motion[i].translation.z(), motion[i].rotation.x(),
                  motion[i].rotation.y(), motion[i].rotation.z());
    if (motion.size() > 5) std::printf("                ... and %zu more\n", motion.size() - 5);
  };
  if (s.interlocking.interlocked) {
    std::printf("  interlocked   yes: no motion of the free bodies opens a contact without closing another (frictionless)\n");
  } else {
    std::printf("  interlocked   no: %zu free bod%s can move away, opening contacts and closing none:\n", s.interlocking.motion.size(),
                s.interlocking.motion.size() == 1 ? "y" : "ies");
    printMotion(s.interlocking.motion);
  }
  if (s.interlocking.slidingModes > 0) {
    std::printf("  sliding       %d independent motion(s) slide along every contact, opening none; friction holds them%s\n",
                s.interlocking.slidingModes, s.interlocking.sliding.empty() ? "" : ", e.g.");
    printMotion(s.interlocking.sliding);
  }
  const auto& st = s.stability;
  std::string least = "no friction up to 10 suffices";
  if (st.leastFriction && *st.leastFriction == 0) least = "it stands without friction";
  else if (st.leastFriction && *st.leastFriction <= 1e-3)
    least = st.settled ? "least friction below 0.001" : "least friction below 0.001: the blocks wedge, standing if squeezed";
  else if (st.leastFriction) least = (st.stable || st.searched ? "least friction " : "it stands from friction ") + format3(*st.leastFriction);
  else if (!st.searched && (st.stable || !st.settled)) least = "tessera check finds the least friction";
  if (!st.settled) {
    std::printf("  stable        %s at friction %.3g: %s (%s)\n", st.stable ? "yes" : "no", s.friction,
                st.stable ? "compressive forces within the friction cones carry every free body's weight"
                          : "compressive forces within the friction cones cannot carry every free body's weight",
                least.c_str());
    if (st.nodes > 0)
      std::printf("                rigid equilibrium decided: settling on the run's contact springs, no equilibrium and no fall\n"
                  "                was found at friction %.3g (the solvers stalled); confirm with a run\n",
                  std::max(10.0, s.friction));
  } else {
    std::string rigid = st.rigidLeastFriction ? "rigid-block equilibrium from " + format3(*st.rigidLeastFriction)
                        : st.searched         ? "no rigid-block equilibrium up to 10"
                                              : "";
    std::printf("  stable        %s at friction %.3g: rigid equilibrium needs friction; built unstressed, %s (%s%s%s)\n",
                st.stable ? "yes" : "no", s.friction,
                st.stable ? "it settles onto the run's contact springs under its weight" : "the run's contact springs cannot settle it under its weight",
                least.c_str(), rigid.empty() ? "" : "; ", rigid.c_str());
    if (!st.stable && !st.falling.empty()) {
      std::printf("                the way it goes:\n");
      printMotion(st.falling);
    }
  }
  std::printf("  checked in %.2f s\n", s.seconds);
}

void printAssemblyVerdict(const Bundle& bundle, const std::string& folder) {
  if (bundle.bodies.size() <= kVerdictBodyLimit) {
    printAssemblyStatics(bundle, analyseAssembly(bundle, AssemblyLevelSets(bundle), kDefaultFriction, false));
    return;
  }
  std::printf("  interlocked   not checked here for %zu bodies (over %zu; it can take minutes): tessera check %s\n",
              bundle.bodies.size(), kVerdictBodyLimit, folder.c_str());
}

}  // namespace tessera::tools
