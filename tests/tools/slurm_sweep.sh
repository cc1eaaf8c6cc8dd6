#!/usr/bin/env bash
# CTest (label slurm): tessera sweep --slurm against a real Slurm. Installs Debian's Slurm and
# munge if missing, starts munged, slurmctld and slurmd as a one-node cluster on loopback inside
# this test's own temporary folder (its own slurm.conf, key, spool, state and ports), then:
#  1. a 4-case sweep submitted with --slurm gives the same table (and final states, by digest) as
#     the same sweep run here;
#  2. in a second Slurm sweep one task is cancelled midway (scancel: SIGTERM to all its processes),
#     one is requeued midway (preemption's path: the task runs again and resumes), one gets SIGTERM
#     at its batch shell alone (a time limit's warning, --signal=B:TERM); --status calls the
#     cancelled and signalled cases interrupted, --resubmit submits those two alone and they
#     resume; the table and final states equal the local sweep's.
# Everything is shut down at the end. Skips (exit 77) only when the daemons cannot run here.
# Usage: slurm_sweep.sh TESSERA SOURCE_DIR
set -euo pipefail
tessera=$1 source=$2
skip() { echo "SKIPPED: $*"; exit 77; }

[ "$(id -u)" -eq 0 ] || skip "slurmd must run as root to start jobs (and apt-get to install Slurm)"
export PATH=$PATH:/usr/sbin:/sbin  # slurmctld, slurmd, munged
if ! command -v slurmctld > /dev/null || ! command -v slurmd > /dev/null || ! command -v sbatch > /dev/null ||
   ! command -v munged > /dev/null; then
  echo "installing Debian's Slurm and munge"
  install=(env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends slurmctld slurmd slurm-client munge)
  # The package lists setup.sh fetched usually serve; fetched again only when they do not.
  "${install[@]}" > /dev/null 2>&1 || { apt-get update -q > /dev/null && "${install[@]}" > /dev/null; } ||
    skip "apt-get could not install slurmctld slurmd slurm-client munge"
fi
python=/usr/bin/python3

