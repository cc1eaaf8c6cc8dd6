#!/usr/bin/python3
"""The paper's figures from a `tessera sweep` directory (PNG and SVG, into SWEEPDIR/report/):

  curves       overlaid P-delta curves, one per case
  parameters   P_max, K and W against the swept parameter, with linear fits over the lowest five and
               the highest five points (dashed, dash-dotted: as the paper's figures); failure mode per case
  normalised   P* = P / (E L^2) against delta* = delta / h, with experimental peaks if given

Usage: /usr/bin/python3 tools/plot/report_sweep.py SWEEPDIR [--experiments points.csv]
Experiments CSV columns: label,E_Pa,L_m,h_m,P_peak_N,delta_peak_m (docs/reproduction.md).
"""
import argparse
import csv
import json
import math
import os
import sys

try:
    import matplotlib
except ImportError:
    raise SystemExit("report: error: needs Debian's python3-matplotlib (scripts/setup.sh installs it)")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from figure_file import save_figure  # noqa: E402

NAMES = {"material.youngs_modulus": ("E", "GPa", 1e-9), "material.friction": ("μ", "", 1.0),
         "indenter.speed": ("speed", "mm/s", 1e3), "indenter.radius": ("R", "mm", 1e3),
         "geometry.angle": ("θ", "°", 1.0), "geometry.thickness": ("h", "mm", 1e3), "geometry.pitch": ("pitch", "mm", 1e3),
         "geometry.radius": ("surface radius", "mm", 1e3)}


def label(key):
    name, unit, scale = NAMES.get(key, (key, "", 1.0))
    return name, unit, scale


