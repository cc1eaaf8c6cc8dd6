#!/usr/bin/env bash
# The cost law of the two methods (docs/performance.md, "The implicit method"): square slabs of the
# default block, N x N for each N given (perimeter fixed, the paper's resolution), indented by the
# default scene to delta_max = 2 h, with solver.method = "implicit" and "explicit", on THREADS
# threads. Prints one line per run: N, method, wall seconds (settling included), steps or
# increments, P_max, K, delta at P_max, W to the end, the failure and the energy residual; each
# run's files stay in OUT/N_method. An explicit run longer than EXPLICIT_LIMIT seconds is stopped
# there and its total extrapolated from its steps per second (marked "~").
# Usage: bench/implicit_scaling.sh [N ...]          (default: 7 15 31)
# Env:   BUILD_DIR (build), OUT (/tmp/tessera_scaling), THREADS (2), EXPLICIT_LIMIT (900 s),
#        SPEED (the scene's indenter.speed, m/s; 0: the protocol's c (h/L)^2 rule; default: 0.03 as the
#        default scene), METHODS ("implicit explicit"), TOLERANCES (solver.implicit_tolerance values,
#        one implicit run each; default: the built-in one), BLOCK (a block mesh in mm; default: the
#        default block), TILE_OPTIONS (more `tessera tile` options, e.g. --no-alternate) and OFFSET
#        (m: the indenter's plan offset along x from the loaded block's centroid, an imperfection;
#        unset: 0)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tessera="${BUILD_DIR:-$here/build}/tools/tessera"
out=${OUT:-/tmp/tessera_scaling}
threads=${THREADS:-2}
limit=${EXPLICIT_LIMIT:-900}
speed=${SPEED:-0.03}
offset=""
[ -z "${OFFSET:-}" ] || offset="\\noffset = [${OFFSET}, 0.0]"
methods=(${METHODS:-implicit explicit})
tolerances=(${TOLERANCES:-default})
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(7 15 31)
python=/usr/bin/python3
mkdir -p "$out"

summary() {  # folder, method, wall, note
  "$python" - "$1" "$2" "$3" "$4" <<'EOF'
import json, sys
folder, method, wall, note = sys.argv[1:5]
s = json.load(open(folder + "/summary.json"))
r, run = s["response"], s["run"]
e = r.get("energy", {})
work = e.get("external_work_mJ", 0) or 1
iterations = f" ({run['newton_iterations']} iterations)" if run.get('method') == 'implicit' else ""
print(f"{folder.split('/')[-1]:>14} {method:>8} {note}{float(wall):8.1f} s  steps {run['steps']:>8}{iterations}  "
      f"P_max {r['peak_load_N']:8.3f} N  K {r['stiffness_N_per_mm']:9.3f} N/mm  delta(P_max) {r['delta_at_peak_mm']:6.3f} mm  "
      f"W {r['loading_energy_to_end_mJ']:8.2f} mJ  failure {r.get('failure_deflection_mm')} ({r.get('failure_mode')})  "
      f"residual {100 * e.get('energy_residual_mJ', 0) / work:5.2f} %")
EOF
}

block=${BLOCK:-$here/assets/blocks/planar_a10_h3.18_5deg.obj}
name=$(basename "$block" .obj)
for n in "${sizes[@]}"; do
  slab="$out/slab${n}_$name"
  [ -f "$slab/bundle.h5" ] || "$tessera" tile --block "$block" --unit mm --grid "${n}x${n}" --pitch 10 --fix perimeter \
    --voxel 0.25 --spacing 0.6 ${TILE_OPTIONS:-} --replace -o "$slab" > /dev/null
  cases=()
  for method in "${methods[@]}"; do
    if [ "$method" = implicit ]; then for t in "${tolerances[@]}"; do cases+=("implicit:$t"); done
    else cases+=("$method:default"); fi
  done
  for case in "${cases[@]}"; do
    method=${case%%:*} tolerance=${case#*:}
    label=$method
    setting=""
    if [ "$tolerance" != default ]; then label="${method}_$tolerance"; setting="\nimplicit_tolerance = $tolerance"; fi
    [ -z "${OFFSET:-}" ] || label="${label}_off$OFFSET"
    scene="$out/scene_${n}_${name}_$label.toml"
    sed -e "s#^bundle = .*#bundle = \"$slab\"#" -e "s#^speed = .*#speed = $speed$offset#" \
      -e "s#^\[damping\]#[solver]\nmethod = \"$method\"$setting\n\n[damping]#" "$here/assets/scenes/default.toml" > "$scene"
    run="$out/${n}_${name}_$label"
    rm -rf "$run"
    start=$(date +%s.%N)
    if [ "$method" = explicit ]; then
      timeout --signal=INT "$limit" "$tessera" run "$scene" -o "$run" --threads "$threads" --no-plot > "$run.log" 2>&1 || true
    else
      "$tessera" run "$scene" -o "$run" --threads "$threads" --no-plot > "$run.log" 2>&1
    fi
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    if grep -q '"stop_reason": "interrupted"' "$run/summary.json" 2>/dev/null || ! [ -f "$run/summary.json" ]; then
      # Stopped at the limit: the steps it would take at the rate it ran (loading's travel left).
      "$python" - "$run" "$wall" "$n" <<'EOF'
import json, sys
run, wall, n = sys.argv[1], float(sys.argv[2]), sys.argv[3]
s = json.load(open(run + "/summary.json"))
steps, dt = s["run"]["steps"], s["run"]["time_step_s"]
speed = s["material"]["indenter_speed_mm_per_s"] * 1e-3
delta_max = s["response"]["delta_max_mm"] * 1e-3
last = s["response"]["end"]["delta_mm"] * 1e-3
left = max(delta_max - last, 0) / (speed * dt)
print(f"{'slab' + n:>14}  explicit ~{wall * (steps + left) / max(steps, 1):8.0f} s  (stopped after {wall:.0f} s at {steps} steps; "
      f"{left:.0f} more to delta_max)")
EOF
    else
      summary "$run" "$label" "$wall" " "
    fi
  done
done
