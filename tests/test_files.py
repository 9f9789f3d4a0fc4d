"""seacable.files: where outputs go and how side files are read. A link planted where a writer
once put its temporary file does not redirect the write; a write that fails leaves the previous
file whole; an output replaces only an output of its kind; a side file is read within its
bounds; an HDF5 file that keeps data elsewhere is refused."""

import os

import h5py
import numpy as np
import pytest

import seacable
from seacable import files
from seacable.errors import InputError, OutputError


def test_a_link_at_the_old_temporary_name_does_not_redirect_a_run(tmp_path):
    """``run`` made its file as ``.out.nc.creating`` beside the output, following a link
    planted there: it overwrote the file the link pointed to (issue 42's probe)."""
    from test_case_errors import CHAIN

    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    (tmp_path / ".out.nc.creating").symlink_to(victim)
    results = seacable.simulate(seacable.load_case(CHAIN), output=tmp_path / "out.nc")
    assert results.status == "complete" and victim.read_text() == "keep me"
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".writing")]


def test_a_failed_write_leaves_the_previous_file_and_no_litter(tmp_path):
    page = tmp_path / "page.html"
    page.write_text("before")
    with pytest.raises(RuntimeError), files.replacing(page) as aside:
        aside.write_text("half")
        raise RuntimeError("interrupted")
    assert page.read_text() == "before" and sorted(os.listdir(tmp_path)) == ["page.html"]
    files.replace_text(page, "after")
    mask = os.umask(0)
    os.umask(mask)
    assert page.read_text() == "after" and (page.stat().st_mode & 0o777) == (0o666 & ~mask)


def test_an_output_replaces_only_an_output_of_its_kind(tmp_path):
    mine = tmp_path / "mine.nc"
    with h5py.File(mine, "w") as f:
        f.attrs["title"] = "seacable equilibria"
    files.check_output(mine, "netcdf", title="seacable equilibria")
    with pytest.raises(OutputError, match=r"is not a 'seacable simulation results' file"):
        files.check_output(mine, "netcdf", title="seacable simulation results")
    link = tmp_path / "link.nc"
    link.symlink_to(mine)
    with pytest.raises(OutputError, match=r"is a link \(to '.*mine\.nc'\)"):
        files.check_output(link, "netcdf", title="seacable equilibria")
    hard = tmp_path / "hard.nc"
    os.link(mine, hard)  # the same file under another name is still a file the command reads
    with pytest.raises(OutputError, match=r"is a file this command reads"):
        files.check_output(hard, "netcdf", [mine], title="seacable equilibria")


def test_side_files_are_read_within_their_bounds(tmp_path):
    with pytest.raises(InputError, match=r"'/dev/zero' is not a regular file"):
        files.read_bytes("/dev/zero", "table file", 1000)
    big = tmp_path / "big.csv"
    big.write_bytes(b"1,2\n" * 1000)
    with pytest.raises(InputError, match=r"larger than 100 bytes"):
        files.read_bytes(big, "table file", 100)
    cell = "a," + "9" * 200_000 + "\n" + "b," + "9" * (files.LONGEST_CELL + 1) + "\n"
    rows = files.csv_rows(cell, "table")
    assert next(rows)[0] == 1  # a cell past csv's default 128 kB reads
    with pytest.raises(InputError, match=r"table line 2: not readable CSV"):
        next(rows)


def test_an_hdf5_file_that_keeps_data_elsewhere_is_refused(tmp_path):
    secret = tmp_path / "secret.bin"
    secret.write_bytes(np.arange(4.0).tobytes())
    path = tmp_path / "results.nc"
    with h5py.File(path, "w") as f:
        f.create_dataset("time", shape=(4,), dtype="<f8", external=[(str(secret), 0, 32)])
    with pytest.raises(InputError, match=r"'time' is stored in"):
        seacable.Results.open(path)
