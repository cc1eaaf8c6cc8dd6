"""The accuracy chart of bench/convergence.sh: error of P_max, K and W against the reference,
against wall time, with the Pareto front and the cheapest settings within 1, 2 and 5 %.

Usage: /usr/bin/python3 bench/plot_convergence.py OUT_DIR PNG
Reads OUT_DIR/*/sweep.csv; writes PNG and OUT_DIR/convergence.csv, prints a markdown table.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from sweep_csv import sweep_rows

# The base scene's settings (assets/scenes/default.toml + the bundle's resolution).
BASE = {"resolution.node_spacing": 0.6e-3, "resolution.edge_spacing_fraction": 0.25, "resolution.voxel": 0.25e-3,
        "indenter.speed": 0.03, "solver.time_step_factor": 0.5, "level_set": "exact"}
METRICS = [("peak_load_N", "P_max"), ("stiffness_N_per_mm", "K"), ("loading_energy_mJ", "W")]


def label(s):
    fraction = s["resolution.edge_spacing_fraction"]
    nodes = "uniform" if fraction >= 1 else "graded to %.2g mm" % (fraction * s["resolution.node_spacing"] * 1e3)
    text = "%.2g mm nodes %s, %g mm/s, f %g" % (s["resolution.node_spacing"] * 1e3, nodes, s["indenter.speed"] * 1e3,
                                                 s["solver.time_step_factor"])
    if s["level_set"] == "grid":
        text += ", grid %.3g mm" % (s["resolution.voxel"] * 1e3)
    return text


def contact_formulation(out):
    """The [solver] contact_evaluation and contact_area of the chart's base scene (two-way and
    nearest unless it sets them)."""
    found = {"contact_evaluation": "two-way", "contact_area": "nearest"}
    with open(os.path.join(out, "base.toml")) as f:
        for line in f:
            key = line.split("=", 1)[0].strip()
            if key in found:
                found[key] = line.split("=", 1)[1].strip().strip('"')
    return "%s, %s area" % (found["contact_evaluation"], found["contact_area"])


def read_cases(out):
    cases = []
    for group, s, row in sweep_rows(out, BASE):
        if group == "voxel":
            s["level_set"] = "grid"
        cases.append({"group": group, "settings": s, "label": label(s), "wall": float(row["wall_seconds"]),
                      **{m: float(row[m]) for m, _ in METRICS}})
    return cases


def main():
    out, png = sys.argv[1], sys.argv[2]
    cases = read_cases(out)
    # The reference: the finest node spacing run (the "fine" group, 0.15 mm, two threads) at the
    # base scene's speed and step and exact level sets.
    base = [c for c in cases if c["settings"]["level_set"] == "exact" and c["settings"]["indenter.speed"] == 0.03
            and c["settings"]["solver.time_step_factor"] == 0.5]
    reference = min(base, key=lambda c: c["settings"]["resolution.node_spacing"])
    reference["group"] = "reference"
    for c in cases:
        for m, name in METRICS:
            c["err_" + name] = 100 * (c[m] / reference[m] - 1)
        c["error"] = max(abs(c["err_" + name]) for _, name in METRICS)
    others = [c for c in cases if c is not reference]
    # Pareto front: no other case both cheaper and more accurate.
    front = sorted((c for c in cases if not any(o["wall"] <= c["wall"] and o["error"] < c["error"] or
                                                o["wall"] < c["wall"] and o["error"] <= c["error"] for o in cases)),
                   key=lambda c: c["wall"])
    floor = 0.5  # %: where the reference (0 by definition) is drawn
    shown = lambda c: max(c["error"], floor)
    fig, ax = plt.subplots(figsize=(8.5, 5.5))
    markers = {"spacing": "o", "graded": "v", "speed": "s", "factor": "^", "voxel": "D", "combined": "P", "coarse": "X",
               "reference": "*"}
    for group, marker in markers.items():
        pts = [c for c in cases if c["group"] == group]
        if pts:
            ax.scatter([c["wall"] for c in pts], [shown(c) for c in pts], marker=marker,
                       s=60 if group != "reference" else 180, label=group, zorder=3)
    ax.step([c["wall"] for c in front], [shown(c) for c in front], "k--", lw=1, where="post", label="Pareto front")
    for level in (1, 2, 5):
        ax.axhline(level, color="grey", lw=0.6, ls=":")
    for c in front:
        ax.annotate(c["label"] + (" (reference)" if c is reference else ""), (c["wall"], shown(c)), fontsize=7,
                    xytext=(5, 4), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(floor * 0.8, 100)
    ax.set_xlabel("wall time of the run, s (1 thread; the reference: 2 threads; 2-core machine)")
    ax.set_ylabel("largest error of P_max, K, W vs the reference, %")
    ax.set_title("Default indentation test (%s): error against cost (reference %s, drawn at %.1f %%)" %
                 (contact_formulation(out), reference["label"], floor), fontsize=9)
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(png, dpi=130)

    with open(os.path.join(out, "convergence.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["group", "settings", "wall_s", "P_max_N", "K_N_per_mm", "W_mJ", "err_P_%", "err_K_%", "err_W_%",
                    "pareto"])
        for c in sorted(cases, key=lambda c: c["wall"]):
            w.writerow([c["group"], c["label"], "%.1f" % c["wall"], "%.4g" % c["peak_load_N"],
                        "%.4g" % c["stiffness_N_per_mm"], "%.4g" % c["loading_energy_mJ"], "%.2f" % c["err_P_max"],
                        "%.2f" % c["err_K"], "%.2f" % c["err_W"], int(c in front)])
    print("| settings | wall s | P_max N | K N/mm | W mJ | err P | err K | err W | Pareto |")
    print("|---|---|---|---|---|---|---|---|---|")
    for c in sorted(cases, key=lambda c: c["wall"]):
        print("| %s | %.0f | %.4g | %.4g | %.4g | %+.2f %% | %+.2f %% | %+.2f %% | %s |" % (
            c["label"] + (" (reference)" if c is reference else ""), c["wall"], c["peak_load_N"],
            c["stiffness_N_per_mm"], c["loading_energy_mJ"], c["err_P_max"], c["err_K"], c["err_W"],
            "yes" if c in front else ""))
    for level in (1, 2, 5, 10):
        within = [c for c in others if c["error"] <= level]
        best = min(within, key=lambda c: c["wall"]) if within else None
        print("cheapest within %d %%: %s" % (level, "%s (%.0f s, %.2f %%)" % (best["label"], best["wall"], best["error"])
                                             if best else "none but the reference"))
    for level in (1, 3):
        within = [c for c in others if abs(c["err_P_max"]) <= level]
        best = min(within, key=lambda c: c["wall"]) if within else None
        print("cheapest with P_max within %d %%: %s" % (level, "%s (%.0f s, %+.2f %%)" % (
            best["label"], best["wall"], best["err_P_max"]) if best else "none but the reference"))


if __name__ == "__main__":
    main()
