#!/usr/bin/env bash
# The slabs toward their peak on GetFEM; docs/validation.md, sections
# "Toward the peak on the 5 × 5 slabs, with GetFEM" and "Tessera's own model, solved by the FE".
# For square3, square5 and hex5, the bundle and Tessera's runs under the three stiffness rules
# (the default scene at E = 4.2 GPa, mu = 0.23; square5 and hex5 at mu = 1 too); getfem_case.py
# on the 5 x 5 slabs' quarter or half (--mirror), 0.4 h elements, linearised (getfem) and
# finite-strain elasticity (getfem_finite_strain; hex5's at 0.6 h, where 0.4 h stalls, and with
# the augmentation parameter x 0.1: _r01), square5
# at 0.5 h too (getfem_finite_strain_coarse: the mesh at the peak; _nu03 at nu = 0.3), both at mu = 1
# (getfem_finite_strain_mu1); on square5 also Tessera's runs under its numerical choices (variant_*),
# 0.3 h elements to 0.4 h (the mesh) and the neighbours 100 x stiffer to 0.6 h; on square3
# Tessera's own model in the FE (rigid blocks, E x 1000, on faces of the span rule's k_n:
# getfem_rigid_blocks), with friction and without (then against Tessera frictionless and the
# rigid wedge's closed form, rigid_wedge.py, also with faces at 10 degrees: square3_10deg); then
# the tables and the figure (getfem_peaks.py). A GetFEM run that stops (Newton not converging
# through a slip) keeps the increments it reached.
# Usage: bench/validation/getfem_peaks.sh [OUT]     (default OUT: out/validation_gf)
# Env:   TESSERA (build/tools/tessera). Hours on 2 cores (docs/validation.md lists each run's time).
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-"$here/out/validation_gf"}
tessera=${TESSERA:-"$here/build/tools/tessera"}
python=/usr/bin/python3
fe() {  # CASE NAME getfem_case.py-options...
  local case=$1 name=$2
  shift 2
  echo "== $case: GetFEM, $name" >&2
  "$python" "$here/bench/validation/getfem_case.py" "$out/$case/bundle" -o "$out/$case/$name" --mirror "$@" \
    > "$out/$case/$name.log" 2>&1 || echo "   (stopped: $out/$case/$name.log)" >&2
}
set -e
mkdir -p "$out/square3" "$out/square5" "$out/hex5"
"$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 3x3 --pitch 10 \
  -o "$out/square3/bundle" --replace > "$out/square3/tile.log" 2>&1
"$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 5x5 --pitch 10 \
  -o "$out/square5/bundle" --replace > "$out/square5/tile.log" 2>&1
"$tessera" tile --tiling hex --grid 5x5 --pitch 10 --thickness 3.18 --angle 5 --unit mm \
  -o "$out/hex5/bundle" --replace > "$out/hex5/tile.log" 2>&1
for case in square3 square5 hex5; do
  for rule in span bars sections; do
    sed -e "s/^youngs_modulus = .*/youngs_modulus = 4.2e9/" \
        -e "s/^friction = .*/friction = 0.23\nstiffness_rule = \"$rule\"/" \
      "$here/assets/scenes/default.toml" > "$out/$case/scene_$rule.toml"
    sed -e "s/^friction = .*/friction = 1.0/" "$out/$case/scene_$rule.toml" > "$out/$case/scene_${rule}_mu1.toml"
    for run in "$rule" "${rule}_mu1"; do
      [ "$case" != square3 ] || [ "$run" = "$rule" ] || continue
      rm -rf "$out/$case/tessera_$run"
      "$tessera" run "$out/$case/scene_$run.toml" --bundle "$out/$case/bundle" -o "$out/$case/tessera_$run" \
        --no-plot > "$out/$case/tessera_$run.log"
    done
  done
done
# square3 frictionless, the span rule, and the same slab of 10-degree faces (square3_10deg):
# Tessera against the rigid wedge's closed form and its contact area against the faces' overlap
mkdir -p "$out/square3_10deg"
"$tessera" tile --tiling square --grid 3x3 --pitch 10 --thickness 3.18 --angle 10 --unit mm \
  -o "$out/square3_10deg/bundle" --replace > "$out/square3_10deg/tile.log" 2>&1
