"""Fixtures of the Python tests (run by CTest: PYTHONPATH holds the build's python/ folder)."""
import os
import subprocess

import pytest

SOURCE = os.environ.get("TESSERA_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))
TESSERA = os.environ.get("TESSERA_EXE", "tessera")
BLOCK = os.path.join(SOURCE, "assets", "blocks", "planar_a10_h3.18_5deg.obj")
SCENE = os.path.join(SOURCE, "assets", "scenes", "default.toml")


@pytest.fixture(scope="session")
def slab(tmp_path_factory):
    """A 3 x 3 slab of the default block at 1 mm uniform nodes, tiled through the Python module."""
    import tessera
    folder = str(tmp_path_factory.mktemp("slab") / "slab")
    tessera.tile(BLOCK, "mm", folder, grid=(3, 3), pitch=10e-3, spacing=1e-3, edge_spacing=1.0)
    return folder


@pytest.fixture(scope="session")
def cli_run(slab, tmp_path_factory):
    """The same test run by the command line, to the protocol's stop."""
    out = str(tmp_path_factory.mktemp("cli") / "run")
    subprocess.run([TESSERA, "run", SCENE, "--bundle", slab, "-o", out, "--no-plot"], check=True,
                   stdout=subprocess.DEVNULL)
    return out
