#!/usr/bin/env bash
# The paper's two studies and the hypothesis studies of docs/reproduction.md, with the failure
# protocol of docs/physics.md ("Protocol"): a run stops once the load is gone and every free body
# is at rest or out (protocol.stop_on_failure), else at delta_max = 2 h.
#   E and mu studies:  the default scene (0.25 mm voxels, 0.6 mm nodes graded to 0.15 mm; 30 mm/s)
#   hypotheses:        k_t/k_n in {0.3, 0.1} across mu and an absolute k_t across E (--preset fast),
#                      post-failure runs at E = 3.3 GPa, mu in {0.19, 0.2, 0.23} (default scene)
# Usage: bench/reproduction.sh [OUTDIR]   (default out/reproduction; needs out/default_slab from
# scripts/run.sh). Re-running finishes only what is missing. 6 min on 2 cores (measured 2026-11-26: runs stop when
# the loaded block falls clear); tables for docs/reproduction.md: /usr/bin/python3 bench/reproduction_tables.py.
# CONTACT_EVALUATION=one-way runs the paper's studies (E, mu, post-failure) with one-way contact
# evaluation (docs/physics.md) instead: bench/reproduction.sh out/reproduction_one_way.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-"$here/out/reproduction"}
tessera="${BUILD_DIR:-$here/build}/tools/tessera"
scene="$here/assets/scenes/default.toml"
bundle="$here/out/default_slab"
[ -f "$bundle/bundle.h5" ] || { echo "reproduction: no $bundle; run scripts/run.sh first" >&2; exit 2; }
mkdir -p "$out"
# The default scene with an absolute bundle path (sweeps copy the scene into their case folders).
sed "s|^bundle = .*|bundle = \"$bundle\"|" "$scene" > "$out/scene.toml"
evaluation=${CONTACT_EVALUATION:-two-way}
[ "$evaluation" = two-way ] || printf '\n[solver]\ncontact_evaluation = "%s"\n' "$evaluation" >> "$out/scene.toml"
E=3.3e9,4.2e9,5e9,7.5e9,10e9,20e9,30e9,50e9,75e9
MU=0.19,0.2,0.21,0.23,0.3,0.5,1,2,3,5,7,9
sweep() { "$tessera" sweep "$out/scene.toml" "$@"; }
sweep -o "$out/E" --set E=$E
sweep -o "$out/mu" --set mu=$MU
if [ "$evaluation" != two-way ]; then  # the paper's studies only
  sweep -o "$out/post_failure" --set E=3.3e9 --set mu=0.19,0.2,0.23
  for d in E mu; do "$tessera" report "$out/$d"; done
  exit 0
fi
for ratio in 1 0.3 0.1; do sweep -o "$out/mu_kt$ratio" --preset fast --set mu=$MU --set material.tangential_ratio=$ratio; done
# k_t fixed at the default k_n (E = 4.2 GPa, M/L = 6/50 mm): 5.04e11 N/m^3.
sweep -o "$out/E_kt_absolute" --preset fast --set E=$E --set material.tangential_stiffness=5.04e11
sweep -o "$out/E_kt_ratio" --preset fast --set E=$E
sweep -o "$out/post_failure" --set E=3.3e9 --set mu=0.19,0.2,0.23
for d in E mu; do "$tessera" report "$out/$d"; done
echo "reproduction: tables in $out/*/sweep.csv, figures in $out/E/report and $out/mu/report"
