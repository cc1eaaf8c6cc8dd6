#!/usr/bin/env bash
# The defect-hunting half of the test command: the project built again with clang under
# AddressSanitizer + UndefinedBehaviorSanitizer and -Werror (in build-sanitize/), the geometry,
# level-set and command-line tests run there (all but the long runs), then each libFuzzer target of fuzz/ run over its
# committed seed corpus for a fixed number of inputs (deterministic: -seed=1).
# Usage: scripts/sanitize.sh        (run by scripts/test.sh; installs clang's runtimes if missing)
# Env:   SANITIZE_BUILD_DIR (default: build-sanitize), FUZZ_RUNS (default: 3000 inputs per target)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${SANITIZE_BUILD_DIR:-"$here/build-sanitize"}
runs=${FUZZ_RUNS:-3000}
jobs=${JOBS:-$(nproc)}

"$here/scripts/setup.sh" --with-sanitizers > /dev/null  # clang's runtimes if missing (and the main build)

cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-O2 -g" \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DTESSERA_SANITIZE=ON -DTESSERA_FUZZ=ON -DTESSERA_PORTABLE=ON \
  -DTESSERA_BUILD_BENCH=OFF > /dev/null
cmake --build "$build_dir" -j "$jobs"  # the solver's unit tests are left out of this build (tests/CMakeLists.txt)

# TBB's and OpenVDB's static objects are not ours: leaks at exit are not reported.
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The fuzzers look for leaks (libFuzzer's own check), except inside assimp (fuzz/lsan.supp).
export LSAN_OPTIONS="suppressions=$here/fuzz/lsan.supp"
# Left out as well: the long slab runs, and the tests that repeat whole runs or sweeps (each
# over 10 s here), and the Slurm test (a cluster started for it; label slurm): the main build runs them all.
slow='default run: the natural failure|a 15 x 15 slab|mu = 9 to 6 mm|scale invariance|sweep regression'
slow+='|run_resumes_after|reliability 8|block writes valid meshes'
slow+='|wave faces interlock|graded nodes on non-convex|does not stand under its own weight'  # 30-40 s each here
slow+='|osteomorphic blocks tiled unturned'  # 3 min here: exact mesh level sets of a 4 608-triangle block
slow+='|tessera check on the Voronoi slab'  # 49 blocks' level sets
slow+='|run_paraview_state_opens_in_paraview|run_paraview_series_is_readable_by_vtk'  # Python reading the files back
slow+='|getfem_|nearest_face_area'  # Python only (GetFEM's Newton; numpy): nothing of ours beyond a tile
(cd "$build_dir" && ctest --output-on-failure -j "$jobs" -E "$slow" -LE slurm)

"$build_dir/fuzz/fuzz_checkpoint" --seeds "$build_dir/fuzz-seeds" > /dev/null
for name in mesh_import scene layout bundle checkpoint; do
  corpus="$build_dir/fuzz-corpus/$name"
  mkdir -p "$corpus"
  cp "$here/fuzz/corpus/$name/"* "$corpus/" 2>/dev/null || true
  cp "$build_dir/fuzz-seeds/$name/"* "$corpus/" 2>/dev/null || true  # fresh HDF5 seeds, this build's format
  echo "sanitize: fuzzing $name ($runs inputs)"
  (cd "$build_dir" && "$build_dir/fuzz/fuzz_$name" -seed=1 -runs="$runs" -max_len=65536 -timeout=20 "$corpus" 2>&1 | tail -3)
done
echo "sanitize: no defect found"
