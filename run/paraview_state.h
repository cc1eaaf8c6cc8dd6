#pragma once
#include <string>

namespace tessera {

/// What the ParaView state of a run needs to set its view.
struct ParaViewView {
  double forceScale = 0;  ///< m per N: the largest contact force drawn as an arrow 3 h long
  double blockSize = 0;   ///< m, the loaded block's thickness h (the scale of the camera's distance)
  double largestDisplacement = 0;  ///< m, over every block and snapshot: the colour scale's top
};

/// Writes `directory`/slab_state.py: a ParaView state (Python; File > Load State, or
/// `paraview --state=slab_state.py`, or `pvpython slab_state.py`) that opens the run's series
/// blocks.pvd, forces.pvd and indenter.pvd beside it, ready to look at: blocks coloured by their
/// displacement, contact forces as arrows, the indenter translucent, the time axis set.
void writeParaViewState(const std::string& directory, const ParaViewView& view);

}  // namespace tessera
