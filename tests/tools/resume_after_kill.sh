#!/usr/bin/env bash
# CTest: a run killed mid-way (SIGKILL, and SIGTERM) and resumed gives the same curve, to the last
# bit, as the run left alone. Usage: resume_after_kill.sh TESSERA SOURCE_DIR
set -euo pipefail
tessera=$1 source=$2
source "$(dirname "${BASH_SOURCE[0]}")/small_slab.sh"  # $work/slab
printf 'bundle = "slab"\n[indenter]\nspeed = 0.003\n[protocol]\ndelta_max = 1.0e-3\n[damping]\nlocal = 0.3\n[solver]\nthreads = 2\n[output]\ncheckpoint_seconds = 0.2\n' > "$work/scene.toml"

"$tessera" run "$work/scene.toml" --no-plot -o "$work/whole" > /dev/null 2>&1

for signal in KILL TERM; do
  out="$work/stopped-$signal"
  "$tessera" run "$work/scene.toml" --no-plot -o "$out" > /dev/null 2>&1 &
  pid=$!
  for _ in $(seq 1 600); do [ -f "$out/checkpoint.h5" ] && break; sleep 0.05; done
  sleep 0.5
  kill -"$signal" "$pid" 2>/dev/null || true
  status=0
  wait "$pid" || status=$?
  if [ "$status" -eq 0 ]; then echo "the run finished before SIG$signal; make it longer"; exit 1; fi
  echo "SIG$signal: stopped with status $status; curve so far: $(($(wc -l < "$out/curve.csv") - 1)) samples"
  "$tessera" run --resume "$out" --no-plot > /dev/null 2>&1
  cmp "$work/whole/curve.csv" "$out/curve.csv"
  echo "SIG$signal: resumed curve identical ($(($(wc -l < "$out/curve.csv") - 1)) samples)"
done
