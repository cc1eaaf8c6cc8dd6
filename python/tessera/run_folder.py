"""The result files of a run folder (tessera run -o DIR, or Simulation(output=DIR)) as numpy arrays.

Reads results.h5 (docs/outputs.md) with h5py and summary.json; whatever ran the test.
"""
import json
import os

__all__ = ["RunFolder", "open_run"]


class RunFolder:
    """A finished or stopped run: `curve` (dict of arrays, SI), `summary` (dict), `snapshots`."""

    def __init__(self, folder):
        self.folder = folder
        results = os.path.join(folder, "results.h5")
        summary = os.path.join(folder, "summary.json")
        if not os.path.isfile(results) or not os.path.isfile(summary):
            raise FileNotFoundError(
                f"{folder}: not a run folder (no results.h5 and summary.json); give the -o folder of tessera run")
        with open(summary, encoding="utf-8") as f:
            self.summary = json.load(f)
        import h5py  # Debian's python3-h5py; only needed here
        with h5py.File(results, "r") as f:
            self.curve = {name: f["curve"][name][()] for name in f["curve"]} if "curve" in f else {}
            self.snapshots = {name: f["snapshots"][name][()] for name in f["snapshots"]} if "snapshots" in f else {}
            self.attributes = {k: v for k, v in f.attrs.items()}

    def __repr__(self):
        return f"RunFolder({self.folder!r}: {len(self.curve.get('delta', []))} samples)"


def open_run(folder):
    """The results of the run in `folder`."""
    return RunFolder(folder)