source "$(dirname "${BASH_SOURCE[0]}")/small_slab.sh"  # $work/slab
cluster=$work/cluster
mkdir -p "$cluster"/{munge,spool,state,log}
chmod 700 "$cluster/munge"
daemons=()
shutdown() {  # bounded: a daemon still up 10 s after SIGTERM gets SIGKILL
  [ -z "${SLURM_CONF:-}" ] || scancel --me > /dev/null 2>&1 || true
  for pid in "${daemons[@]}"; do kill "$pid" 2> /dev/null || true; done
  for _ in $(seq 100); do
    alive=0
    for pid in "${daemons[@]}"; do kill -0 "$pid" 2> /dev/null && alive=1; done
    [ "$alive" -eq 0 ] && break
    sleep 0.1
  done
  for pid in "${daemons[@]}"; do kill -9 "$pid" 2> /dev/null || true; wait "$pid" 2> /dev/null || true; done
  rm -rf "$work"
}
trap shutdown EXIT
show_logs() { tail -n 20 "$cluster"/log/* 2> /dev/null || true; }

# munge: its own key and socket.
head -c 1024 /dev/urandom > "$cluster/munge/munge.key"
chmod 400 "$cluster/munge/munge.key"
munged -F --force --key-file="$cluster/munge/munge.key" --socket="$cluster/munge/munge.sock" \
  --pid-file="$cluster/munge/munged.pid" --seed-file="$cluster/munge/seed" --log-file="$cluster/log/munged.log" \
  > "$cluster/log/munged.out" 2>&1 &
daemons+=($!)
for _ in $(seq 50); do [ -S "$cluster/munge/munge.sock" ] && break; sleep 0.1; done
[ -S "$cluster/munge/munge.sock" ] || { show_logs; skip "munged did not start"; }

# Slurm: one node (this machine, on 127.0.0.1), two free loopback ports.
read -r ctld_port node_port < <($python -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
host=$(uname -n | cut -d. -f1)
memory=$(($(awk '/MemTotal/ {print $2}' /proc/meminfo) / 2048))
cat > "$cluster/slurm.conf" <<CONF
ClusterName=tessera-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$cluster/munge/munge.sock
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldLogFile=$cluster/log/slurmctld.log
SlurmdLogFile=$cluster/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$cluster/slurm.conf
slurmctld -D > "$cluster/log/slurmctld.out" 2>&1 &
daemons+=($!)
slurmd -D > "$cluster/log/slurmd.out" 2>&1 &
daemons+=($!)
for _ in $(seq 100); do sinfo -h -o %T 2> /dev/null | grep -q idle && break; sleep 0.2; done
sinfo -h -o %T 2> /dev/null | grep -q idle || { show_logs; skip "slurmctld and slurmd did not start a node here"; }
echo "[${SECONDS} s] cluster up: $host, slurmctld on 127.0.0.1:$ctld_port"

# A case solves for about 4 s on one core: long enough to cancel one midway. (Each faster kernel
# has shortened it: to 0.2 mm at 2 mm/s it took 1 s after the kernel of 2026-11-24, to 0.6 mm 2 s
# after its third set, to 0.9 mm 2 s after its fourth; each time a case once ended before its
# cancel under a full ctest. Now 0.9 mm at 1 mm/s.)
printf 'bundle = "%s"\n[indenter]\nspeed = 0.001\n[protocol]\ndelta_max = 0.9e-3\n[output]\ncheckpoint_seconds = 0.2\n' \
  "$work/slab" > "$work/scene.toml"
cases=(--set mu=0.3,0.5 --set E=4.2e9,20e9)

count() {  # count FOLDER STATE: cases of the sweep in that state
  "$tessera" sweep "$1" --status --json | $python -c "import json, sys; print(json.load(sys.stdin)['counts']['$2'])"
}
wait_complete() {  # wait_complete FOLDER: until every case is complete and every task has left
  # the queue (a task rewrites the sweep's tables after its case completes); fails on a failed case
  for _ in $(seq 600); do
    [ "$(count "$1" complete)" -eq 4 ] && queue=$(squeue -h) && [ -z "$queue" ] && return 0
    [ "$(count "$1" failed)" -eq 0 ] || { "$tessera" sweep "$1" --status; cat "$1"/case_*/log.txt; show_logs; exit 1; }
    sleep 0.5
  done
  echo "the Slurm sweep $1 did not finish in 300 s"; "$tessera" sweep "$1" --status; squeue || true; show_logs; exit 1
}
same_results() {  # same_results A B: equal tables (all but the wall time) and equal final states
  $python - "$1" "$2" <<'PY'
import csv, json, pathlib, sys
a, b = (pathlib.Path(p) for p in sys.argv[1:3])
rows = [[{k: v for k, v in r.items() if k != "wall_seconds"} for r in csv.DictReader(open(f / "sweep.csv"))] for f in (a, b)]
if len(rows[0]) != 4 or rows[0] != rows[1]:
    sys.exit(f"tables differ:\n{rows[0]}\n{rows[1]}")
for case in sorted(p.name for p in a.glob("case_*")):
    d = [json.load(open(f / case / "run" / "summary.json"))["state_digest"] for f in (a, b)]
    if d[0] != d[1]:
        sys.exit(f"{case}: final states differ ({d[0]} here, {d[1]} on Slurm)")
print(f"same table and final states: {a.name} and {b.name}")
PY
}

# 1. Here, then on Slurm: the same table.
"$tessera" sweep "$work/scene.toml" -o "$work/local" "${cases[@]}" --jobs 2 > "$work/local.log" 2>&1 ||
  { cat "$work/local.log"; exit 1; }
