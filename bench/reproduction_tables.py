#!/usr/bin/env python3
"""Markdown tables of bench/reproduction.sh's sweeps, for docs/reproduction.md.

Usage: reproduction_tables.py [OUTDIR]   (default out/reproduction). Standard library only.
Per case: P_max, delta at the peak, K, W to failure and to the end, the failure deflection and the
loaded block's displacement there (in h), the main drop (the largest fall) with delta_b / h where it
starts, the drops after it, the failure mode and who is out, and the quasi-static ratio.
"""
import csv
import json
import os
import sys


def curve(run):
    with open(os.path.join(run, "curve.csv")) as f:
        return [(float(r["delta_mm"]), float(r["load_N"]), float(r["block_displacement_mm"])) for r in csv.DictReader(f)]


def row(run):
    s = json.load(open(os.path.join(run, "summary.json")))
    r = s["response"]
    h = r["thickness_mm"]
    drops = r["load_drops"]
    main, after, main_b = None, 0, None
    if drops:
        k = max(range(len(drops)), key=lambda i: drops[i]["load_before_N"] - drops[i]["load_after_N"])
        main, after = drops[k], len(drops) - k - 1
        c = curve(run)
        main_b = min(c, key=lambda p: abs(p[0] - main["delta_mm"]))[2] / h
    fallen = r["fallen"]
    out = ", ".join(f["name"] + ("*" if f["touching"] else "") for f in fallen) if len(fallen) <= 4 else "%d blocks" % len(fallen)
    fd = r["failure_deflection_mm"]
    return {
        "P": r["peak_load_N"], "dP": r["delta_at_peak_mm"], "K": r["stiffness_N_per_mm"],
        "W": r["loading_energy_mJ"], "Wend": r["loading_energy_to_end_mJ"],
        "fd": "–" if fd is None else "%.2f" % fd,
        "fb": "–" if fd is None else "%.2f" % (r["block_displacement_at_failure_mm"] / h),
        "main": "–" if main is None else "%.2f (%.2f h): %.0f→%.0f N" % (main["delta_mm"], main_b, main["load_before_N"], main["load_after_N"]),
        "after": after, "mode": r["failure_mode"], "out": out or "–", "qs": r["quasi_static_ratio"],
        "end": r["end"]["delta_mm"], "residual": 100 * abs(r["energy"]["energy_residual_mJ"]) / max(r["energy"]["external_work_mJ"], 1e-30),
    }


def table(sweep, label, scale=1.0, unit=""):
    d = json.load(open(os.path.join(sweep, "sweep.json")))
    keys = d["keys"]
    print("\n### %s (%s)\n" % (os.path.basename(sweep), ", ".join(keys)))
    print("| %s | P_max (N) | δ(P_max) (mm) | K (N/mm) | W to failure / end (mJ) | failure δ (mm) | δ_b there (h) | main drop: δ (δ_b/h), load | drops after | mode (out; * still touching) | KE/W | residual (%% of W) |" % label)
    print("|" + "---|" * 12)
    for c in d["cases"]:
        run = os.path.join(sweep, c["directory"], "run")
        if not os.path.exists(os.path.join(run, "summary.json")):
            print("| %g | (missing) |" % (c["values"][0] * scale))
            continue
        x = row(run)
        print("| %s | %.1f | %.2f | %.1f | %.0f / %.0f | %s | %s | %s | %d | %s (%s) | %.1e | %.2f |" % (
            " ".join("%g" % (v * scale) for v in c["values"]), x["P"], x["dP"], x["K"], x["W"], x["Wend"], x["fd"], x["fb"],
            x["main"], x["after"], x["mode"], x["out"], x["qs"], x["residual"]))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "out", "reproduction")
    for name, label, scale in [("E", "E (GPa)", 1e-9), ("mu", "μ", 1), ("mu_kt1", "μ", 1), ("mu_kt0.3", "μ", 1),
                               ("mu_kt0.1", "μ", 1), ("E_kt_ratio", "E (GPa)", 1e-9), ("E_kt_absolute", "E (GPa)", 1e-9),
                               ("post_failure", "E (GPa), μ", 1)]:
        sweep = os.path.join(out, name)
        if os.path.exists(os.path.join(sweep, "sweep.json")):
            table(sweep, label, scale)


if __name__ == "__main__":
    main()
