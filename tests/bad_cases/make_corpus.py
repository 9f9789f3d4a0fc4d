"""Writes the corpus of bad case files (``tests/test_bad_cases.py`` runs it): each file a case
that must be refused, and ``expected.yaml``: for each file, its group (``kind``) and what the
one-line message must match (``expect``, a regex: the field or file, and the value). Most are
mutations of an example (every kind of number made NaN, infinite, a boolean, text, a list, negative;
keys missing, unknown or given twice; names that resolve to nothing); the rest are hostile or
broken YAML and files that are not cases. Run from the repository's root:
``python tests/bad_cases/make_corpus.py`` (it replaces the files it writes)."""

import copy
import re
from pathlib import Path

import corpus_commands
import yaml

HERE = Path(__file__).resolve().parent
BASE = yaml.safe_load(
    (HERE.parent.parent / "examples/two_buoys_moored_with_hawser.yaml").read_text()
)

# (path in the case, as the message writes it; keys to reach it; positive only)
NUMBERS = [
    ("environment.water_density", ["environment", "water_density"], True),
    ("environment.water_depth", ["environment", "water_depth"], True),
    ("environment.seabed.stiffness", ["environment", "seabed", "stiffness"], False),
    ("environment.current.velocity", ["environment", "current", "velocity"], False),
    ("bodies[6].mass", ["bodies", 6, "mass"], False),
    ("bodies[6].position", ["bodies", 6, "position", 2], False),
    ("bodies[6].shape.radius", ["bodies", 6, "shape", "radius"], True),
    ("bodies[6].added_mass", ["bodies", 6, "added_mass", 0], False),
    ("bodies[6].external forces[2].drag_coefficient",
     ["bodies", 6, "external forces", 2, "drag_coefficient"], False),
    ("line_types[0].diameter", ["line_types", 0, "diameter"], True),
    ("line_types[0].mass_per_length", ["line_types", 0, "mass_per_length"], True),
    ("line_types[0].axial_stiffness", ["line_types", 0, "axial_stiffness"], True),
    ("line_types[0].axial_damping_ratio", ["line_types", 0, "axial_damping_ratio"], False),
    ("line_types[0].drag_coefficient_normal", ["line_types", 0, "drag_coefficient_normal"], False),
    ("lines[0].sections[0].length", ["lines", 0, "sections", 0, "length"], True),
    ("lines[0].sections[0].segments", ["lines", 0, "sections", 0, "segments"], True),
    ("lines[6].unstretched_length", ["lines", 6, "unstretched_length"], True),
    ("lines[6].damping", ["lines", 6, "damping"], False),
    ("simulation.duration", ["simulation", "duration"], True),
    ("simulation.output_interval", ["simulation", "output_interval"], True),
]  # fmt: skip
PUSH = ["bodies", 7, "external forces", 3, "force_x"]  # buoy B's applied force
ZERO_ALLOWED = {"lines[6].unstretched_length"}  # a tie of zero length: a spring between points
VALUES = [  # (file name part, value, what the message quotes)
    ("nan", float("nan"), r"nan"), ("inf", float("inf"), r"inf"),
    ("minus_inf", -float("inf"), r"-inf"), ("true", True, r"True"), ("text", "abc", r"'abc'"),
    ("list", [1.0, 2.0], r"\[1\.0, 2\.0\]"),
]  # fmt: skip


def _set(data, keys, value):
    """Put ``value`` at ``keys`` in ``data``."""
    for key in keys[:-1]:
        data = data[key]
    data[keys[-1]] = value


def _remove(data, keys):
    for key in keys[:-1]:
        data = data[key]
    del data[keys[-1]]


def _mutated(name, kind, expect, change):
    """A corpus entry: the base case changed by ``change``."""
    data = copy.deepcopy(BASE)
    change(data)
    return (name, kind, expect, yaml.safe_dump(data, sort_keys=False), None)


