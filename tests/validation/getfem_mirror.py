"""The GetFEM reference run (bench/validation/getfem_case.py) by a slab's quarter against the whole.

The 3 x 3 slab of the paper's block (`tessera tile`) is its own mirror image about the vertical
planes through its centre, so the quarter model (--mirror: the blocks cut there, the cut faces held
normal to their plane, the load 4 x the quarter's) must give the whole slab's answer: after one
small increment, the stiffness on the loaded block's mean displacement, load / delta_b, within 3 %
(measured: 1.5 %; the two meshes differ, gmsh meshes the cut blocks anew, and so do the punch
patches, which moves the load at a given punch displacement by 5 %). A quarter that lost its
symmetry conditions (the block free to spread) or its factor 4 is far off. In each run the punch's
reaction equals the vertical force on the fixed blocks (equilibrium; both 122.892615 N on the
whole slab) to 1e-3.

Usage: getfem_mirror.py TESSERA_EXE WORK_DIR. Exit 77 (skipped) where GetFEM or gmsh is not installed.
"""
import csv
import json
import subprocess
import sys
from pathlib import Path

root = Path(__file__).resolve().parents[2]


def run(bundle: Path, out: Path, *extra: str) -> tuple[float, float, dict]:
    run = subprocess.run([sys.executable, str(root / "bench/validation/getfem_case.py"), str(bundle), "-o", str(out),
                          "--element-size", "0.3", "--deflection", "0.03", "--increments", "1", *extra],
                         capture_output=True, text=True)
    assert run.returncode == 0, f"getfem_case.py failed ({run.returncode}): {run.stdout[-2000:]}{run.stderr[-2000:]}"
    with open(out / "curve.csv") as f:
        row = list(csv.DictReader(f))[-1]
    load, support = float(row["load_N"]), float(row["support_N"])
    assert abs(support / load - 1) < 1e-3, f"the punch's reaction {load} N is not the supports' {support} N"
    return load, float(row["block_displacement_mm"]), json.loads((out / "summary.json").read_text())


def main() -> int:
    try:
        import getfem  # noqa: F401
        import gmsh  # noqa: F401
    except ImportError as e:
        print(f"skipped: {e} (scripts/setup.sh installs python3-getfem and python3-gmsh)")
        return 77
    tessera, work = sys.argv[1], Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    bundle = work / "slab3"
    subprocess.run([tessera, "tile", "--block", str(root / "assets/blocks/planar_a10_h3.18_5deg.obj"),
                    "--unit", "mm", "--grid", "3x3", "--pitch", "10", "-o", str(bundle), "--replace"],
                   check=True, capture_output=True)
    load, sink, whole = run(bundle, work / "whole")
    load_q, sink_q, quarter = run(bundle, work / "quarter", "--mirror")
    print(f"whole: {load:.4g} N at delta_b {sink:.4g} mm ({load / sink:.5g} N/mm); "
          f"quarter: {load_q:.4g} N at {sink_q:.4g} mm ({load_q / sink_q:.5g} N/mm)")
    assert whole["status"] == quarter["status"] == "reached the deflection", (whole["status"], quarter["status"])
    assert whole["mirror_planes"] == [] and quarter["mirror_planes"] == ["x", "y"], quarter["mirror_planes"]
    assert load > 0 and sink > 0, "the pressed slab carries no load"
    assert abs((load_q / sink_q) / (load / sink) - 1) < 0.03, "the quarter's stiffness (x 4) is not the whole slab's"
    return 0


if __name__ == "__main__":
    sys.exit(main())
