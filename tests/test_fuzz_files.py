"""Property-based fuzzing of what reads a side file and of the command line's options
(hypothesis): a table of states, of load cases, of a time function, a mesh (OBJ, STL, GDF), a
hydrodynamic database (WAMIT's .1, an HDB file), a MoorDyn deck, made of random bytes or of a
good file changed at random, is read or refused with seacable's own error; an option given
random text is taken or refused in one line with exit code 2, never an internal error. The
same examples each run; a campaign: ``SEACABLE_FUZZ_EXAMPLES=20000 pytest
tests/test_fuzz_files.py`` (random examples)."""

import os
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from seacable import CaseError, SeacableError, hydrodb, meshes
from seacable.case import moordyn
from seacable.case.base import Table
from seacable.cli import main
from seacable.stability.operability import table as states_table

HERE = Path(__file__).resolve().parent
DATA = HERE / "data"
CAMPAIGN = os.environ.get("SEACABLE_FUZZ_EXAMPLES")
FUZZ = settings(
    max_examples=int(CAMPAIGN or 100), deadline=None, derandomize=CAMPAIGN is None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)  # fmt: skip
STATES = b"current_speed,current_towards_deg,wind_speed,wind_towards_deg\n1.0,0,10,0\n1,0,10,30\n"
SEEDS = {  # a good file of each format, which the fuzzing changes
    "states.csv": STATES,
    "table.csv": b"time,force\n0,0\n1,1000\n2,500\n",
    "hull.obj": b"v -1 -1 -1\nv 1 -1 -1\nv 0 1 -1\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n",
    "hull.stl": b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                b"vertex 0 1 0\nendloop\nendfacet\nendsolid a\n",
    "box.1": (DATA / "box.1").read_bytes(),
    "box.hdb": (DATA / "box.hdb").read_bytes(),
    "deck.txt": (DATA / "moordyn_v2_spread.txt").read_bytes(),
}  # fmt: skip


def _changed(seed: bytes, at: int, cut: int, inserted: bytes) -> bytes:
    at = at % (len(seed) + 1)
    return seed[:at] + inserted + seed[at + cut :]


def _read(name: str, path: Path) -> None:
    """Read ``path`` as the format ``name`` names; seacable's refusals are the expected ones."""
    try:
        if name == "states.csv":
            states_table(path)
        elif name == "table.csv":
            Table(kind="table", file=str(path)).load()
        elif name.startswith("hull."):
            meshes.read(path)
        elif name.startswith("box."):
            hydrodb.read(path)
        else:
            moordyn.convert(str(path))
    except (SeacableError, meshes.MeshError) as exc:
        assert "\n" not in str(exc).strip() or isinstance(exc, CaseError), str(exc)
    except ValueError as exc:  # a table's refusal, which the case's field then names
        assert name == "table.csv" and type(exc) is ValueError, repr(exc)
        assert "\n" not in str(exc), str(exc)


@pytest.mark.parametrize("name", sorted(SEEDS))
@FUZZ
@given(at=st.integers(min_value=0, max_value=10**6), cut=st.integers(0, 200),
       inserted=st.binary(max_size=40))  # fmt: skip
@example(at=2676, cut=1, inserted=b"")  # box.1: a period less than the .3's (a campaign's)
def test_a_changed_side_file_is_read_or_refused(tmp_path, name, at, cut, inserted):
    path = tmp_path / name
    if name == "box.1":  # WAMIT's other files beside it, unchanged
        for side in (".3", ".3sc", ".3fk", ".hst"):
            (tmp_path / f"box{side}").write_bytes((DATA / f"box{side}").read_bytes())
    path.write_bytes(_changed(SEEDS[name], at, cut, inserted))
    _read(name, path)


@pytest.mark.parametrize("name", sorted(SEEDS))
@FUZZ
@given(content=st.binary(max_size=400))
def test_random_bytes_as_a_side_file_are_refused(tmp_path, name, content):
    path = tmp_path / name
    path.write_bytes(content)
    _read(name, path)


NUMBER_OPTIONS = [  # (command before the option, option): each takes a number
    (["stats", "{results}"], "--storm"), (["stats", "{results}"], "--from"),
    (["plot", "{results}", "-o", "{tmp}/x.png"], "--every"),
    (["animate", "{results}", "-o", "{tmp}/x.gif", "--no-progress"], "--fps"),
    (["animate", "{results}", "-o", "{tmp}/x.gif", "--no-progress"], "--speed"),
    (["export", "{results}", "--vtk", "-o", "{tmp}/x.pvd"], "--every"),
    (["modes", "{case}"], "--count"),
    (["hydrodb", "{mesh}", "-o", "{tmp}/x.nc"], "--rho"),
    (["hydrodb", "{mesh}", "-o", "{tmp}/x.nc"], "--directions"),
    (["operability", "{case}", "--dask", "none"], "--current-speed"),
    (["operability", "{case}", "--dask", "none", "--current-speed", "1"], "--ratios"),
    (["operability", "{case}", "--dask", "none", "--current-speed", "1"], "--current-towards"),
]  # fmt: skip
TEXTS = st.one_of(
    st.sampled_from(["nan", "inf", "-inf", "-0", "1e999", "0x10", "1_0", "", " ", "1,", ",",
                     "0:1:0", "1:0:1", "0:inf:1", "nan:1:1", "-1", "1e-320", "9" * 5000]),
    st.text(max_size=12),
)  # fmt: skip


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict:
    """A small case's results, the case and a mesh, for the options' commands."""
    import seacable

    sys.path.insert(0, str(HERE / "bad_cases"))
    try:
        import corpus_commands
        import make_corpus
    finally:
        sys.path.remove(str(HERE / "bad_cases"))
    tmp = tmp_path_factory.mktemp("fuzz")
    case = tmp / "system.yaml"
    case.write_text(corpus_commands._system(make_corpus.BASE, make_corpus.PUSH))
    (tmp / "push.dat").write_text("time,force\n0,0\n1,1000\n")
    seacable.simulate(seacable.load_case(case), output=tmp / "results.nc", progress=False)
    (tmp / "hull.obj").write_bytes(corpus_commands.BOX_OBJ)
    return {"results": str(tmp / "results.nc"), "case": str(case), "mesh": str(tmp / "hull.obj"),
            "tmp": str(tmp)}  # fmt: skip


@pytest.mark.parametrize("command,option", NUMBER_OPTIONS)
@settings(max_examples=int(CAMPAIGN or 25), deadline=None, derandomize=CAMPAIGN is None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
@given(text=TEXTS)
def test_an_option_given_any_text_is_taken_or_refused_in_one_line(files, command, option, text):
    """Options that take a number are refused cleanly: exit 2 with one line, or taken; a value
    an option takes only reaches the command when it is one (the operability grid, the modes
    are never run here: each is given a value that stops it before it computes)."""
    args = [a.format(**files) for a in command] + [option, text]
    if args[0] == "operability":
        args += ["--wind-towards", "0", "-o", f"{files['tmp']}/x.txt"]  # refused after parsing
    if args[0] == "modes":
        args += ["--set", "simulation.duration=-1"]  # refused after parsing
    if args[0] == "hydrodb":
        args += ["--omega", "3", "1", "30"]  # refused after parsing (first > last)
    result = CliRunner().invoke(main, args)
    assert result.exit_code in (0, 2), result.output
    errors = [line for line in result.output.splitlines() if line.startswith("error:")]
    assert result.exit_code == 0 or len(errors) == 1, result.output
    assert "internal error" not in result.output and "Traceback" not in result.output