def cases():
    """(name, kind, expect, text or bytes, output) of every bad case: ``output`` None for a
    case ``seacable validate`` refuses, else the output path (relative to the corpus) that
    ``seacable run`` refuses."""
    out: list = []

    def mutated(name, kind, expect, change):
        out.append(_mutated(name, kind, expect, change))

    for where, keys, positive in NUMBERS:
        stem = re.sub(r"\W+", "_", where).strip("_")
        for label, value, quoted in VALUES:
            mutated(f"{stem}.{label}", "numbers", re.escape(where) + r".*\(got .*" + quoted,
                    lambda d, k=keys, v=value: _set(d, k, v))  # fmt: skip
        mutated(f"{stem}.huge", "numbers", re.escape(where) + r": a number beyond 1e\+15 .*"
                r"\(got .*1e\+300", lambda d, k=keys: _set(d, k, 1e300))  # fmt: skip
        if positive:
            mutated(f"{stem}.negative", "numbers", re.escape(where) + r".*\(got -1(\.0)?\)",
                    lambda d, k=keys: _set(d, k, -1.0))  # fmt: skip
        if positive and where not in ZERO_ALLOWED:
            mutated(f"{stem}.zero", "numbers",
                    re.escape(where) + r".*greater than (0|or equal to 1).*\(got 0",
                    lambda d, k=keys: _set(d, k, 0))  # fmt: skip
    for where, keys in [
        ("(top level)", ["simulation"]),
        ("bodies[0]", ["bodies", 0, "name"]),
        ("bodies[6]", ["bodies", 6, "mass"]), ("lines[0]", ["lines", 0, "from"]),
        ("lines[0].sections[0]", ["lines", 0, "sections", 0, "length"]),
        ("line_types[0]", ["line_types", 0, "diameter"]),
        ("simulation", ["simulation", "duration"]),
    ]:  # fmt: skip
        missing = ".".join(str(k) for k in keys[-1:])
        path = missing if where == "(top level)" else f"{where}.{missing}"
        mutated(
            f"missing.{'_'.join(str(k) for k in keys)}",
            "missing keys",
            re.escape(path) + r": required key is missing",
            lambda d, k=keys: _remove(d, k),
        )
    for where, keys, key in [
        ("(top level)", [], "solver"), ("bodies[6]", ["bodies", 6], "colour"),
        ("lines[0].sections[0]", ["lines", 0, "sections", 0], "lenght"),
        ("environment", ["environment"], "wave_height"), ("simulation", ["simulation"], "dt"),
    ]:  # fmt: skip
        mutated(
            f"unknown.{key}",
            "unknown keys",
            re.escape(f"{where}: unknown key '{key}'") + r"\. Valid keys",
            lambda d, k=keys, name=key: _set(d, [*k, name], 1.0),
        )
    for name, expect, keys, value in [
        ("from_nowhere", r"lines\[0\].*'nowhere'", ["lines", 0, "from"], "nowhere"),
        ("to_unknown", r"lines\[1\].*'buoy_z'", ["lines", 1, "to"], "buoy_z"),
        ("section_type", r"\(a_north\)\.sections\[0\]\.type: no line type 'chain9'",
         ["lines", 0, "sections", 0, "type"], "chain9"),
        ("line_model", r"lines\[0\]\.model: value 'spring' is not allowed", ["lines", 0, "model"],
         "spring"),
        ("body_type", r"bodies\[6\]\.type: value 'floating' is not allowed", ["bodies", 6, "type"],
         "floating"),
        ("integrator", r"simulation\.integrator: .*'euler'", ["simulation", "integrator"],
         "euler"),
        ("same_body_names", r"bodies: names must be unique; \['buoy_a'\]", ["bodies", 7, "name"],
         "buoy_a"),
        ("same_line_names", r"lines: names must be unique; \['a_north'\]", ["lines", 1, "name"],
         "a_north"),
        ("long_duration", r"simulation: .*output rows, more than any run can write",
         ["simulation", "duration"], 1e12),
        ("anchor_below_seabed",
         r"bodies\[0\] \(anchor_a_north\)\.position: z = -60 m is below the seabed \(z = -50 m",
         ["bodies", 0, "position", 2], -60.0),
    ]:  # fmt: skip
        mutated(f"names.{name}", "names and choices", expect,
                lambda d, k=keys, v=value: _set(d, k, v))  # fmt: skip
    mutated("geometry.stretched_line", "impossible geometry",
            r"lines \(a_west\): its ends are 235\.\d+ m apart and its unstretched length is "
            r"150 m, a strain of 56\.9 %.*more stretch than a line takes",
            lambda d: (d.update(start="as_given"), _set(d, ["bodies", 6, "position"],
                                                        [100.0, 0.0, 0.0])))  # fmt: skip

    def point_volume(d):
        d["bodies"][6].pop("shape")
        d["bodies"][6]["volume"] = 78.5

    for name, expect, change in [
        ("body_below_seabed", r"bodies\[6\] \(buoy_a\): starts at z = -60 m, below the seabed",
         lambda d: (d.update(start="as_given"), _set(d, ["bodies", 6, "position", 2], -60.0))),
        ("point_volume_above_water",
         r"bodies\[6\] \(buoy_a\): its centre of buoyancy starts at z = 24\.9\d* m, above the "
         r"water", point_volume),
        ("overstretched_in_balance",
         r"lines \(a_north\): its most stretched segment \(14\) starts at a strain of 46\.2 %.*"
         r"more stretch than a line takes",
         lambda d: _set(d, ["line_types", 0, "axial_stiffness"], 5e4)),
    ]:  # fmt: skip
        mutated(f"geometry.{name}", "impossible geometry", expect, change)
    beyond = r"s is beyond rk4's stability limit: .* rad/s, moving node \d+ of line '\w+'.*Use "
    for name, step, change in [
        ("rk4_default_step", "0.01", {}),
        ("rk4_step", "0.00625", {"time_step": 0.00625}),
        ("stiff_chain", "0.002", {"time_step": 0.002}),
    ]:  # fmt: skip

        def unstable(d, change=change, name=name):
            d["simulation"].update(integrator="rk4", **change)
            if name == "stiff_chain":  # stable at EA 2.5e8 N (0.64 of the limit), not at 2.5e10
                d["line_types"][0]["axial_stiffness"] = 2.5e10

        mutated(f"unstable.{name}", "unstable steps",
                re.escape(f"simulation.time_step: {step} ") + beyond, unstable)  # fmt: skip
    return out + _vessel_forces() + _files()


