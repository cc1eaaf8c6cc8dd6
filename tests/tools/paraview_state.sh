#!/usr/bin/env bash
# CTest: the ParaView state a run writes (paraview/slab_state.py) opens in ParaView itself: its
# three series load with every time step, the view renders, and a screenshot is written.
# Needs ParaView's pvpython and xvfb-run (Debian: paraview, python3-paraview, xvfb); without them
# it reports itself skipped (ParaView is not part of the build's dependencies).
# Usage: paraview_state.sh TESSERA SOURCE_DIR
set -euo pipefail
tessera=$1 source=$2
if ! command -v pvpython > /dev/null || ! command -v xvfb-run > /dev/null; then
  echo "skipped: needs ParaView's pvpython and xvfb-run (Debian: paraview python3-paraview xvfb)"; exit 77
fi
. "$(dirname "$0")/small_slab.sh"
printf 'bundle = "slab"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 0.6e-3\n[damping]\nlocal = 0.3\n[output]\nsnapshot_every = 0.1e-3\n' > "$work/scene.toml"
"$tessera" run "$work/scene.toml" -o "$work/out" --no-plot > /dev/null 2>&1
cat > "$work/open.py" <<'PY'
import runpy, sys
from paraview.simple import GetActiveView, GetAnimationScene, GetSources, SaveScreenshot
runpy.run_path(sys.argv[1])
names = sorted(name for name, _ in GetSources().keys())
assert names == ["blocks", "contact forces", "forces", "indenter"], names
times = GetAnimationScene().TimeKeeper.TimestepValues
assert len(times) >= 6, times
scene = GetAnimationScene()
scene.AnimationTime = times[len(times) // 2]
SaveScreenshot(sys.argv[2], GetActiveView(), ImageResolution=[640, 480])
print(f"ok: {len(times)} time steps, sources {names}")
PY
# Under load, Mesa's GLX under Xvfb sometimes fails to create ParaView's first window (an abort in
# vtkXOpenGLRenderWindow::CreateAWindow, before the state is read): that alone is tried again.
for attempt in 1 2 3; do
  status=0
  xvfb-run -a -e "$work/xvfb.log" -s "-screen 0 1024x768x24" \
    pvpython "$work/open.py" "$work/out/paraview/slab_state.py" "$work/shot.png" > "$work/pvpython.log" 2>&1 || status=$?
  if [ $status = 0 ] || ! grep -q "CreateAWindow" "$work/pvpython.log"; then break; fi
  echo "paraview_state: attempt $attempt: ParaView could not open an X window; trying again"
done
cat "$work/pvpython.log"
if [ $status != 0 ]; then echo "paraview_state: pvpython failed (status $status); the X server's log:"; cat "$work/xvfb.log"; exit 1; fi
test -s "$work/shot.png"
