"""An imposed body moved by one table of its six motions (time, x, y, z, roll_deg, pitch_deg,
yaw_deg; a vessel's motion from a seakeeping code or a model test), each channel naming its
column (case.base.Table's ``column``): the body's pose at the table's times is the table's."""

import numpy as np
import pytest

import seacable
from seacable.errors import CaseError

COLUMNS = ("x", "y", "z", "roll_deg", "pitch_deg", "yaw_deg")


def _case(folder, column="roll_deg"):
    times = np.arange(0.0, 2.01, 0.25)
    motions = np.column_stack([times] + [np.sin(times + k) * (k + 1) for k in range(6)])
    table = folder / "motions.csv"
    rows = "\n".join(",".join(f"{v:.12g}" for v in row) for row in motions)
    table.write_text("time," + ",".join(COLUMNS) + "\n" + rows)
    vessel = {"name": "vessel", "type": "imposed", "points": {"fairlead": [10.0, 0.0, -5.0]}}
    for name in COLUMNS:
        vessel[name] = {"kind": "table", "file": str(table),
                        "column": column if name == "roll_deg" else name}  # fmt: skip
    return seacable.load_case({
        "bodies": [vessel, {"name": "anchor", "type": "fixed", "position": [200.0, 0.0, -60.0]}],
        "line_types": [{"name": "chain", "diameter": 0.1, "mass_per_length": 200.0,
                        "axial_stiffness": 8.0e8}],
        "lines": [{"name": "line", "model": "lumped_mass", "from": "anchor",
                   "to": "vessel.fairlead", "sections": [{"type": "chain", "length": 220.0,
                                                          "segments": 10}]}],
        "environment": {"water_depth": 60.0, "seabed": {"stiffness": 3.0e5}},
        "start": "as_given",
        "simulation": {"duration": 2.0, "output_interval": 0.25},
    }), motions  # fmt: skip


def test_an_imposed_body_follows_a_table_of_its_six_motions(tmp_path):
    case, motions = _case(tmp_path)
    body = seacable.simulate(case).dataset["bodies/vessel"].to_dataset()
    names = ("position_x", "position_y", "position_z", "roll", "pitch", "yaw")
    for k, name in enumerate(names):
        np.testing.assert_allclose(body[name].values, motions[:, k + 1], atol=1e-9)


def test_a_column_the_table_lacks_is_refused_with_its_columns(tmp_path):
    with pytest.raises(CaseError, match="has no column 'heel'.*its columns: time, x, y"):
        seacable.simulate(_case(tmp_path, column="heel")[0])
