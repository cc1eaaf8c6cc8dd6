#!/usr/bin/python3
"""Draw curve.png of a tessera run: P(delta) with the peak, the stiffness fit and the loading
energy marked (like Fig. 1d of Feldfogel et al.).

Usage: /usr/bin/python3 tools/plot/plot_curve.py RUNDIR      (reads curve.csv and summary.json)
Needs Debian's python3-matplotlib.
"""
import csv
import json
import sys

try:
    import matplotlib
except ImportError:
    raise SystemExit("needs Debian's python3-matplotlib (scripts/setup.sh installs it)")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from figure_file import save_figure  # noqa: E402


def main():
    run = sys.argv[1]
    with open(f"{run}/curve.csv") as f:
        rows = list(csv.DictReader(f))
    delta = [float(r["delta_mm"]) for r in rows]
    load = [float(r["load_N"]) for r in rows]
    with open(f"{run}/summary.json") as f:
        summary = json.load(f)
    r = summary["response"]
    ultimate = r["ultimate_deflection_mm"]

    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    inside = [(d, p) for d, p in zip(delta, load) if d <= ultimate]
    if inside:
        ax.fill_between([d for d, _ in inside], [p for _, p in inside], color="tab:orange", alpha=0.25,
                        label=f"W = {r['loading_energy_mJ']:.4g} mJ")
    ax.plot(delta, load, color="black", lw=1.2, label="P(δ)")
    ax.plot([r["delta_at_peak_mm"]], [r["peak_load_N"]], "o", color="tab:red",
            label=f"P_max = {r['peak_load_N']:.4g} N at δ = {r['delta_at_peak_mm']:.3g} mm")
    lo, hi = r["stiffness_fit_window_mm"]
    k = r["stiffness_N_per_mm"]
    fit_to = min(max(delta) if delta else hi, 2.5 * hi if hi > 0 else 0)
    if k > 0:
        ax.plot([0, fit_to], [0, k * fit_to], "--", color="tab:blue", label=f"K = {k:.4g} N/mm (fit {lo:.2g}–{hi:.2g} mm)")
    ax.set_xlabel("δ [mm]")
    ax.set_ylabel("P [N]")
    m = summary["material"]
    ax.set_title(f"E = {m['youngs_modulus_GPa']:.3g} GPa, μ = {m['friction']:.3g}: {r['failure_mode']}")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=min(0, min(load) if load else 0))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    save_figure(fig, f"{run}/curve.png")


if __name__ == "__main__":
    main()
