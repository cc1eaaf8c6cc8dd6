"""The finished cases of the sweeps in a folder, for the accuracy charts (plot_convergence.py,
nonconvex_table.py): OUT/GROUP/sweep.csv, one row per case."""
import csv
import glob
import os


def sweep_rows(out, base):
    """(group, settings, row) for each finished case of OUT/*/sweep.csv, in path order: settings are
    `base` with the values of its keys that the row's sweep set."""
    for path in sorted(glob.glob(os.path.join(out, "*", "sweep.csv"))):
        group = os.path.basename(os.path.dirname(path))
        with open(path) as f:
            for row in csv.DictReader(f):
                if not row.get("peak_load_N"):
                    continue  # a case that did not finish
                settings = dict(base)
                for key in base:
                    if key in row:
                        settings[key] = float(row[key])
                yield group, settings, row
