#!/usr/bin/env python3
"""Tables of bench/geometry_studies.sh for docs/reproduction.md ("Geometry studies").

Usage: /usr/bin/python3 bench/geometry_tables.py [OUTDIR]   (default out/geometry_studies)
"""
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "out", "geometry_studies")
ANGLES = ["0", "2.5", "5", "7.5", "10", "15", "20"]


def rows(sweep):
    path = os.path.join(OUT, sweep, "sweep.csv")
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return {float(r["material.friction"]): r for r in csv.DictReader(f)}


def cells(r):
    if r is None:
        return "– | – | – | –"
    return "%.1f | %.1f | %.0f | %s" % (float(r["peak_load_N"]), float(r["stiffness_N_per_mm"]),
                                       float(r["loading_energy_mJ"]), r["failure_mode"])


print("| θ (°) | P_max (N), μ = 0.23 | K (N/mm) | W (mJ) | failure | P_max (N), μ = 7 | K (N/mm) | W (mJ) | failure |")
print("|---|---|---|---|---|---|---|---|---|")
for a in ANGLES:
    r = rows(os.path.join("angle_" + a, "mu"))
    print("| %s | %s | %s |" % (a, cells(r.get(0.23)), cells(r.get(7.0))))
print()
print("| μ | planar P_max (N) | K (N/mm) | W (mJ) | failure | wave P_max (N) | K (N/mm) | W (mJ) | failure |")
print("|---|---|---|---|---|---|---|---|---|")
planar, wave = rows(os.path.join("planar", "mu")), rows(os.path.join("wave", "mu"))
for mu in sorted(set(planar) | set(wave)):
    print("| %g | %s | %s |" % (mu, cells(planar.get(mu)), cells(wave.get(mu))))
