"""Property-based fuzzing of the case loader (hypothesis): an example case changed at random
(a value replaced by any kind of value, a key removed or added, its YAML text cut or its bytes
changed) is read or refused with ``CaseError``; no other exception escapes. A campaign of
20,000 random examples a test: ``SEACABLE_FUZZ_EXAMPLES=20000 pytest tests/test_fuzz_loader.py``."""

import copy
import os
from pathlib import Path

import yaml
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import seacable
from seacable import CaseError

EXAMPLE = Path(__file__).resolve().parent.parent / "examples/two_buoys_moored_with_hawser.yaml"
TEXT = EXAMPLE.read_text()
BASE = yaml.safe_load(TEXT)

VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=20),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner,
                                                                max_size=3),
    max_leaves=8,
)  # fmt: skip


def _paths(data, prefix=()):
    """Every path to a value in nested dicts and lists."""
    yield prefix
    if isinstance(data, dict):
        for key, value in data.items():
            yield from _paths(value, (*prefix, key))
    elif isinstance(data, list):
        for k, value in enumerate(data):
            yield from _paths(value, (*prefix, k))


PATHS = [path for path in _paths(BASE) if path]
# 300 examples a test, the same ones each run (the suite must not flicker); a campaign:
# SEACABLE_FUZZ_EXAMPLES=20000 pytest tests/test_fuzz_loader.py (random examples)
CAMPAIGN = os.environ.get("SEACABLE_FUZZ_EXAMPLES")
FUZZ = settings(
    max_examples=int(CAMPAIGN or 300), deadline=None, derandomize=CAMPAIGN is None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)  # fmt: skip


def _load(source) -> None:
    try:
        seacable.load_case(source)
    except CaseError:
        pass


@FUZZ
@given(st.lists(st.tuples(st.sampled_from(PATHS), st.sampled_from(["set", "remove", "add"]),
                          VALUES), min_size=1, max_size=4))  # fmt: skip
def test_a_changed_case_is_read_or_refused_with_a_case_error(changes):
    data = copy.deepcopy(BASE)
    for path, how, value in changes:
        parent = data
        try:
            for key in path[:-1]:
                parent = parent[key]
            if how == "set":
                parent[path[-1]] = value
            elif how == "remove":
                del parent[path[-1]]
            elif isinstance(parent, dict):
                parent[f"{path[-1]}_extra"] = value
        except (KeyError, IndexError, TypeError):
            continue  # an earlier change removed the way there
    _load(data)


@FUZZ
@example(at=0, cut=0, inserted=b"? {a: 1}\n: 2\n")  # a mapping as a key: found by a campaign
@given(st.integers(0, len(TEXT)), st.integers(0, 40), st.binary(max_size=12))
def test_changed_yaml_text_is_read_or_refused_with_a_case_error(at, cut, inserted):
    text = TEXT[:at] + inserted.decode("utf-8", "replace") + TEXT[at + cut :]
    _load(text)


@FUZZ
@given(st.binary(max_size=200))
def test_bytes_as_a_case_file_are_refused_with_a_case_error(tmp_path_factory, content):
    path = tmp_path_factory.mktemp("fuzz") / "case.yaml"
    path.write_bytes(content)
    _load(path)
