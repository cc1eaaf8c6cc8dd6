#!/usr/bin/env python3
"""Table and figure of the slabs toward their peak on GetFEM (getfem_peaks.sh): for each case,
the FE curve (getfem_case.py) and Tessera's under each stiffness rule, compared on the loaded
block's displacement delta_b. Where the FE run ended before its load fell 2 % past its maximum,
that maximum is a lower bound of its P_max, and the table says so.

Usage: getfem_peaks.py OUT CASE...   (OUT/CASE/getfem*: getfem_case.py outputs; OUT/CASE/tessera_RULE
       and OUT/CASE/variant_NAME: tessera run)
Writes OUT/table.md and OUT/getfem_peaks.png.
"""
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare import save  # noqa: E402

RULES = ("span", "bars", "sections")


def friction_suffix(mu: float) -> str:
    """The suffix of Tessera's runs at friction mu: "" at the cases' 0.23, else _mu0, _mu1."""
    return "" if mu == 0.23 else f"_mu{mu:g}"


def rising(curve):
    """The curve's part up to its peak load."""
    end = int(np.argmax(curve["load_N"])) + 1
    return curve["block_displacement_mm"][:end], curve["load_N"][:end]


def main() -> int:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out, cases = Path(sys.argv[1]), sys.argv[2:]
    lines = ["| case | FE run | FE P_max (N) | at δ_b (mm) | rule | Tessera P_max (N) | at δ_b (mm) | "
             "Tessera at the FE's P_max δ_b (N) |", "|---|---|---|---|---|---|---|---|"]
    # one row of axes per friction: 0.23 (with the frictionless runs), and 1 where a case has it
    rows = 2 if any(list((out / c).glob("*_mu1/curve.csv")) for c in cases) else 1
    fig, axes = plt.subplots(rows, len(cases), figsize=(6 * len(cases), 4.5 * rows), squeeze=False)
    for column, case in enumerate(cases):
        def ax_for(suffix):  # (runs at another friction: drawn in the first row)
            return axes[1 if suffix == "_mu1" and rows == 2 else 0][column]
        # Tessera's curves under each rule, at the cases' friction 0.23 (tessera_RULE) and others
        # (tessera_RULE_muF: _mu0 frictionless, _mu1)
        tessera_runs = {suffix: {r: np.genfromtxt(out / case / f"tessera_{r}{suffix}" / "curve.csv", delimiter=",",
                                                  names=True)
                                 for r in RULES if (out / case / f"tessera_{r}{suffix}" / "curve.csv").exists()}
                        for suffix in ("", "_mu0", "_mu1")}
        for run in sorted((out / case).glob("getfem*/summary.json")):
            s = json.loads(run.read_text())
            tessera = tessera_runs.get(friction_suffix(s["friction"]), {})
            fe = np.genfromtxt(run.parent / "curve.csv", delimiter=",", names=True, ndmin=1)
            if fe.size == 0:
                continue
            peak = int(np.argmax(fe["load_N"]))
            # a peak, not a bound: the load fell 2 % past its maximum (a run that ended or stopped
            # still rising bounds the peak from below)
            reached = fe["load_N"][-1] < 0.98 * fe["load_N"][peak]
            label = (f"{run.parent.name}: {s['element_size_mm']:.2f} mm elements, "
                     f"{s['converged_increments']} of {s['increments']} increments")
            if s.get("neighbour_stiffness", 1.0) != 1.0:
                label += f", neighbours' E x {s['neighbour_stiffness']:g}"
            if s.get("block_stiffness", 1.0) != 1.0:
                label += f", blocks' E x {s['block_stiffness']:g}"
            if s.get("faces_k_n_MPa_per_mm"):
                label += f", faces k_n = {s['faces_k_n_MPa_per_mm']:.0f} MPa/mm"
            label += ", finite strain" if s.get("large_displacements") else ", linearised"
            if s["friction"] == 0:
                label += ", frictionless"
            elif s["friction"] != 0.23:
                label += f", μ = {s['friction']:g}"
            if s["poisson"] != 0.2:
                label += f", ν = {s['poisson']:g}"
            augmentations = sorted({a["augmentation"] for a in s.get("sessions", [])} | {s.get("augmentation", 1.0)})
            if augmentations != [1.0]:
                label += ", augmentation x " + ", ".join(f"{a:g}" for a in augmentations)
            ax_for(friction_suffix(s["friction"])).plot(fe["block_displacement_mm"], fe["load_N"], "o-", ms=3,
                                                         label="GetFEM, " + run.parent.name)
            last = fe["block_displacement_mm"][-1]
            for rule, t in tessera.items():
                d, p = rising(t)
                at_peak = float(np.interp(fe["block_displacement_mm"][peak],
                                          np.maximum.accumulate(t["block_displacement_mm"]), t["load_N"]))
                fe_p = f"{fe['load_N'][peak]:.0f}" if reached else f"≥ {fe['load_N'][peak]:.0f}"
                fe_d = f"{fe['block_displacement_mm'][peak]:.2f}" if reached else f"≥ {last:.2f}"
                difference = f"{p[-1] / fe['load_N'][peak] - 1:+.0%}"
                if not reached:  # against a lower bound, only a shortfall is a (least) difference
                    difference = "≤ " + difference if p[-1] < fe["load_N"][peak] else "the FE's peak not reached"
                versus = f" ({difference})"
                lines.append(f"| {case} | {label} | {fe_p} | {fe_d} | {rule} | {p[-1]:.0f}{versus} | {d[-1]:.2f} | "
                             f"{at_peak:.0f} ({at_peak / fe['load_N'][peak] - 1:+.0%}) |")
        for suffix, what in (("", ""), ("_mu0", ", frictionless"), ("_mu1", ", μ = 1")):
            for rule, t in tessera_runs[suffix].items():
                ax_for(suffix).plot(t["block_displacement_mm"], t["load_N"], lw=1, label=f"Tessera, {rule} rule{what}")
        for row, title in enumerate((case, f"{case}, μ = 1")[:rows]):
            ax = axes[row][column]
            if row and not ax.lines:  # a case without runs at mu = 1
                ax.set_visible(False)
                continue
            ax.set_title(title)
            ax.set_xlabel("loaded block's displacement δ_b (mm)")
            ax.set_ylabel("load (N)")
            ax.set_xlim(0, 3.5)
            ax.legend(fontsize=7)
    for case in cases:  # Tessera's P_max under its numerical choices (getfem_peaks.sh's variants)
        variants = sorted((out / case).glob("variant_*/summary.json"))
        if variants:
            lines += ["", f"| {case}: Tessera, bars rule, with | P_max (N) | at δ_b (mm) |", "|---|---|---|"]
        for run in variants:
            r = json.loads(run.read_text())["response"]
            lines.append(f"| {run.parent.name[len('variant_'):]} | {r['peak_load_N']:.1f} | "
                         f"{r['at_peak']['block_displacement_mm']:.2f} |")
    save(fig, lines, out, "getfem_peaks.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