def _vessel_forces() -> list:
    """A propeller or a fin added to buoy B with one bad key, and on a buoy at all (a point
    body: they act on a rigid one)."""
    out: list = []
    propeller = {"model": "propeller", "diameter": 2.0, "rpm": 100.0,
                 "open_water": {"kind": "b_series", "pitch_ratio": 1.0, "area_ratio": 0.7,
                                "blades": 4}}  # fmt: skip
    fin = {"model": "fin", "area": 2.0, "lift_slope": 3.0, "span_direction": [0.0, -1.0, 0.0],
           "angle_deg": 5.0}  # fmt: skip
    at = re.escape("bodies[7].external forces[4]")
    for name, expect, model in [
        ("wake_fraction", at + r"\.wake_fraction: Input should be less than 1 \(got 1\.2\)",
         propeller | {"wake_fraction": 1.2}),
        ("pitch_ratio", at + r"\.open_water\.pitch_ratio: Input should be less than or equal to "
         r"1\.4 \(got 1\.6\)",
         propeller | {"open_water": propeller["open_water"] | {"pitch_ratio": 1.6}}),
        ("rpm_and_controller", at + r": give exactly one of 'rpm' \[rpm, time function\] or "
         r"'controller'",
         propeller | {"controller": {"kind": "surge_speed", "target": 3.0, "gain": 10.0}}),
        ("curves_backwards", at + r"\.open_water: coefficients: advance ratios \[0\.5, 0\.2\] "
         r"must be 2 or more, increasing strictly",
         propeller | {"open_water": {"kind": "table",
                                     "coefficients": [[0.5, 0.3, 0.04], [0.2, 0.4, 0.05]]}}),
        ("fin_span_along_x", at + r": span_direction \[1\.0, 0\.0, 0\.0\] has no length or "
         r"lies along the body's x axis", fin | {"span_direction": [1.0, 0.0, 0.0]}),
        ("propeller_on_a_buoy", re.escape("bodies[7] (buoy_b).external forces[4]: model "
                                          "'propeller' acts on a vessel: a 'rigid' body (this "
                                          "one is 'point')"), propeller),
    ]:  # fmt: skip

        def add(data, model=model):
            data["bodies"][7]["external forces"].append(model)

        out.append(_mutated(f"vessel.{name}", "vessel forces", expect, add))
    return out


