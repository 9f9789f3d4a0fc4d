"""The moored barge example (examples/moored_barge_irregular_sea.yaml): its statics are taken
in still water whatever the waves, the incident wave's pressure is counted once, and its
excitation rises over the build-up from rest."""

import copy
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

import seacable
from seacable.errors import CaseError
from seacable.system import model

EXAMPLE = Path(__file__).parent.parent / "examples" / "moored_barge_irregular_sea.yaml"


def _raw() -> dict:
    raw = yaml.safe_load(EXAMPLE.read_text())
    for body in raw["bodies"]:
        for key in ("mesh", "hydrodynamics"):
            if key in body:
                body[key]["file"] = str(EXAMPLE.parent / body[key]["file"])
    return raw


def _barge(raw: dict) -> dict:
    return next(b for b in raw["bodies"] if b["name"] == "barge")


def test_statics_are_in_still_water():
    """The static start in waves is the calm water's balance, to the bit: the waves' mean."""
    raw = _raw()
    calm = copy.deepcopy(raw)
    calm["environment"]["waves"] = []
    wavy = model.build(seacable.load_case(raw))
    still = model.build(seacable.load_case(calm))
    assert wavy.params.wave.shape[1] == 180 and still.params.wave.shape[1] == 0
    assert np.array_equal(wavy.y0, still.y0)


def test_the_incident_pressure_is_counted_once():
    """Hydrostatics clipped at the wave elevation with the database's linear Froude-Krylov
    force, or both Froude-Krylov forces, are refused with the fix."""
    raw = _raw()
    forces = _barge(raw)["external forces"]
    forces[1] = {"model": "non-linear hydrostatic"}
    with pytest.raises(CaseError, match="free_surface: still"):
        seacable.load_case(raw)
    forces[1] = {"model": "non-linear hydrostatic", "free_surface": "still"}
    forces.append({"model": "non-linear Froude-Krylov"})
    with pytest.raises(CaseError, match="keep one of them"):
        seacable.load_case(raw)


@pytest.mark.slow  # 6 s: the chains in a 180-component sea (benchmarks/vessel_cost.py)
def test_the_sea_rises_from_rest():
    """From its static start the barge is at rest and the excitation starts from zero: in the
    first second it moves less than a millimetre, and as the sea rises it moves."""
    raw = _raw()
    raw["simulation"].update(duration=8.0, output_interval=1.0)
    results = seacable.simulate(seacable.load_case(raw))
    barge = results["bodies/barge"]
    start = {c: barge[f"position_{c}"].values for c in "xyz"}
    assert max(abs(v[1] - v[0]) for v in start.values()) < 1e-3
    assert np.ptp(start["z"]) > 0.01  # [m] (0.019 measured)
    tension = results["lines/bow"]["tension"].values
    assert np.all(np.isfinite(tension)) and tension.max() > 0.0


def test_the_animation_draws_the_hull_and_the_waves(tmp_path):
    """viz.system rebuilds the case a results file keeps (its mesh given by an absolute path,
    put back into a temporary folder): the barge's outline in plan is its 90 m x 24 m
    waterplane rectangle turned by its yaw and moved to its position, the sea its 180
    components; the animation is written."""
    from seacable.viz import system as vs

    raw = _raw()
    raw["simulation"] |= {"duration": 1.0, "output_interval": 0.5}
    path = tmp_path / "barge.nc"
    seacable.simulate(seacable.load_case(raw), output=path)
    tree = xr.open_datatree(path)
    meshes, sea = vs.scene(tree)
    hulls = {name: mesh.vertices for name, mesh in meshes.items()}
    assert set(hulls) == {"barge"} and sea["wave"].shape[1] == 180
    ds = tree["bodies/barge"].to_dataset()
    h, v = vs._outline(hulls["barge"], ds, 2, "x", "y")
    yaw = math.radians(float(ds["yaw"].values[2]))
    centre = np.array([ds["position_x"].values[2], ds["position_y"].values[2]])
    turn = np.array([[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]])
    for corner in ([45.0, 12.0], [45.0, -12.0], [-45.0, 12.0], [-45.0, -12.0]):
        x, y = turn @ corner + centre
        assert np.hypot(np.array(h) - x, np.array(v) - y).min() < 0.05  # roll, pitch: cm
    assert (h[0], v[0]) == (h[-1], v[-1])  # closed (a rectangle's corners, or the hexagon of a
    # box tilted by roll and pitch: its corners within centimetres of the rectangle's)
    gif = vs.animate_system(tree, tmp_path / "barge.gif", fps=2, progress=False)
    assert gif.stat().st_size > 0


def test_coarse_chains_find_the_barges_static_balance():
    """The barge on chains of 10 and 20 segments (the example's 40 and a finer 80 too) finds
    its calm-water balance (it found none with 20 before the statics continued from the plain
    seabed spring to the band, system.initial); the poses agree within the discretisation's
    millimetres."""
    poses = {}
    for segments in (10, 20, 40, 80):
        raw = _raw()
        raw["environment"]["waves"] = []
        for line in raw["lines"]:
            for section in line["sections"]:
                section["segments"] = segments
        results = seacable.statics(seacable.load_case(raw))
        assert results.complete
        barge = results.dataset["bodies/barge"]
        poses[segments] = np.array([float(barge[name].values[-1]) for name in
                                    ("position_x", "position_y", "position_z", "yaw")])  # fmt: skip
    for segments in (10, 20, 40):
        assert np.abs(poses[segments] - poses[80]).max() < 5e-3, poses  # measured 2.2e-3