sed -e "s/^friction = .*/friction = 0.0/" "$out/square3/scene_span.toml" > "$out/square3/scene_span_mu0.toml"
for case in square3 square3_10deg; do
  rm -rf "$out/$case/tessera_span_mu0"
  "$tessera" run "$out/square3/scene_span_mu0.toml" --bundle "$out/$case/bundle" -o "$out/$case/tessera_span_mu0" \
    --no-plot > "$out/$case/tessera_span_mu0.log"
  "$python" "$here/bench/validation/rigid_wedge.py" "$out/$case/bundle" --tessera "$out/$case/tessera_span_mu0" \
    > "$out/$case/rigid_wedge.txt"
done
# square5 under Tessera's numerical choices (the bars rule's scene, each with one change)
variants=('implicit|[solver]\nmethod = "implicit"'
          'blended|[solver]\ncontact_area = "blended"'
          'one_way|[solver]\ncontact_evaluation = "one-way"'
          'tangential_10|[solver]\nmethod = "implicit"|s/^tangential_ratio = .*/tangential_ratio = 10.0/'
          'nodes_half|[solver]\nmethod = "implicit"\n[resolution]\nnode_spacing_ratio = 0.0943'
          'nodes_third|[solver]\nmethod = "implicit"\n[resolution]\nnode_spacing_ratio = 0.0629'
          'no_gravity|[solver]\nmethod = "implicit"\ngravity = [0.0, 0.0, 0.0]')
for variant in "${variants[@]}"; do
  IFS='|' read -r name keys edit <<< "$variant"
  sed -e "${edit:-s/^//}" "$out/square5/scene_bars.toml" > "$out/square5/scene_$name.toml"
  printf '\n%b\n' "$keys" >> "$out/square5/scene_$name.toml"
  rm -rf "$out/square5/variant_$name"
  "$tessera" run "$out/square5/scene_$name.toml" --bundle "$out/square5/bundle" -o "$out/square5/variant_$name" \
    --no-plot > "$out/square5/variant_$name.log"
done
set +e
fe square5 getfem --element-size 0.4 --deflection 1.0 --increments 30
fe hex5 getfem --element-size 0.4 --deflection 1.0 --increments 30
fe square5 getfem_fine --element-size 0.3 --deflection 0.4 --increments 12
fe square5 getfem_rigid_neighbours --element-size 0.4 --deflection 0.6 --increments 18 --neighbour-stiffness 100
rigid=(--block-stiffness 1000 --span-contact --large-displacements)  # Tessera's model: rigid blocks, k_n faces
fe square3 getfem_rigid_blocks --element-size 0.3 --deflection 1.2 --increments 80 "${rigid[@]}"
fe square3 getfem_rigid_blocks_mu0 --element-size 0.3 --deflection 1.2 --increments 80 "${rigid[@]}" --friction 0
fe square3_10deg getfem_rigid_blocks_mu0 --element-size 0.3 --deflection 1.0 --increments 60 "${rigid[@]}" --friction 0
strain=(--large-displacements --augmentation 0.1)
fe square5 getfem_finite_strain --element-size 0.4 --deflection 1.0 --increments 30 --large-displacements
fe square5 getfem_finite_strain_coarse --element-size 0.5 --deflection 0.7 --increments 21 "${strain[@]}"
fe square5 getfem_finite_strain_nu03 --element-size 0.5 --deflection 0.7 --increments 21 "${strain[@]}" --poisson 0.3
fe hex5 getfem_finite_strain --element-size 0.6 --deflection 1.0 --increments 30 --large-displacements
fe hex5 getfem_finite_strain_r01 --element-size 0.6 --deflection 1.0 --increments 30 "${strain[@]}"
fe square5 getfem_finite_strain_mu1 --element-size 0.5 --deflection 1.0 --increments 30 "${strain[@]}" --friction 1
fe hex5 getfem_finite_strain_mu1 --element-size 0.6 --deflection 1.0 --increments 30 "${strain[@]}" --friction 1
"$python" "$here/bench/validation/getfem_peaks.py" "$out" square3 square3_10deg square5 hex5
