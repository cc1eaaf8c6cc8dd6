"""The stability map of bench/stability_map: measured critical time step against E and mu,
beside the automatic step.

Usage: /usr/bin/python3 bench/plot_stability_map.py MAP.csv PNG   (prints a markdown table)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    es = sorted({float(r["youngs_modulus_GPa"]) for r in rows})
    mus = sorted({float(r["friction"]) for r in rows})
    cell = {(float(r["youngs_modulus_GPa"]), float(r["friction"])): r for r in rows}
    margin = np.array([[float(cell[e, m]["margin"]) for e in es] for m in mus])

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.8))
    image = left.imshow(margin, origin="lower", cmap="viridis", aspect="auto")
    left.set_xticks(range(len(es)), ["%g" % e for e in es])
    left.set_yticks(range(len(mus)), ["%g" % m for m in mus])
    left.set_xlabel("Young's modulus E, GPa")
    left.set_ylabel("friction coefficient mu")
    left.set_title("margin = critical step / automatic step (factor 0.5)", fontsize=10)
    for i, m in enumerate(mus):
        for j, e in enumerate(es):
            left.text(j, i, "%.2f" % margin[i, j], ha="center", va="center", color="white", fontsize=8)
    fig.colorbar(image, ax=left)

    for m in mus:
        crit = [float(cell[e, m]["critical_dt_s"]) for e in es]
        right.loglog(es, crit, "o-", label="critical, mu = %g" % m, ms=4)
    auto = [float(cell[e, mus[0]]["automatic_dt_s"]) for e in es]
    right.loglog(es, auto, "k--", lw=2, label="automatic (factor 0.5)")
    right.set_xlabel("Young's modulus E, GPa")
    right.set_ylabel("time step, s")
    right.set_title("critical and automatic time steps (default slab, 0.6 mm nodes)", fontsize=10)
    right.legend(fontsize=7)
    right.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=130)

    print("| E GPa | mu | automatic dt s | critical factor | critical dt s | margin | first failure |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %.3g | %.3g | %.3g | %.2f | %s |" % (
            r["youngs_modulus_GPa"], r["friction"], float(r["automatic_dt_s"]), float(r["critical_factor"]),
            float(r["critical_dt_s"]), float(r["margin"]), r["failure"]))
    print("smallest margin: %.2f" % margin.min())


if __name__ == "__main__":
    main()
