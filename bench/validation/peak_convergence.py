#!/usr/bin/env python3
"""Tables and figure of the 3 x 3 slab's peak (peak_convergence.sh): FE P_max against the contact
penalty and the increments, in small and large displacements, and the secant stiffness
P / delta_b over its start against the overlap left, f = 1 - delta_b / h (a penalty layer's law)
and sqrt(f) (an elastic solid's, a flat punch).

Usage: peak_convergence.py OUT   (OUT/fe_cC_iN, OUT/fe_cC_iN_large: run_case.py outputs, the second
       with --large-displacements; OUT/tessera_RULE: tessera run)
Writes OUT/table.md and OUT/peak_convergence.png.
"""
import json
import re
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare import save  # noqa: E402


def secant(displacement, load, at):
    """P / delta_b at delta_b = at: the curve interpolated where delta_b first reaches `at` (delta_b
    taken as its running maximum, so that a step back does not fold the curve)."""
    return float(np.interp(at, np.maximum.accumulate(displacement), load)) / at


def main() -> int:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(sys.argv[1])
    runs = []
    folders = [(m, d) for d in out.glob("fe_c*_i*") if (m := re.fullmatch(r"fe_c(\d+)_i(\d+)(_large)?", d.name))]
    for m, d in sorted(folders, key=lambda md: (bool(md[0][3]), int(md[0][1]), int(md[0][2]))):
        c, n = int(m[1]), int(m[2])
        s = json.loads((d / "summary.json").read_text())
        name = f"FE, C = {c}, {n}" + (", large" if s.get("large_displacements") else "")
        runs.append((name, c, n, np.genfromtxt(d / "curve.csv", delimiter=",", names=True), s))
    h = runs[0][4]["thickness_mm"]
    rows = ["| penalty C | displacements | increments | FE P_max | δ_b(P_max) | K, first increment | FE run |",
            "|---|---|---|---|---|---|---|"]
    for _, c, n, f, s in runs:
        k = int(np.argmax(f["load_N"]))
        geometry = "large" if s.get("large_displacements") else "small"
        rows.append(f"| {c} | {geometry} | {n} | {f['load_N'][k]:.0f} N | {f['block_displacement_mm'][k]:.2f} mm "
                    f"| {f['load_N'][1] / f['block_displacement_mm'][1]:.0f} N/mm | {s['total_seconds'] / 60:.1f} min |")
    tessera = []
    for rule in ("span", "bars", "sections"):
        t = np.genfromtxt(out / f"tessera_{rule}" / "curve.csv", delimiter=",", names=True)
        r = json.loads((out / f"tessera_{rule}" / "summary.json").read_text())["response"]
        tessera.append((f"Tessera, {rule} rule", t))
        rows.append(f"| Tessera, {rule} | | | {r['peak_load_N']:.0f} N | {r['at_peak']['block_displacement_mm']:.2f} mm | | |")
    # The secants over their start: the FE's first increment, Tessera's first sample past 0.05 mm.
    at = (0.5, 1.0, 1.5, 1.8)
    rows += ["", "| δ_b | f | √f | " + " | ".join(name[4:] for name, _, _, _, _ in runs) + " | "
             + " | ".join(name for name, _ in tessera) + " |", "|---" * (3 + len(runs) + len(tessera)) + "|"]
    starts = [f["load_N"][1] / f["block_displacement_mm"][1] for _, _, _, f, _ in runs]
    tstarts = []
    for name, t in tessera:
        past = np.flatnonzero(t["block_displacement_mm"] > 0.05)
        if not past.size:
            raise SystemExit(f"peak_convergence: {name}: the loaded block never moved 0.05 mm")
        tstarts.append(t["load_N"][past[0]] / t["block_displacement_mm"][past[0]])
    for x in at:
        f_left = 1 - x / h
        cells = [f"{secant(f['block_displacement_mm'], f['load_N'], x) / s0:.3f}" for (_, _, _, f, _), s0 in zip(runs, starts)]
        cells += [f"{secant(t['block_displacement_mm'], t['load_N'], x) / s0:.3f}" for (_, t), s0 in zip(tessera, tstarts)]
        rows.append(f"| {x} mm | {f_left:.3f} | {np.sqrt(f_left):.3f} | " + " | ".join(cells) + " |")

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    grid = np.linspace(0.05, 0.8 * h, 60)
    for (name, _, _, f, _), s0 in zip(runs, starts):
        line, = left.plot(f["block_displacement_mm"], f["load_N"], "-", lw=1.2, label=name)
        right.plot(grid, [secant(f["block_displacement_mm"], f["load_N"], x) / s0 for x in grid], "-", lw=1.2,
                   color=line.get_color())
    for (name, t), s0 in zip(tessera, tstarts):
        line, = left.plot(t["block_displacement_mm"], t["load_N"], "--", lw=1, label=name)
        right.plot(grid, [secant(t["block_displacement_mm"], t["load_N"], x) / s0 for x in grid], "--", lw=1,
                   color=line.get_color())
    right.plot(grid, 1 - grid / h, "k:", lw=2, label="f = 1 − δ_b/h (penalty layer)")
    right.plot(grid, np.sqrt(1 - grid / h), "k-.", lw=2, label="√f (elastic solid)")
    left.set_xlim(0, 1.2 * h)
    left.set_xlabel("loaded block's displacement δ_b (mm)")
    left.set_ylabel("load P (N)")
    left.set_title("3 × 3 square slab, μ = 0.23: FE (quarter model) and Tessera", fontsize=9)
    right.set_xlabel("δ_b (mm)")
    right.set_ylabel("secant P/δ_b over its start")
    right.set_title("secant stiffness against the overlap left", fontsize=9)
    for ax in (left, right):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    save(fig, rows, out, "peak_convergence.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
