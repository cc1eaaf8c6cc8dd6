"""Tessera: LS-DEM indentation tests of topologically interlocked slabs.

Lengths in m, forces in N, energies in J, times in s; quaternions (w, x, y, z), body to world.

    import tessera
    sim = tessera.Simulation("assets/scenes/default.toml", bundle="out/default_slab")
    sim.run()                       # settle, load to the protocol's stop
    sim.curve["delta"], sim.curve["load"], sim.response["peak_load"]

See docs/python.md for a load-unload cycle driven by a sample callback.
"""
from ._tessera import (  # noqa: F401  (the C++ core)
    Control,
    InputError,
    Progress,
    Sample,
    Simulation,
    SolverInstability,
    WriteError,
    __version__,
    check,
    curve_units,
    prep,
    read_bundle,
    tile,
    tile_layout,
    tile_tiling,
)
from .run_folder import RunFolder, open_run  # noqa: F401