"$tessera" sweep "$work/scene.toml" -o "$work/slurm" "${cases[@]}" --slurm --max-concurrent 2 | tee "$work/submit.log"
echo "[${SECONDS} s] local sweep done"
grep -q "submitted 4 case(s)" "$work/submit.log"
grep -q -- "--array=0-3%2" "$work/slurm/slurm/sweep.sbatch"
wait_complete "$work/slurm"
echo "[${SECONDS} s] Slurm sweep done"
same_results "$work/local" "$work/slurm"
grep -q '"slurm_job": "[0-9]*_2"' "$work/slurm/case_002/attempt.json"

# 2. One task cancelled midway, then --resubmit: it resumes and ends where the local run did.
"$tessera" sweep "$work/scene.toml" -o "$work/cancel" "${cases[@]}" --slurm --max-concurrent 2 > /dev/null
job=$($python -c "import json; print(json.load(open('$work/cancel/slurm/jobs.json'))['jobs'][-1]['job_id'])")
for _ in $(seq 600); do [ -f "$work/cancel/case_001/run/checkpoint.h5" ] && break; sleep 0.05; done
[ -f "$work/cancel/case_001/run/checkpoint.h5" ] || { echo "case_001 never checkpointed"; show_logs; exit 1; }
scancel "${job}_1"
echo "[${SECONDS} s] cancelled ${job}_1"
# Preemption's path: case_002 requeued midway (SIGTERM, then the same task again; Slurm delays a
# requeued task by a few minutes, so it is released at once here). It resumes from its checkpoint.
for _ in $(seq 600); do [ -f "$work/cancel/case_002/run/checkpoint.h5" ] && break; sleep 0.05; done
[ -f "$work/cancel/case_002/run/checkpoint.h5" ] || { echo "case_002 never checkpointed"; show_logs; exit 1; }
scontrol requeue "${job}_2"
for _ in $(seq 100); do [ "$(squeue -h -j "${job}_2" -o %T)" = PENDING ] && break; sleep 0.1; done
scontrol update jobid="${job}_2" StartTime=now
echo "[${SECONDS} s] requeued ${job}_2"
# A time limit's warning: SIGTERM to the batch shell alone (--signal=B:TERM), which is the case's
# runner: it passes the signal to the run, which checkpoints.
for _ in $(seq 600); do [ -f "$work/cancel/case_003/run/checkpoint.h5" ] && break; sleep 0.05; done
[ -f "$work/cancel/case_003/run/checkpoint.h5" ] || { echo "case_003 never checkpointed"; show_logs; exit 1; }
scancel --batch --signal=TERM "${job}_3"
echo "[${SECONDS} s] signalled the batch shell of ${job}_3"
# Until the two are interrupted and the requeued one has started again (on a loaded machine Slurm
# can take a minute to start it: 40 s once was not enough under a parallel build).
for _ in $(seq 600); do [ "$(count "$work/cancel" interrupted)" -eq 2 ] && break; sleep 0.2; done
"$tessera" sweep "$work/cancel" --status | tee "$work/status.log"
for n in 1 3; do
  grep -q "case_00$n *interrupted *slurm ${job}_$n" "$work/status.log" ||
    { echo "case_00$n is not reported interrupted"; cat "$work/cancel/case_00$n/log.txt"; show_logs; exit 1; }
  grep -q '"exit_status": 130' "$work/cancel/case_00$n/attempt.json"
done
"$tessera" sweep "$work/cancel" --resubmit | tee "$work/resubmit.log"
grep -q "submitted 2 case(s) .* (array 1,3%2)" "$work/resubmit.log"
wait_complete "$work/cancel"
echo "[${SECONDS} s] resubmitted case done"
grep -q "resuming case_001" "$work/cancel/slurm/task_"*_1.out
grep -q "resuming case_003" "$work/cancel/slurm/task_"*_3.out
grep -q "resuming case_002" "$work/cancel/slurm/task_${job}_2.out" || { echo "the requeued case did not resume"; exit 1; }
same_results "$work/local" "$work/cancel"
"$tessera" sweep "$work/cancel" --resubmit | grep -q "nothing to resubmit"
echo "ok: Slurm sweep equals the local one; cancelled and signalled cases resumed by --resubmit, a requeued one by Slurm, to the same results"
