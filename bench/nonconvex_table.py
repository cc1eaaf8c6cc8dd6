"""The tables of bench/convergence_nonconvex.sh: for each block, every case's P_max, K and W and
their error against the block's reference, with wall time: the node reference (exact mesh, 0.3 mm
graded nodes) when it ran, else the level-set reference (exact mesh at 0.0625 mm voxels), else the
exact mesh at 0.25 mm voxels with graded 0.6 mm nodes.

Usage: /usr/bin/python3 bench/nonconvex_table.py OUT_DIR
Reads OUT_DIR/BLOCK/*/sweep.csv; writes OUT_DIR/nonconvex.csv and prints markdown tables.
"""
import csv
import glob
import os
import sys

from sweep_csv import sweep_rows

METRICS = [("peak_load_N", "P_max N"), ("stiffness_N_per_mm", "K N/mm"), ("loading_energy_to_end_mJ", "W mJ")]
BASE = {"resolution.node_spacing": 0.6e-3, "resolution.edge_spacing_fraction": 0.25, "resolution.voxel": 0.25e-3}


def label(group, s):
    fraction = s["resolution.edge_spacing_fraction"]
    nodes = "uniform" if fraction >= 1 else "graded"
    text = "%s %.2g mm nodes" % (nodes, s["resolution.node_spacing"] * 1e3)
    voxel = "%.3g mm" % (s["resolution.voxel"] * 1e3)
    level_set = "grid " + voxel if group == "grid" else "exact mesh, " + voxel
    return level_set + ", " + text


def read_block(directory):
    cases = []
    for group, s, row in sweep_rows(directory, BASE):
        cases.append({"group": group, "label": label(group, s), "wall": float(row["wall_seconds"]),
                      **{m: float(row[m]) for m, _ in METRICS}})
    return cases


def main():
    out = sys.argv[1]
    rows = []
    for directory in sorted(glob.glob(os.path.join(out, "*", ""))):
        block = os.path.basename(os.path.dirname(directory))
        cases = read_block(directory)
        reference = ([c for c in cases if c["group"] == "reference"] or [c for c in cases if c["group"] == "voxel"] or
                     [c for c in cases if c["group"] == "nodes" and "graded" in c["label"]])
        if not reference:
            continue
        ref = reference[0]
        print("\n%s (reference: %s, %s)\n" % (block, ref["label"],
                                              ", ".join("%s %.4g" % (n, ref[m]) for m, n in METRICS)))
        print("| case | wall s | " + " | ".join(n for _, n in METRICS) + " | err P | err K | err W |")
        print("|---|---|" + "---|" * (2 * len(METRICS)))
        for c in sorted(cases, key=lambda c: c["wall"]):
            errors = [100 * (c[m] / ref[m] - 1) for m, _ in METRICS]
            print("| %s | %.0f | %s | %s |" % (c["label"] + (" (reference)" if c is ref else ""), c["wall"],
                                               " | ".join("%.4g" % c[m] for m, _ in METRICS),
                                               " | ".join("%+.2f %%" % e for e in errors)))
            rows.append([block, c["label"], c["wall"]] + [c[m] for m, _ in METRICS] + errors)
    with open(os.path.join(out, "nonconvex.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["block", "case", "wall_seconds"] + [m for m, _ in METRICS] + ["err_P", "err_K", "err_W"])
        writer.writerows(rows)


if __name__ == "__main__":
    main()
