#!/usr/bin/python3
"""A load-unload cycle on the default slab, driven from Python (docs/python.md).

Loads the paper's 7 x 7 slab to delta = 1 mm (about half the peak deflection), lifts the
indenter at the same speed until it no longer touches, and reloads to 1.5 mm. Writes
cycle.png and cycle.csv into OUT, and, given the command line's run of the same scene, checks
that the first loading is that run's curve.

Usage: load_unload.py BUNDLE OUT [CLI_RUN]
  e.g. load_unload.py out/default_slab out/cycle out/default_run   (after scripts/run.sh)
"""
import os
import sys

import numpy as np

import tessera

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "assets", "scenes", "default.toml")
if not os.path.isfile(SCENE):  # installed: the assets are in <prefix>/share/tessera
    SCENE = os.path.join(sys.prefix, "share", "tessera", "assets", "scenes", "default.toml")


def main(bundle, out, cli_run=None):
    sim = tessera.Simulation(SCENE, bundle=bundle)
    speed = {}      # the protocol's speed, m/s
    legs = []       # index of the first sample of each leg after the first
    targets = [("lift", 1.0e-3), ("reload", 1.5e-3)]

    def on_sample(sample, control):
        speed.setdefault("down", control.indenter_speed)
        leg = len(legs)
        if leg == 0 and sample.delta >= targets[0][1]:
            legs.append(len(sim.curve["delta"]))
            control.indenter_speed = -speed["down"]       # lift
        elif leg == 1 and sample.load <= 0:
            legs.append(len(sim.curve["delta"]))
            control.indenter_speed = speed["down"]        # reload
        elif leg == 2 and sample.delta >= targets[1][1]:
            control.stop()

    print("stopped:", sim.run(on_sample))
    curve = sim.curve
    delta, load = curve["delta"], curve["load"]
    lift, reload = legs
    print(f"loaded to {delta[lift - 1] * 1e3:.3f} mm at {load[lift - 1]:.2f} N; "
          f"unloaded to zero load at {delta[reload - 1] * 1e3:.3f} mm (permanent set); "
          f"reloaded to {delta[-1] * 1e3:.3f} mm at {load[-1]:.2f} N")
    work = curve["external_work"]
    print(f"work: {work[lift - 1] * 1e3:.3f} mJ in, {(work[lift - 1] - work[reload - 1]) * 1e3:.3f} mJ given back "
          f"on lifting; energy residual {sim.energy['energy_residual'] / work.max():.2e} of the work")

    os.makedirs(out, exist_ok=True)
    np.savetxt(os.path.join(out, "cycle.csv"), np.column_stack([delta * 1e3, load]), delimiter=",",
               header="delta_mm,load_N", comments="")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 3.6))
    for label, part in (("load", slice(0, lift)), ("lift", slice(lift - 1, reload)), ("reload", slice(reload - 1, None))):
        ax.plot(delta[part] * 1e3, load[part], label=label)
    ax.set_xlabel("indenter displacement delta (mm)")
    ax.set_ylabel("load P (N)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "cycle.png"), dpi=150)

    if cli_run:
        cli = tessera.open_run(cli_run).curve
        n = lift
        worst = max(np.abs(curve[c][:n] - cli[c][:n]).max() / np.abs(cli[c][:n]).max() for c in ("delta", "load"))
        print(f"first loading against {cli_run}: {n} samples, largest relative difference {worst:.1e}")
        if worst > 1e-12:
            sys.exit("the first loading differs from the command line's run")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    main(*sys.argv[1:])
