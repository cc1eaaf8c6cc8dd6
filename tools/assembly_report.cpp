#include "tools/assembly_report.h"

#include "geometry/length_unit.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

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

}  // namespace tessera::tools