def _files() -> list:
    """Bad table files, hostile or broken YAML, files that are not cases, bad output paths."""
    out: list = []

    def mutated(name, kind, expect, change):
        out.append(_mutated(name, kind, expect, change))

    push = PUSH
    for name, expect in [
        ("missing", r"table file '.*tables/missing\.csv' does not exist"),
        ("nan", r"table file '.*tables/nan\.csv': NaN or infinite values"),
        ("huge", r"table file '.*tables/huge\.csv': a value beyond 1e\+15"),
        ("backwards", r"table file '.*tables/backwards\.csv' needs at least 2 rows with strictly "
                      r"increasing times"),
        ("latin1", r"table file '.*tables/latin1\.csv' is not UTF-8 text \(byte 0xe9"),
        ("bad_row", r"table file '.*tables/bad_row\.csv': bad row \['1', 'ten'\]"),
        ("folder", r"table file '.*tables/folder\.csv' is a directory"),
    ]:  # fmt: skip
        mutated(
            f"tables.{name}",
            "bad tables",
            re.escape("bodies[7]") + r".*" + expect,
            lambda d, f=name: _set(d, push, {"kind": "table", "file": f"tables/{f}.csv"}),
        )
    text = yaml.safe_dump(BASE, sort_keys=False)
    bomb = "a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n" + "".join(
        f"{chr(98 + i)}: &{chr(98 + i)} [{', '.join([f'*{chr(97 + i)}'] * 10)}]\n"
        for i in range(7)
    )  # fmt: skip
    for name, expect, content in [
        ("duplicate_key", r"key 'name' is given twice in one mapping", text + "name: again\n"),
        ("unclosed_flow_list", r"not valid YAML",
         text.replace("- name: buoy_a", "- name: [buoy_a", 1)),
        ("tab_indent", r"not valid YAML", text.replace("\n  water_depth", "\n\twater_depth", 1)),
        ("alias_bomb", r"more than 1,000,000 values once its aliases", bomb),
        ("deep_nesting", r"nested too deeply", "a: " + "[" * 5000 + "]" * 5000 + "\n"),
        ("top_level_list", r"a case must be a mapping", "- 1\n- 2\n"),
        ("empty", r"a case must be a mapping", "# nothing\n"),
        ("python_tag", r"not valid YAML", "!!python/object/apply:os.system ['true']\n"),
        ("cables_form", r"single-cable form", "cables: []\n"),
    ]:  # fmt: skip
        out.append((f"yaml.{name}", "hostile or broken YAML", expect, content, None))
    for name, expect, content in [
        ("latin1", r"not UTF-8 text \(byte 0xe9", ("# caf\xe9\n" + text).encode("latin-1")),
        ("utf16", r"not UTF-8 text \(byte 0xff", text.encode("utf-16")),
        ("results_file", r"is a results file \(NetCDF/HDF5\)", b"\x89HDF\r\n\x1a\n" + bytes(64)),
        ("binary_garbage", r"not UTF-8 text", bytes(range(128, 256)) * 4),
    ]:  # fmt: skip
        out.append((f"files.{name}", "not a case", expect, content, None))
    for name, output, expect in [
        ("the_case_itself", "outputs.the_case_itself.yaml", r"is a file this command reads"),
        ("a_folder", "tables", r"'.*tables' is a directory"),
        ("missing_folder", "no_such_folder/run.nc",
         r"output '.*no_such_folder/run\.nc': its folder '.*no_such_folder' does not exist"),
        ("a_table_it_reads", "tables/push.dat",
         r"output '.*push\.dat' is a file this command reads"),
        ("not_results", "tables/notes.nc",
         r"'.*notes\.nc' exists and is not a 'seacable simulation results' file"),
        ("not_a_results_name", "tables/notes.pdf",
         r"'.*notes\.pdf': the output is a NetCDF file, and '\.pdf' is not one of its names"),
        ("a_link", "tables/link.nc", r"output '.*link\.nc' is a link \(to 'push\.dat'\)"),
    ]:  # fmt: skip
        data = copy.deepcopy(BASE)
        _set(data, push, {"kind": "table", "file": "tables/push.dat"})
        out.append((f"outputs.{name}", "bad output paths", expect,
                    yaml.safe_dump(data, sort_keys=False), output))  # fmt: skip
    return out


TABLES = {  # the corpus's table files (tables/): bad ones, and two good ones the outputs use
    "nan.csv": b"time,force\n0,0\n1,nan\n",
    "huge.csv": b"time,force\n0,0\n1,1e300\n",
    "backwards.csv": b"time,force\n0,0\n2,1\n1,2\n",
    "latin1.csv": "# caf\xe9\n0,0\n1,1\n".encode("latin-1"),
    "bad_row.csv": b"time,force\n0,0\n1,ten\n",
    "push.dat": b"time,force\n0,0\n1,1000\n",
    "notes.pdf": b"%PDF-1.4 not results\n",
    "notes.nc": b"%PDF-1.4 not results\n",
}


def main() -> None:
    for old in HERE.glob("*.yaml"):
        old.unlink()
    tables = HERE / "tables"
    (tables / "folder.csv").mkdir(parents=True, exist_ok=True)
    (tables / "folder.csv" / ".keep").write_text("a table name that is a folder\n")
    for name, content in TABLES.items():
        (tables / name).write_bytes(content)
    link = tables / "link.nc"  # an output that links to a table: written through, replaced
    link.unlink(missing_ok=True)
    link.symlink_to("push.dat")
    expected = {}
    for name, kind, expect, content, output in cases():
        body = content.encode() if isinstance(content, str) else content
        (HERE / f"{name}.yaml").write_bytes(body)
        expected[f"{name}.yaml"] = {"kind": kind, "expect": expect}
        if output is not None:
            expected[f"{name}.yaml"]["output"] = output
    for name, kind, expect, args in corpus_commands.entries():
        assert name not in expected, name
        expected[name] = {"kind": kind, "expect": expect, "args": args}
    (HERE / "expected.yaml").write_text(yaml.safe_dump(expected, sort_keys=True, width=200))
    print(f"{len(expected)} bad cases written to {HERE}")


if __name__ == "__main__":
    main()
