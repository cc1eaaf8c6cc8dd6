#!/usr/bin/env bash
# CTest (reliability 8 and 13): Ctrl-C stops a sweep: no new case starts, the running case
# checkpoints and is counted incomplete (not tabled, not plotted), the sweep exits 130; a second
# sweep on the same folder meanwhile is refused; the same sweep again resumes and finishes it.
# Usage: sweep_interrupt.sh TESSERA SOURCE_DIR
set -euo pipefail
tessera=$1 source=$2
source "$(dirname "${BASH_SOURCE[0]}")/small_slab.sh"  # $work/slab
printf 'bundle = "slab"\n[indenter]\nspeed = 0.002\n[protocol]\ndelta_max = 0.3e-3\n[output]\ncheckpoint_seconds = 0.2\n' \
  > "$work/scene.toml"
sweep=("$tessera" sweep "$work/scene.toml" -o "$work/mu" --set mu=0.2,0.3,0.4 --jobs 1 --threads 1)

"${sweep[@]}" > "$work/first.log" 2>&1 &
pid=$!
for _ in $(seq 1 600); do [ -f "$work/mu/case_000/run/checkpoint.h5" ] && break; sleep 0.05; done
[ -f "$work/mu/case_000/run/checkpoint.h5" ] || { echo "case_000 never started"; cat "$work/first.log"; exit 1; }

# A second sweep on the same folder while the first runs: refused.
status=0
"${sweep[@]}" > "$work/second.log" 2>&1 || status=$?
[ "$status" -eq 2 ] || { echo "a concurrent sweep was not refused (status $status)"; cat "$work/second.log"; exit 1; }
grep -q "another tessera process" "$work/second.log"

kill -INT "$pid"
status=0
wait "$pid" || status=$?
cat "$work/first.log"
[ "$status" -eq 130 ] || { echo "the interrupted sweep exited $status, not 130"; exit 1; }
if pgrep -f "$work/mu/case_" > /dev/null; then echo "a case still runs after the sweep stopped"; exit 1; fi
[ ! -e "$work/mu/case_001/run" ] || { echo "a case started after Ctrl-C"; exit 1; }
grep -q '"stop_reason": "interrupted"' "$work/mu/case_000/run/summary.json"
# Its printed summary gives no verdict on a loading not yet done.
grep -q "failure deflection none yet (run incomplete)" "$work/mu/case_000/log.txt" &&
  grep -q "run incomplete: no verdict" "$work/mu/case_000/log.txt" || { cat "$work/mu/case_000/log.txt"; exit 1; }
[ "$(wc -l < "$work/mu/sweep.csv")" -eq 1 ] || { echo "sweep.csv lists an incomplete case"; cat "$work/mu/sweep.csv"; exit 1; }
status=0
"$tessera" report "$work/mu" > "$work/report.log" 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "no complete case" "$work/report.log" || { echo "report drew an incomplete case"; exit 1; }

# The same sweep again resumes case_000 and finishes all three.
"${sweep[@]}" > "$work/again.log" 2>&1 || { cat "$work/again.log"; exit 1; }
grep -q "resuming case_000" "$work/again.log"
[ "$(wc -l < "$work/mu/sweep.csv")" -eq 4 ] || { cat "$work/mu/sweep.csv"; exit 1; }
echo "ok: interrupted with 130, nothing tabled; refused a concurrent sweep; resumed and finished"
