"""The Python module against the command line and against the physics it stands for."""
import subprocess

import numpy as np
import pytest

import tessera
from conftest import BLOCK, SCENE, TESSERA


def load_unload(slab, turn_at, scene=SCENE, **options):
    """Load to delta = turn_at, then lift the indenter at the same speed until the load is gone."""
    sim = tessera.Simulation(scene, bundle=slab, **options)
    state = {"lifting": False, "turned_at": None}

    def on_sample(sample, control):
        if not state["lifting"] and sample.delta >= turn_at:
            state["lifting"] = True
            state["turned_at"] = len(sim.curve["delta"])
            control.indenter_speed = -control.indenter_speed
        elif state["lifting"] and sample.load <= 0:
            control.stop()

    assert sim.run(on_sample) == "requested"
    return sim, state["turned_at"]


def test_import_names_the_version():
    assert tessera.__version__.count(".") == 2


def test_loading_branch_equals_the_command_line_run(slab, cli_run):
    sim, turned = load_unload(slab, 0.3e-3)
    cli = tessera.open_run(cli_run).curve
    for column in ("time", "delta", "load", "block_displacement", "external_work", "elastic_energy", "friction_dissipated"):
        # The same run, step for step: bit for bit.
        assert np.array_equal(sim.curve[column][:turned], cli[column][:turned]), column


def test_unloading_returns_the_indenter_and_balances_energy(slab):
    sim, turned = load_unload(slab, 0.3e-3)
    delta, load = sim.curve["delta"], sim.curve["load"]
    assert delta[turned - 1] >= 0.3e-3
    assert np.all(np.diff(delta[turned:]) < 0), "delta decreases while lifting"
    assert load[-1] <= 0 < load[turned - 1]
    # Unloading gives back less than loading took (friction, damping): a hysteresis loop.
    assert sim.curve["external_work"][-1] < sim.curve["external_work"][turned - 1]
    e = sim.energy
    assert abs(e["energy_residual"]) < 0.02 * max(sim.curve["external_work"])
    assert sim.indenter["velocity"][2] > 0, "lifting at the end"


def test_the_implicit_method_loads_and_unloads_as_the_explicit_one(slab, tmp_path):
    scene = tmp_path / "implicit.toml"
    scene.write_text(open(SCENE).read().replace("[damping]", '[solver]\nmethod = "implicit"\n\n[damping]'))
    implicit, turned = load_unload(slab, 0.3e-3, scene=str(scene))
    explicit, explicit_turned = load_unload(slab, 0.3e-3)
    delta, load = implicit.curve["delta"], implicit.curve["load"]
    assert np.all(np.diff(delta[turned:]) < 0), "delta decreases while lifting"
    assert load[-1] <= 0 < load[turned - 1]
    assert implicit.curve["external_work"][-1] < implicit.curve["external_work"][turned - 1]
    assert abs(implicit.energy["energy_residual"]) < 0.02 * max(implicit.curve["external_work"])
    # The loading branches at delta = 0.25 mm.
    ours = np.interp(0.25e-3, delta[:turned], load[:turned])
    theirs = np.interp(0.25e-3, explicit.curve["delta"][:explicit_turned], explicit.curve["load"][:explicit_turned])
    assert ours == pytest.approx(theirs, rel=0.01)
    assert implicit.steps < explicit.steps / 50


def test_backing_off_is_no_failure(slab):
    # Lift the indenter well past the load's end, further than the failure rule's quiet travel
    # (0.1 h): the load is gone because the indenter left, so the run neither stops on failure
    # nor reports one.
    sim = tessera.Simulation(SCENE, bundle=slab)

    def on_sample(sample, control):
        if sample.delta >= 0.3e-3 and control.indenter_speed > 0:
            control.indenter_speed = -control.indenter_speed
        elif control.indenter_speed < 0 and sample.delta < -0.2e-3:
            control.stop()

    assert sim.run(on_sample) == "requested"
    assert sim.response["failure_deflection"] is None
    assert sim.response["failure_mode"] == "none up to the requested stop"


def test_results_as_arrays_in_si_units(slab):
    sim, _ = load_unload(slab, 0.1e-3)
    n = len(sim.body_names)
    assert sim.positions.shape == (n, 3) and sim.orientations.shape == (n, 4)
    assert np.allclose(np.linalg.norm(sim.orientations, axis=1), 1.0)
    c = sim.contacts()
    assert len(c["a"]) > 0 and c["force"].shape == (len(c["a"]), 3)
    assert np.all(c["area"] > 0) and np.all(c["node_contacts"] > 0)
    # Newton's third law over the whole slab at rest: the contact forces on the free block and the
    # fixed ones, with the indenter's reaction, balance its weight (to the dynamics left).
    assert sim.time_step > 0 and sim.steps > 0


