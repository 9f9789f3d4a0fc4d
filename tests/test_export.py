"""seacable export --vtk: the files ParaView reads, read back by another reader (meshio): each
line's segments with the tension the results give them, the barge's hull as its mesh's
triangles turned and moved as the body is (a rotation composed here, Rz Ry Rx), and a
collection that orders the files in time."""

import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import seacable
from seacable.cli import main
from seacable.meshes import read

meshio = pytest.importorskip("meshio")
EXAMPLES = Path(__file__).parent.parent / "examples"


def _turn(roll: float, pitch: float, yaw: float) -> np.ndarray:
    r, p, y = (math.radians(a) for a in (roll, pitch, yaw))
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def test_a_moored_barge_for_paraview(tmp_path):
    run = tmp_path / "barge.nc"
    outcome = CliRunner().invoke(main, ["run", str(EXAMPLES / "moored_barge_irregular_sea.yaml"),
                                        "-o", str(run), "--no-progress", "--set",
                                        "simulation.duration=4"])  # fmt: skip
    assert outcome.exit_code == 0, outcome.output
    outcome = CliRunner().invoke(main, ["export", str(run), "--vtk", "--every", "2"])
    assert outcome.exit_code == 0, outcome.output
    collection = (tmp_path / "barge.pvd").read_text()
    steps = re.findall(r'timestep="([^"]+)" file="([^"]+)"', collection)
    results = seacable.Results.open(run)
    t = results["time"].values
    assert [float(s) for s, _ in steps] == [0.0, 2.0, 4.0]
    case = seacable.load_case(EXAMPLES / "moored_barge_irregular_sea.yaml")
    mesh = read(EXAMPLES / case.bodies[3].mesh.file)
    for stamp, name in steps:
        i = int(np.flatnonzero(t == float(stamp))[0])
        grid = meshio.read(tmp_path / name)
        segments = grid.cells_dict["line"]
        tension = np.ravel(grid.cell_data_dict["tension"]["line"])
        offset = 0
        for line in case.lines:
            expected = results[f"lines/{line.name}/tension"].values[i]
            n = expected.size
            np.testing.assert_allclose(tension[offset : offset + n], expected, rtol=1e-8)
            nodes = np.column_stack([results[f"lines/{line.name}/node_{c}"].values[i]
                                     for c in "xyz"])  # fmt: skip
            np.testing.assert_allclose(grid.points[segments[offset : offset + n, 0]],
                                       nodes[:-1], atol=1e-6)  # fmt: skip
            offset += n
        assert len(segments) == offset
        triangles = grid.cells_dict["triangle"]
        assert len(triangles) == len(mesh.triangles)
        body = {
            k: float(results[f"bodies/barge/{k}"].values[i])
            for k in ("position_x", "position_y", "position_z", "roll", "pitch", "yaw")
        }
        where = mesh.vertices @ _turn(body["roll"], body["pitch"], body["yaw"]).T + [
            body["position_x"], body["position_y"], body["position_z"]]  # fmt: skip
        np.testing.assert_allclose(grid.points[triangles], where[mesh.triangles], atol=1e-6)
    again = CliRunner().invoke(main, ["export", str(run), "--vtk", "-o", str(run)])
    assert again.exit_code == 2 and "ending in .pvd" in again.output
    mine = tmp_path / "mine.pvd"
    mine.write_text("my notes")
    refused = CliRunner().invoke(main, ["export", str(run), "--vtk", "-o", str(mine)])
    assert refused.exit_code == 2 and "is not a ParaView collection" in refused.output
    no_format = CliRunner().invoke(main, ["export", str(run)])
    assert no_format.exit_code == 2 and "--vtk" in no_format.output
