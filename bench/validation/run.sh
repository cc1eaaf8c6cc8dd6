#!/usr/bin/env bash
# The FE references of docs/validation.md, regenerated: for each case, the slab's bundle (tessera
# tile), Tessera's runs at its default preset under the span, bar and section stiffness rules, the FE
# model of the same bundle (run_case.py: gmsh + CalculiX), then the table and the overlaid curves
# (compare.py).
# Usage: bench/validation/run.sh [OUT]          (default OUT: out/validation)
# Env:   CASES (default "square3 square5 hex5 tet3"; tet5 and tall3 too), MU (0.23), NU (0.2), E (4.2e9 Pa),
#        DEFLECTION (the FE runs' last deflection, a fraction of h: 0.8; 0.15 gives K alone, in
#        a fifth of the time), INCREMENTS (20),
#        FE_OPTIONS (extra run_case.py flags, e.g. "--element-size 0.2"), TESSERA (build/tools/tessera),
#        MIRROR (1: the slabs with mirror planes through the loaded block, square3, square5 and tall3
#        (two: a quarter) and hex5 (one: a half), are modelled by that part, run_case.py --mirror; 0: whole)
# Needs calculix-ccx and python3-gmsh (scripts/setup.sh installs them). Each case's FE run takes
# minutes (docs/validation.md lists the times); the cases run one after another on 2 threads.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-"$here/out/validation"}
tessera=${TESSERA:-"$here/build/tools/tessera"}
python=/usr/bin/python3
mu=${MU:-0.23}
nu=${NU:-0.2}
young=${E:-4.2e9}
block="$here/assets/blocks/planar_a10_h3.18_5deg.obj"

bundle() {  # CASE DIR: the slab of each case, in the paper's block size (mm); sets case_options
  case_options=()
  local mirror=()
  [ "${MIRROR:-1}" = 0 ] || mirror=(--mirror)
  case "$1" in
    square3) "$tessera" tile --block "$block" --unit mm --grid 3x3 --pitch 10 -o "$2" --replace
      case_options=("${mirror[@]}") ;;
    square5) "$tessera" tile --block "$block" --unit mm --grid 5x5 --pitch 10 -o "$2" --replace
      case_options=(--element-size 0.4 "${mirror[@]}") ;;  # nine free blocks
    hex5) "$tessera" tile --tiling hex --grid 5x5 --pitch 10 --thickness 3.18 --angle 5 --unit mm -o "$2" --replace
      case_options=(--element-size 0.4 "${mirror[@]}") ;;
    tet3 | tet5)  # Dyskin's tetrahedral blocks, truncated: a 10 mm mid-section square, faces at
      # 35.26 deg (a regular tetrahedron's), 13.5 mm thick (the whole tetrahedron: 14.14), a 0.45 mm top ridge
      "$tessera" block planar --size 10 --thickness 13.5 --angle 35.26 --unit mm -o "$2.obj"
      "$tessera" tile --block "$2.obj" --unit mm --grid "${1#tet}x${1#tet}" --pitch 10 -o "$2" --replace
      case_options=(--element-size 0.1) ;;  # 1.35 mm, as 0.4 h is on the 3.18 mm blocks
    tall3)  # square3 with its loaded block twice as tall upwards: its faces keep their overlap
      "$tessera" tile --block "$block" --unit mm --grid 3x3 --pitch 10 -o "$2.base" --replace
      "$tessera" export "$2.base" -o "$2.export"
      "$python" "$here/bench/validation/tall_block.py" "$2.export/layout.json" "$2.layout.json"
      "$tessera" tile --layout "$2.layout.json" -o "$2" --replace
      case_options=(--element-size 0.15 "${mirror[@]}") ;;  # of the tall block's 2 h: 0.3 of the neighbours' h
    *) echo "run.sh: unknown case $1 (square3, square5, hex5, tet3, tet5, tall3)" >&2; exit 2 ;;
  esac
}

mkdir -p "$out"
cases=(${CASES:-square3 square5 hex5 tet3})
for c in "${cases[@]}"; do
  dir="$out/$c"
  rm -rf "$dir"/tessera_* "$dir/fe"  # regenerated whole
  mkdir -p "$dir"
  bundle "$c" "$dir/bundle" > "$dir/tile.log" 2>&1
  for rule in span bars sections; do  # the default scene at this case's material, under each stiffness rule
    sed -e "s/^youngs_modulus = .*/youngs_modulus = $young/" \
        -e "s/^friction = .*/friction = $mu\nstiffness_rule = \"$rule\"/" \
      "$here/assets/scenes/default.toml" > "$dir/scene_$rule.toml"
    echo "== $c: Tessera, $rule rule" >&2
    "$tessera" run "$dir/scene_$rule.toml" --bundle "$dir/bundle" -o "$dir/tessera_$rule" --no-plot > "$dir/tessera_$rule.log"
  done
  echo "== $c: FE" >&2
  # shellcheck disable=SC2086
  "$python" "$here/bench/validation/run_case.py" "$dir/bundle" -o "$dir/fe" --youngs-modulus "$young" \
    --poisson "$nu" --friction "$mu" --deflection "${DEFLECTION:-0.8}" --increments "${INCREMENTS:-20}" \
    "${case_options[@]}" ${FE_OPTIONS:-}
done
"$python" "$here/bench/validation/compare.py" "$out" "${cases[@]}"