def test_a_run_folder_written_from_python_reads_back(slab, tmp_path):
    out = str(tmp_path / "run")
    sim, _ = load_unload(slab, 0.1e-3, output=out)
    folder = tessera.open_run(out)
    assert folder.summary["stop_reason"] == "requested"
    assert np.array_equal(folder.curve["load"], sim.curve["load"])


def test_prep_adds_a_validated_shape(tmp_path):
    shape = tessera.prep(BLOCK, "mm", str(tmp_path / "b"))
    a, h, theta = 10e-3, 3.18e-3, np.radians(5)
    assert shape["volume"] == pytest.approx(a * a * h - h ** 3 * np.tan(theta) ** 2 / 3, rel=1e-9)
    assert shape["nodes"] > 100 and shape["level_set"].startswith("exact planes")
    # Nodes graded to a quarter of the spacing along the sharp edges by default; 1 is uniform.
    assert shape["edge_node_spacing"] == pytest.approx(0.25 * shape["node_spacing"])
    uniform = tessera.prep(BLOCK, "mm", str(tmp_path / "u"), edge_spacing=1.0)
    assert uniform["edge_node_spacing"] == uniform["node_spacing"] and uniform["nodes"] < shape["nodes"] / 2
    assert tessera.read_bundle(str(tmp_path / "b"))["shapes"] == ["planar_a10_h3.18_5deg"]
    with pytest.raises(ValueError, match="already holds a shape"):
        tessera.prep(BLOCK, "mm", str(tmp_path / "b"))
    with pytest.raises(ValueError, match="edge_spacing must be between"):
        tessera.prep(BLOCK, "mm", str(tmp_path / "c"), edge_spacing=2.0)


def test_overrides_change_the_scene(slab):
    soft = tessera.Simulation(SCENE, bundle=slab, overrides={"material.youngs_modulus": 2.1e9})
    stiff = tessera.Simulation(SCENE, bundle=slab)
    assert soft.time_step > stiff.time_step  # dt goes as 1 / sqrt(k_n)


def test_bad_input_is_a_value_error_naming_the_problem(slab, tmp_path):
    with pytest.raises(ValueError, match="no such scene file"):
        tessera.Simulation(str(tmp_path / "missing.toml"), bundle=slab)
    with pytest.raises(tessera.InputError, match="material.nonsense"):
        tessera.Simulation(SCENE, bundle=slab, overrides={"material.nonsense": 1.0})
    # Values a run would not take as given (issue #39): refused, never rounded or crashed on.
    with pytest.raises(tessera.InputError, match="'span.interfaces' takes a whole number, not 2.5"):
        tessera.Simulation(SCENE, bundle=slab, overrides={"span.interfaces": 2.5})
    with pytest.raises(tessera.InputError, match="threads must be 0 .all cores. or 1 to 1024"):
        tessera.Simulation(SCENE, bundle=slab, threads=10**9)
    with pytest.raises(ValueError, match="overlap"):
        tessera.tile(BLOCK, "mm", str(tmp_path / "tight"), grid=(3, 3), pitch=8e-3)
    # A pitch given in mm (10 m): no two blocks touch, refused before anything is written.
    with pytest.raises(ValueError, match="no two of the 9 bodies touch.*pitch or positions"):
        tessera.tile(BLOCK, "mm", str(tmp_path / "apart"), grid=(3, 3), pitch=10)
    assert not (tmp_path / "apart").exists()


def test_tile_turns_a_y_up_block_to_z_up(tmp_path):
    # The block written y-up, (x, y, z) -> (x, z, -y): with up="y" the same slab as the z-up one.
    lines = []
    for line in open(BLOCK):
        if line.startswith("v "):
            x, y, z = (float(t) for t in line.split()[1:4])
            line = f"v {x!r} {z!r} {-y!r}\n"
        lines.append(line)
    (tmp_path / "yup.obj").write_text("".join(lines))
    kw = dict(grid=(3, 3), pitch=10e-3, spacing=1e-3, edge_spacing=1.0)
    up = tessera.tile(str(tmp_path / "yup.obj"), "mm", str(tmp_path / "up"), up="y", **kw)
    z = tessera.tile(BLOCK, "mm", str(tmp_path / "z"), **kw)
    assert up["interlocked"] == z["interlocked"] == 1
    a, b = tessera.read_bundle(str(tmp_path / "up")), tessera.read_bundle(str(tmp_path / "z"))
    assert np.abs(np.asarray(a["position"]) - np.asarray(b["position"])).max() < 1e-12
    # prep takes up= too (what it changes, the shape's frame, is what the tiling above checks);
    # an axis that is none is refused.
    shape = tessera.prep(str(tmp_path / "yup.obj"), "mm", str(tmp_path / "shapes"), up="y", spacing=1e-3)
    assert shape["volume"] == pytest.approx(tessera.prep(BLOCK, "mm", str(tmp_path / "shapes_z"), spacing=1e-3)["volume"], rel=1e-9)
    with pytest.raises(ValueError, match="up axis 'q'"):
        tessera.prep(BLOCK, "mm", str(tmp_path / "bad"), up="q")


