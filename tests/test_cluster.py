"""What a Dask worker is sent (seacable.cluster.pack): the case's settings and the bytes of
every file it reads, nothing of this machine's folders; built from them in another folder, the
system is the one built from the case's own files."""

import shutil
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable import cluster
from seacable.errors import CaseError
from seacable.system import model

ROOT = Path(__file__).parent.parent


def test_a_packed_case_builds_the_same_system_where_its_folder_is_gone(tmp_path):
    """The moored barge (a hull mesh and a NetCDF database in data/) copied into a folder,
    packed, the folder removed, then unpacked elsewhere: no path of the old folder in what
    is sent, and the same initial state and the same hydrodynamic database (bit for bit)."""
    here = tmp_path / "users_project"
    shutil.copytree(ROOT / "examples" / "data", here / "data")
    shutil.copy(ROOT / "examples" / "moored_barge_irregular_sea.yaml", here / "barge.yaml")
    case = seacable.load_case(here / "barge.yaml")
    expected = model.build(case, str(here))
    packed = cluster.pack(case)
    assert str(tmp_path) not in repr(packed)
    assert sorted(packed["files"]) == ["input_0/barge.stl", "input_1/barge_hydrodb.nc"]
    shutil.rmtree(here)
    rebuilt = cluster.unpack(packed, tmp_path / "worker")
    found = model.build(rebuilt, rebuilt._base_dir)
    np.testing.assert_array_equal(found.y0, expected.y0)
    for name, value in expected.params._asdict().items():  # the mesh's and the database's included
        if name != "entries" and isinstance(value, np.ndarray):  # entries: compiled addresses
            np.testing.assert_array_equal(getattr(found.params, name), value, err_msg=name)
    assert "input_1/barge_hydrodb.nc" in repr(rebuilt.model_dump())  # its files renamed


def test_a_name_pack_does_not_give_is_refused(tmp_path):
    with pytest.raises(CaseError, match="not a name pack gives"):
        cluster.unpack({"case": {}, "files": {"../escape.csv": b"1,2"}}, tmp_path)
    assert not (tmp_path.parent / "escape.csv").exists()