def read_curve(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return np.array([float(r["delta_mm"]) for r in rows]), np.array([float(r["load_N"]) for r in rows])


def save(figure, directory, name):
    for extension in ("png", "svg"):
        save_figure(figure, os.path.join(directory, f"{name}.{extension}"))
    plt.close(figure)


def fit(ax, x, y, points, style, colour):
    if len(x) < 2:
        return
    order = np.argsort(x)
    chosen = order[:points] if style == "--" else order[-points:]
    if len(chosen) < 2:
        return
    slope, intercept = np.polyfit(x[chosen], y[chosen], 1)
    xs = np.linspace(min(x), max(x), 50)
    ax.plot(xs, slope * xs + intercept, style, color=colour, lw=0.9)


EXPERIMENT_COLUMNS = ["label", "E_Pa", "L_m", "h_m", "P_peak_N", "delta_peak_m"]


def read_experiments(path):
    """(label, E, L, h, P_peak, delta_peak) per row of the experiments CSV, each value a positive
    number; anything else ends the report with one line naming the file, the row and the fix."""
    def refuse(why):
        sys.stderr.write(f"report: error: {path}: {why}; give a CSV with the columns {','.join(EXPERIMENT_COLUMNS)} "
                         "(docs/reproduction.md)\n")
        sys.exit(2)
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            header = reader.fieldnames or []
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        refuse(f"cannot read it ({e})")
    missing = [c for c in EXPERIMENT_COLUMNS if c not in header]
    if missing:
        refuse(f"no column {', '.join(missing)}")
    points = []
    for line, row in enumerate(rows, start=2):
        try:
            values = [float(row[c]) for c in EXPERIMENT_COLUMNS[1:]]
        except (TypeError, ValueError):
            refuse(f"line {line}: a value missing or not a number")
        if not all(math.isfinite(v) and v > 0 for v in values):
            refuse(f"line {line}: every value must be a positive number")
        points.append((row["label"], *values))
    if not points:
        refuse("no rows")
    return points


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sweep")
    parser.add_argument("--experiments")
    args = parser.parse_args()
    try:
        with open(os.path.join(args.sweep, "sweep.json")) as f:
            manifest = json.load(f)
    except (OSError, ValueError) as e:
        raise SystemExit(f"report: error: {args.sweep}: not a readable sweep folder ({e}); give the -o folder of tessera sweep")
    experiments = read_experiments(args.experiments) if args.experiments else []  # checked before anything is drawn
    key = manifest["keys"][0]
    name, unit, scale = label(key)
    out = os.path.join(args.sweep, "report")
    os.makedirs(out, exist_ok=True)

    cases = []
    for case in manifest["cases"]:
        run = os.path.join(args.sweep, case["directory"], "run")
        try:
            with open(os.path.join(run, "summary.json")) as f:
                summary = json.load(f)
            delta, load = read_curve(os.path.join(run, "curve.csv"))
        except (OSError, ValueError):
            continue
        if summary.get("stop_reason") not in ("delta_max", "failure"):
            continue  # interrupted, unstable or still running: never drawn as a result
        cases.append((case["values"][0] * scale, summary, delta, load))
    if not cases:
        raise SystemExit(f"report: error: {args.sweep}: no complete case yet; finish the sweep by running it again")
    cases.sort(key=lambda c: c[0])
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(cases)))
    caption = f"{name} [{unit}]" if unit else name

    figure, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for (value, _, delta, load), colour in zip(cases, colours):
        ax.plot(delta, load, color=colour, lw=1.0, label=f"{name} = {value:g} {unit}".strip())
    ax.set_xlabel("δ [mm]")
    ax.set_ylabel("P [N]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    figure.tight_layout()
    save(figure, out, "curves")

    x = np.array([c[0] for c in cases])
    figure, axes = plt.subplots(1, 4, figsize=(15, 3.8), dpi=120)
    for ax, (field, title) in zip(axes[:3], [("peak_load_N", "P_max [N]"), ("stiffness_N_per_mm", "K [N/mm]"),
                                              ("loading_energy_mJ", "W [mJ]")]):
        y = np.array([c[1]["response"][field] for c in cases])
        ax.plot(x, y, "o-", color="black", lw=0.8, ms=4)
        fit(ax, x, y, 5, "--", "tab:blue")
        fit(ax, x, y, 5, "-.", "tab:red")
        ax.set_xlabel(caption)
        ax.set_ylabel(title)
        ax.grid(alpha=0.3)
    modes = [c[1]["response"]["failure_mode"] for c in cases]
    kinds = sorted(set(modes))
    axes[3].scatter(x, [kinds.index(m) for m in modes], c=[kinds.index(m) for m in modes], cmap="tab10", vmin=0, vmax=9)
    axes[3].set_yticks(range(len(kinds)))
    axes[3].set_yticklabels(kinds, fontsize=8)
    axes[3].set_xlabel(caption)
    axes[3].set_title("failure mode", fontsize=9)
    if key == "material.friction" and max(x) / max(min(x), 1e-12) > 20:
        for ax in axes:
            ax.set_xscale("log")
    figure.tight_layout()
    save(figure, out, "parameters")

    figure, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for (value, summary, delta, load), colour in zip(cases, colours):
        e = summary["material"]["youngs_modulus_GPa"] * 1e9
        span = summary["material"]["span_length_mm"] * 1e-3
        h = summary["response"].get("thickness_mm", 0) * 1e-3
        if h > 0:
            ax.plot(delta * 1e-3 / h, load / (e * span * span), color=colour, lw=1.0, label=f"{name} = {value:g} {unit}".strip())
    for label_text, e, span, h, p_peak, delta_peak in experiments:
        p_star, d_star = p_peak / (e * span ** 2), delta_peak / h
        ax.plot([d_star], [p_star], "s", color="tab:red")
        ax.annotate(label_text, (d_star, p_star), fontsize=7)
    ax.set_xlabel("δ* = δ / h")
    ax.set_ylabel("P* = P / (E L²)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    figure.tight_layout()
    save(figure, out, "normalised")
    print(f"report: {len(cases)} cases drawn into {out} (curves, parameters, normalised; PNG and SVG)")


if __name__ == "__main__":
    try:
        main()
    except OSError as e:  # a folder that cannot be made or read: one line, not a traceback
        sys.stderr.write(f"report: error: {e.filename or ''}: {e.strerror or e}\n")
        sys.exit(2)
