#!/usr/bin/env python3
"""Tessera against the FE references: a table of K, P_max and delta(P_max), and one figure of
overlaid curves per case.

Usage: compare.py OUT CASE...   (OUT/CASE/tessera_span, tessera_bars, tessera_sections: `tessera run`
                                 outputs under each stiffness rule; OUT/CASE/fe: run_case.py's)
Writes OUT/table.md and OUT/curves.png (one panel per case).

Tessera's delta is the indenter's travel, which includes the sphere's own penetration into the
block; delta_b is the loaded block's displacement. The FE model's delta is its patch's
displacement, which includes the block's local compression under the patch; its delta_b is the
mean displacement of the loaded block's nodes. The two are compared on delta_b (the slab's
response); K on delta is listed for both.
K is fitted as Tessera fits it (docs/outputs.md), the least-squares slope before the peak: on delta
over [0, w], w the end of Tessera's own fit window; on delta_b, for both models, over [0, w_b],
w_b the FE block's displacement when its patch has travelled w (one range of the slab's own
displacement for both: Tessera's delta_b at its delta = w is smaller, by the indenter's
penetration). Each fit includes the curve interpolated at its range's end (an FE run has few
increments).
"""
import json
import sys
from pathlib import Path

import numpy as np


def slope(x: np.ndarray, y: np.ndarray, to: float, with_end: bool = False) -> float:
    """Least-squares slope of y(x) over x in [0, to], before y's peak; with_end: the curve
    interpolated at `to` (between the samples on either side) is one more point."""
    before = np.arange(len(y)) <= np.argmax(y)
    xs, ys = x[before], y[before]
    m = xs <= to * (1 + 1e-9)
    px, py = list(xs[m]), list(ys[m])
    beyond = np.flatnonzero(xs > to * (1 + 1e-9))
    if with_end and beyond.size and beyond[0] > 0:
        k = beyond[0]
        px.append(to)
        py.append(ys[k - 1] + (ys[k] - ys[k - 1]) * (to - xs[k - 1]) / (xs[k] - xs[k - 1]))
    return float(np.polyfit(px, py, 1)[0]) if len(px) >= 2 else float("nan")


def difference(fe: float, tessera: float) -> str:
    return f"{100 * (tessera / fe - 1):+.0f} %"


RULES = ("span", "bars", "sections")


def save(fig, rows: list[str], out: Path, figure: str) -> None:
    """The figure as OUT/figure and the table's rows as OUT/table.md, and the table printed."""
    import matplotlib.pyplot as plt
    fig.tight_layout()
    fig.savefig(out / figure, dpi=100)
    plt.close(fig)
    (out / "table.md").write_text("\n".join(rows) + "\n")
    print("\n".join(rows))


def main() -> int:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out, cases = Path(sys.argv[1]), sys.argv[2:]
    rows = ["| case | rule | K on δ_b: FE | Tessera | K on δ: FE | Tessera | P_max: FE | Tessera "
            "| δ_b(P_max): FE | Tessera | FE run |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    columns = min(2, len(cases))
    fig, axes = plt.subplots((len(cases) + columns - 1) // columns, columns, figsize=(5.2 * columns, 3.6 * ((len(cases) + 1) // columns)),
                             squeeze=False)
    for number, case in enumerate(cases):
        ax = axes.flat[number]
        f = np.genfromtxt(out / case / "fe" / "curve.csv", delimiter=",", names=True)
        fs = json.loads((out / case / "fe" / "summary.json").read_text())
        peak = int(np.argmax(f["load_N"]))
        # A peak at the FE run's last increment is a lower bound (the run stopped or ended there).
        bound = "≥ " if peak == len(f) - 1 else ""
        p_fe, d_fe = f["load_N"][peak], f["block_displacement_mm"][peak]
        part = {0: "", 1: " (a half)", 2: " (a quarter)"}[len(fs.get("mirror_planes", []))]
        run = f"{fs['nodes']} nodes{part}, {fs['total_seconds'] / 60:.1f} min" + ("" if fs["completed"] else ", stopped")
        ax.plot(f["block_displacement_mm"], f["load_N"], "k-", lw=2, label="FE (CalculiX): block's mean displacement")
        ax.plot(f["delta_mm"], f["load_N"], "k:", lw=1.5, label="FE: patch displacement")
        reach, curves = f["delta_mm"].max(), []
        for colour, rule in zip(("C0", "C1", "C2"), RULES):
            t = np.genfromtxt(out / case / f"tessera_{rule}" / "curve.csv", delimiter=",", names=True)
            ts = json.loads((out / case / f"tessera_{rule}" / "summary.json").read_text())["response"]
            window = ts["stiffness_fit_window_mm"][1]
            window_b = float(np.interp(window, f["delta_mm"], f["block_displacement_mm"]))
            k_fe = slope(f["block_displacement_mm"], f["load_N"], window_b, with_end=True)
            k_fe_patch = slope(f["delta_mm"], f["load_N"], window, with_end=True)
            k_t, k_t_travel = slope(t["block_displacement_mm"], t["load_N"], window_b, with_end=True), ts["stiffness_N_per_mm"]
            p_t, d_t = ts["peak_load_N"], ts["at_peak"]["block_displacement_mm"]
            # Against a bound (the FE run ended before its peak) a difference says nothing.
            p_diff = f" ({difference(p_fe, p_t)})" if not bound else ""
            d_diff = f" ({difference(d_fe, d_t)})" if not bound else ""
            rows.append(f"| {case} | {rule} | {k_fe:.0f} | {k_t:.0f} ({difference(k_fe, k_t)}) | {k_fe_patch:.0f} "
                        f"| {k_t_travel:.0f} ({difference(k_fe_patch, k_t_travel)}) | {bound}{p_fe:.0f} "
                        f"| {p_t:.0f}{p_diff} | {bound}{d_fe:.2f} | {d_t:.2f}{d_diff} | {run} |")
            curves += [(t["block_displacement_mm"], t["load_N"]), (t["delta_mm"], t["load_N"])]
            ax.plot(t["block_displacement_mm"], t["load_N"], f"{colour}-", lw=1, label=f"Tessera, {rule} rule: δ_b")
            ax.plot(t["delta_mm"], t["load_N"], f"{colour}:", lw=1, label=f"Tessera, {rule} rule: δ")
            reach = max(reach, d_t)
        # The FE run's range, and as much of Tessera's again (to its peak, where the FE run went that far).
        ax.set_xlim(0, 2 * f["delta_mm"].max() if bound else 1.2 * reach)
        ax.set_ylim(0, 1.1 * max(p_fe, max(np.interp(2 * f["delta_mm"].max(), *xy) for xy in curves)) if bound else None)
        ax.set_xlabel("displacement (mm)")
        ax.set_ylabel("load P (N)")
        ax.set_title(f"{case}: E {fs['youngs_modulus_MPa'] / 1000:g} GPa, ν {fs['poisson']:g}, μ {fs['friction']:g}", fontsize=9)
        ax.legend(fontsize=6)
        ax.grid(alpha=0.3)
    for ax in axes.flat[len(cases):]:
        ax.set_visible(False)
    save(fig, rows, out, "curves.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
