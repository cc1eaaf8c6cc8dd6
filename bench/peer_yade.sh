#!/usr/bin/env bash
# Tessera and YADE's LS-DEM side by side on the same scenes, in one invocation (docs/performance.md,
# "Peer"): time per step on the default slab (same bodies, poses, grids, node counts and fixed dt)
# with 1 and 2 threads, as a ratio; and the same two physics checks in both (a box resting on a
# box; a box on an incline at 12 and 14 degrees, mu = 0.23).
# Usage: bench/peer_yade.sh [STEPS]   (installs YADE through scripts/setup.sh --with-yade if missing;
#        needs the default slab: scripts/run.sh, or build/tools/tessera tile ... -o out/default_slab)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
steps=${1:-300}
dt=1e-6
slab="$here/out/default_slab"
command -v yade >/dev/null || "$here/scripts/setup.sh" --with-yade
[ -x "$here/build/bench/peer_tessera" ] || "$here/scripts/setup.sh"
[ -f "$slab/bundle.h5" ] || { echo "peer: no default slab at $slab: run scripts/run.sh first" >&2; exit 2; }

tessera() { "$here/build/bench/peer_tessera" "$@"; }
yade_() { local threads=$1; shift; yade -j "$threads" -n -x "$here/bench/peer_yade.py" "$@" 2>/dev/null | tail -n 1; }
field() { /usr/bin/python3 -c "import json,sys; print(json.loads(sys.argv[1])['$2'])" "$1"; }

echo "| check | Tessera | YADE 2023.02a | YADE / Tessera |"
echo "|---|---|---|---|"
for threads in 1 2; do
  t=$(tessera step "$slab" "$threads" "$dt" "$steps")
  y=$(yade_ "$threads" step "$slab" "$dt" "$steps")
  ts=$(field "$t" us_per_step); ys=$(field "$y" us_per_step)
  printf '| time per step, %d thread(s) | %.0f us | %.0f us | %.1fx |\n' "$threads" "$ts" "$ys" \
    "$(/usr/bin/python3 -c "print($ys / $ts)")"
done
t=$(tessera rest "$dt"); y=$(yade_ 1 rest "$dt")
printf '| box on box: contact force / weight | %.6f | %.6f | |\n' "$(field "$t" force_over_weight)" "$(field "$y" force_over_weight)"
printf '| box on box: step-to-step spread (std / mean) | %.2e | %.2e | |\n' "$(field "$t" spread_over_mean)" "$(field "$y" spread_over_mean)"
for degrees in 12 14; do
  t=$(tessera incline "$degrees" "$dt"); y=$(yade_ 1 incline "$degrees" "$dt")
  printf '| incline %d deg (mu 0.23 -> 12.95 deg): slip in 0.05 s | %.3g m | %.3g m | |\n' "$degrees" \
    "$(field "$t" slip_m)" "$(field "$y" slip_m)"
done
