#include "run/paraview_state.h"

#include "io/safe_write.h"

#include <cstdio>
#include <filesystem>

namespace tessera {

namespace {

// The state, for ParaView 5.9 and later (paraview.simple). %s: the folder as written (for a
// ParaView that runs the state without __file__); %.17g: force scale, block size, largest displacement.
constexpr const char* kState = R"(# ParaView state of a Tessera run (written by tessera run; docs/outputs.md).
# Open it with File > Load State (Python state), `paraview --state=slab_state.py` or `pvpython slab_state.py`.
# Blocks coloured by their displacement from the bundle's pose (m), contact forces as arrows (the
# largest 3 h long, h the loaded block's thickness) coloured by their sliding fraction, the
# indenter translucent; the time axis is delta in mm (the snapshot's number if the indenter went back up).
import os
from paraview.simple import *

WRITTEN_IN = r"%s"
try:
    here = os.path.dirname(os.path.abspath(__file__))
except NameError:
    here = WRITTEN_IN
if not os.path.exists(os.path.join(here, "blocks.pvd")):
    here = WRITTEN_IN
FORCE_SCALE = %.17g  # m per N
BLOCK = %.17g        # m
LARGEST_DISPLACEMENT = %.17g  # m, over the whole run

view = GetActiveViewOrCreate("RenderView")
blocks = PVDReader(registrationName="blocks", FileName=os.path.join(here, "blocks.pvd"))
shown = Show(blocks, view)
ColorBy(shown, ("CELLS", "displacement", "Magnitude"))
GetColorTransferFunction("displacement").RescaleTransferFunction(0.0, max(LARGEST_DISPLACEMENT, 1e-12))
shown.SetScalarBarVisibility(view, True)

forces = PVDReader(registrationName="forces", FileName=os.path.join(here, "forces.pvd"))
arrows = Glyph(registrationName="contact forces", Input=forces, GlyphType="Arrow")
arrows.OrientationArray = ["POINTS", "force"]
arrows.ScaleArray = ["POINTS", "magnitude"]
arrows.ScaleFactor = FORCE_SCALE
arrows.GlyphMode = "All Points"
arrowsShown = Show(arrows, view)
ColorBy(arrowsShown, ("POINTS", "sliding_fraction"))

indenter = PVDReader(registrationName="indenter", FileName=os.path.join(here, "indenter.pvd"))
indenterShown = Show(indenter, view)
indenterShown.Opacity = 0.35

GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
view.CameraPosition = [-12 * BLOCK, -18 * BLOCK, 10 * BLOCK]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
Render()
)";

}  // namespace

void writeParaViewState(const std::string& directory, const ParaViewView& view) {
  const std::string folder = std::filesystem::absolute(directory).lexically_normal().string();
  const int size = std::snprintf(nullptr, 0, kState, folder.c_str(), view.forceScale, view.blockSize, view.largestDisplacement);
  std::string text(static_cast<std::size_t>(size) + 1, '\0');
  std::snprintf(text.data(), text.size(), kState, folder.c_str(), view.forceScale, view.blockSize, view.largestDisplacement);
  text.resize(static_cast<std::size_t>(size));
  writeTextFileSafely(std::filesystem::path(directory) / "slab_state.py", text);
}

}  // namespace tessera
