"""The evaluation compiled for the kinds a system holds (system.variants, system.evaluation) and
ahead-of-time compilation (seacable compile).

A system's evaluation is a copy of ``system/evaluation.py`` with the flags of the kinds it holds;
the kinds it does not hold are pruned before numba types them. The golden results
(tests/test_golden.py) show the copies compute what the single right-hand side did; here: which
flags a system gets, that a copy refuses a system holding more than it compiles, that the copy
of a set of kinds is written once under a name that changes with the sources, and the command.
"""

import re
from pathlib import Path

import numpy as np
import pytest
import yaml
from click.testing import CliRunner

import seacable
from seacable import ahead
from seacable.cli import main
from seacable.system import kernel, variants
from seacable.system import model as system_model

EXAMPLES = Path(__file__).parent.parent / "examples"


def _built(name: str):
    return system_model.build(seacable.load_case(EXAMPLES / name))


def test_each_system_gets_the_flags_of_the_kinds_it_holds():
    buoys = variants.features(_built("two_buoys_moored_with_hawser.yaml").params)
    assert buoys == ("LUMPED", "TIES", "F_DRAG", "F_APPLIED")  # gravity, buoyancy: in every copy
    thesis = variants.features(_built("thesis_6_1_sim1_air_12_links.yaml").params)
    assert thesis == ("PLANAR", "F_STIFFNESS", "F_DAMPING")
    assert "COMPENSATORS" not in thesis and "F_MESH" not in thesis


def test_a_copy_refuses_a_system_holding_a_kind_it_does_not_compile():
    buoys = _built("two_buoys_moored_with_hawser.yaml")
    chain = _built("thesis_6_1_sim1_air_12_links.yaml")
    foreign = buoys.params._replace(entries=chain.params.entries)  # compiled for planar links
    y = buoys.y0.copy()
    with pytest.raises(RuntimeError, match="compiled without one of its kinds"):
        kernel.rhs(0.0, y, foreign, kernel.make_work(foreign), np.zeros_like(y))

    # waves given to a system whose copy was compiled without the lines' wave code (WAVES)
    sea = np.zeros((buoys.params.wave.shape[0], 1))
    sea[:, 0] = 1.0  # one component's row (the values do not matter: refused before use)
    wavy = buoys.params._replace(wave=sea)
    assert "WAVES" not in variants.features(buoys.params) and "WAVES" in variants.features(wavy)
    with pytest.raises(RuntimeError, match="compiled without one of its kinds"):
        kernel.rhs(0.0, y, wavy, kernel.make_work(wavy), np.zeros_like(y))


def test_unbound_parameters_are_refused_not_called():
    built = _built("two_buoys_moored_with_hawser.yaml")
    p = built.params._replace(entries=np.zeros(len(kernel.ENTRIES), dtype=np.int64))
    y = built.y0.copy()
    with pytest.raises(RuntimeError, match="not bound"):
        kernel.rhs(0.0, y, p, kernel.make_work(p), np.zeros_like(y))


def test_the_copy_of_a_set_of_kinds_is_written_once_under_a_name_of_its_sources(
    monkeypatch, tmp_path
):
    p = _built("two_buoys_moored_with_hawser.yaml").params
    found = variants.variant(p)
    path = Path(found.module.__file__)
    assert path.parent == variants.cache_folder()
    assert path.read_text() == variants.source(variants.features(p))
    stamp = path.stat().st_mtime_ns
    assert variants.variant(p) is found and path.stat().st_mtime_ns == stamp
    text = variants.source(variants.features(p))
    assert "LUMPED = True" in text and "PLANAR = False" in text and "F_MESH = False" in text
    monkeypatch.setattr(variants.stamp, "_digest", ["an edited kernel"])
    monkeypatch.setenv("SEACABLE_CACHE_DIR", str(tmp_path))
    other = variants._module(variants.features(p))
    assert Path(other.__file__).parent == tmp_path
    assert other.__name__ != found.module.__name__  # edited sources: a new copy, a new cache


def test_compile_command_compiles_a_case_and_says_what_it_does(tmp_path):
    data = yaml.safe_load((EXAMPLES / "two_buoys_moored_with_hawser.yaml").read_text())
    data["simulation"]["duration"] = 1.0
    path = tmp_path / "buoys.yaml"
    path.write_text(yaml.safe_dump(data))
    result = CliRunner().invoke(main, ["compile", str(path)])
    assert result.exit_code == 0, result.output
    assert "[1/1] buoys.yaml, dopri5 ..." in result.stderr
    assert "compiled in" in result.stdout
    assert not list(tmp_path.glob("*.nc"))  # nothing written beside the case
    bad = CliRunner().invoke(main, ["compile", str(tmp_path / "missing.yaml")])
    assert bad.exit_code == 2 and bad.stderr.startswith("error:")


def test_the_built_in_systems_are_valid_cases():
    names = [name for name, _ in ahead.built_in()]
    assert names == list(ahead.BUILT_IN)
    labels = [item.label for item in ahead.items(ahead.built_in(), every=True)]
    assert len(labels) == len(ahead.BUILT_IN) * (len(ahead.FAMILIES) + 1)
    # what `seacable compile` runs by default passes every check a run makes first (its
    # step was beyond rk4's limit: the command with no argument exited 2)
    for _, case in ahead.built_in():
        seacable.simulation.prepare(ahead._short(case, None))


@pytest.mark.slow
def test_compile_all_of_the_built_in_systems():
    result = CliRunner().invoke(main, ["compile", "--all"])
    assert result.exit_code == 0, result.output
    started = re.findall(r"^\[\d+/\d+\] .* \.\.\.$", result.stderr, re.MULTILINE)
    assert len(started) == len(ahead.BUILT_IN) * (len(ahead.FAMILIES) + 1), result.stderr
