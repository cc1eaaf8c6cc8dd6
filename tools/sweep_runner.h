#pragma once
#include "run/sweep.h"

#include <string>
#include <vector>

namespace tessera::tools {

/// Runs sweep cases on this machine, `jobs` at a time, each an ordinary `tessera run` of the
/// case's scene.toml into case_N/run (resumed where it has a checkpoint; skipped when complete or
/// when another process holds the case's lock), its output appended to case_N/log.txt, its start
/// and end recorded in case_N/attempt.json (with `slurmJob`, "" when not a Slurm task). SIGINT and SIGTERM stop launching
/// and are passed to the running cases, which checkpoint and stop. Returns the sweep's exit status:
/// 130 when stopped by a signal, else the first failed case's (2 input, 3 unstable), else 0.
int runSweepCases(const std::vector<SweepCase>& cases, int jobs, int threads, const std::string& slurmJob);

}  // namespace tessera::tools