def test_results_file_states_units_scene_and_contact_split(cli_run):
    import h5py
    with h5py.File(f"{cli_run}/results.h5", "r") as f:
        assert f.attrs["format_version"] == 3
        assert b"[material]" in f.attrs["scene_text"] or "[material]" in str(f.attrs["scene_text"])
        missing = []
        f.visititems(lambda name, item: missing.append(name) if isinstance(item, h5py.Dataset) and
                     item.dtype.kind != "S" and "unit" not in item.attrs else None)
        assert missing == []
        s = f["snapshots"]
        assert s["orientation"].attrs["note"].startswith(b"unit quaternion (w, x, y, z)")
        force, normal, tangential = s["force"][()], s["force_normal"][()], s["force_tangential"][()]
        assert len(force) > 0
        assert np.allclose(normal + tangential, force, rtol=0, atol=1e-12 * np.abs(force).max())
        assert np.all((s["force_sliding_fraction"][()] >= 0) & (s["force_sliding_fraction"][()] <= 1))
        assert np.all(s["force_area"][()] > 0) and np.all(s["force_node_contacts"][()] > 0)
        assert s["velocity"].shape == s["position"].shape
        assert s["indenter"].shape == (len(s["delta"]), 3)


def test_a_callback_that_raises_stops_the_run_resumably(slab, tmp_path):
    out = str(tmp_path / "run")
    sim = tessera.Simulation(SCENE, bundle=slab, output=out, overrides={"protocol.delta_max": 0.3e-3})

    def fails(sample, control):
        if sample.delta >= 0.1e-3:
            raise ArithmeticError("my controller")

    with pytest.raises(ArithmeticError, match="my controller"):
        sim.run(fails)
    assert sim.stop_reason == "interrupted"
    with pytest.raises(tessera.InputError, match="this process still holds a run there"):
        tessera.Simulation.resume(out)  # the first session still holds the folder (not "another process")
    del sim  # releases the folder
    resumed = tessera.Simulation.resume(out)
    assert resumed.run() == "delta_max"
    whole = tessera.Simulation(SCENE, bundle=slab, overrides={"protocol.delta_max": 0.3e-3})
    whole.run()
    assert np.array_equal(resumed.curve["load"], whole.curve["load"])


def test_a_control_is_valid_only_inside_its_callback_and_speeds_are_bounded(slab):
    kept = []
    sim = tessera.Simulation(SCENE, bundle=slab, overrides={"protocol.delta_max": 0.05e-3})
    sim.run(lambda sample, control: kept.append(control))
    with pytest.raises(RuntimeError, match="only inside the sample callback"):
        kept[0].indenter_speed = 1.0
    fast = tessera.Simulation(SCENE, bundle=slab)

    def too_fast(sample, control):
        control.indenter_speed = 1e6

    with pytest.raises(ValueError, match="broad-phase margin"):
        fast.run(too_fast)
    with pytest.raises(ValueError, match="no run folder"):
        fast.write_outputs()



def test_a_generated_tiling_is_checked_as_the_command_line_checks_it(tmp_path):
    import json
    slab = str(tmp_path / "hex")
    summary = tessera.tile_tiling("hex", slab, thickness=3.18e-3, angle=5, grid=(5, 5), pitch=10e-3)
    assert summary["bodies"] == 25 and summary["free"] == 9
    verdict = tessera.check(slab)
    assert verdict["interlocked"] and verdict["stable"] and verdict["least_friction"] == 0
    cli = json.loads(subprocess.run([TESSERA, "check", slab, "--json"], check=True, capture_output=True, text=True).stdout)
    assert set(verdict) == set(cli)  # the same keys as tessera check --json
    for key in set(cli) - {"seconds"}:
        assert verdict[key] == cli[key], key
    with pytest.raises(ValueError, match="needs pitch"):
        tessera.tile_tiling("hex", str(tmp_path / "nopitch"), thickness=3.18e-3)
