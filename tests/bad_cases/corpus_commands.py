"""The corpus's entries that go through the commands (``make_corpus.py`` writes them with the
case files): every command's output paths, its options, and the side files it reads (tables
of states and of load cases, meshes, hydrodynamic databases, MoorDyn decks, results files).
Each is a command line (``args``, ``{here}`` the corpus's folder) that must exit 2 with one
line matching ``expect``, leaving every file of ``inputs/`` as it was. ``write_inputs`` writes
the good files the entries start from and the bad side files into ``inputs/`` of a folder
(the test's, each time: a results file of the version tested)."""

import copy
import re

import numpy as np
import yaml

IN = "{here}/inputs"
SYSTEM, TANDEM, RESULTS = f"{IN}/system.yaml", f"{IN}/tandem.yaml", f"{IN}/results.nc"
DECK, LEGACY, HULL, BOX = f"{IN}/deck.txt", f"{IN}/legacy.yaml", f"{IN}/hull.obj", f"{IN}/box.yaml"

# (command, its args before the output, the output option, the kind's suffix, the input file
# the command reads that an output must not replace)
WRITERS = [
    ("run", ["run", SYSTEM, "--no-progress"], "-o", ".nc", SYSTEM),
    ("statics", ["statics", SYSTEM], "-o", ".nc", SYSTEM),
    ("repeat", ["repeat", RESULTS, "--no-progress"], "-o", ".nc", RESULTS),
    ("sweep", ["sweep", SYSTEM, "--vary", "simulation.duration=1,2", "--dask", "none"], "-o",
     ".nc", SYSTEM),
    ("equilibria", ["equilibria", TANDEM], "-o", ".nc", TANDEM),
    ("continuation", ["continuation", TANDEM, "--parameter", "current.speed", "--from", "0.5",
                      "--to", "1"], "-o", ".nc", TANDEM),
    ("continuation_plot", ["continuation", TANDEM, "--parameter", "current.speed", "--from",
                           "0.5", "--to", "1"], "--plot", ".png", TANDEM),
    ("curves", ["curves", TANDEM, "--parameter", "current.speed", "--from", "0.5", "--to", "1",
                "--second", "wind.speed", "--second-from", "5", "--second-to", "6"], "-o", ".nc",
     TANDEM),
    ("orbit", ["orbit", TANDEM], "-o", ".nc", TANDEM),
    ("orbit_plot", ["orbit", TANDEM], "--plot", ".png", TANDEM),
    ("operability", ["operability", TANDEM, "--current-speed", "1", "--current-towards", "0",
                     "--wind-towards", "0", "--ratios", "10", "--dask", "none"], "-o", ".nc",
     TANDEM),
    ("operability_plot", ["operability", TANDEM, "--current-speed", "1", "--current-towards",
                          "0", "--wind-towards", "0", "--ratios", "10", "--dask", "none"],
     "--plot", ".png", TANDEM),
    ("compare", ["compare", TANDEM], "-o", ".nc", TANDEM),
    ("compare_plot", ["compare", TANDEM], "--plot", ".png", TANDEM),
    ("import_moordyn", ["import", "moordyn", DECK], "-o", ".yaml", DECK),
    ("upgrade", ["upgrade", LEGACY], "-o", ".yaml", LEGACY),
    ("hydrodb", ["hydrodb", HULL], "-o", ".nc", HULL),
    ("plot", ["plot", RESULTS], "-o", ".png", RESULTS),
    ("animate", ["animate", RESULTS, "--no-progress"], "-o", ".gif", RESULTS),
    ("export", ["export", RESULTS, "--vtk"], "-o", ".pvd", RESULTS),
    ("report", ["report", RESULTS], "-o", ".html", RESULTS),
]  # fmt: skip
WRONG_NAME = {".nc": ".txt", ".png": ".nc", ".yaml": ".csv", ".gif": ".mp4", ".pvd": ".vtu",
              ".html": ".pdf"}  # fmt: skip


def _outputs() -> list:
    """Each writing command with each kind of output it must refuse."""
    out = []
    for name, args, option, suffix, source in WRITERS:
        for variant, target, expect in [
            ("its_input", source, r"is a file this command reads"),
            ("a_folder", IN, r"is a directory"),
            ("missing_folder", f"{IN}/missing/out{suffix}", r"its folder '.*missing' does not "
                                                            r"exist"),
            ("a_link", f"{IN}/link{suffix}", r"is a link \(to 'push\.dat'\)"),
            ("wrong_name", f"{IN}/out{WRONG_NAME[suffix]}",
             re.escape(f"'{WRONG_NAME[suffix]}' is not one of its names")),
            ("not_of_its_kind", f"{IN}/notes{suffix}", r"exists and is not"),
        ]:  # fmt: skip
            if variant == "its_input" and option == "--plot":
                expect = r"--plot '.*' is a file this command reads"
            out.append((f"output.{name}.{variant}", "output paths", expect,
                        [*args, option, target]))  # fmt: skip
    for name, args, table in [
        ("run", ["run", SYSTEM, "--no-progress", "-o"], f"{IN}/push.dat"),
        ("statics", ["statics", SYSTEM, "-o"], f"{IN}/push.dat"),
        ("sweep", ["sweep", SYSTEM, "--vary", "simulation.duration=1,2", "--dask", "none", "-o"],
         f"{IN}/push.dat"),
        ("upgrade", ["upgrade", LEGACY, "-o"], f"{IN}/surge.yaml"),
        ("run_box_database", ["run", BOX, "--no-progress", "-o"], f"{IN}/box.nc"),
        ("run_box_mesh", ["run", BOX, "--no-progress", "-o"], f"{IN}/hull.obj"),
        ("run_other_results_kind", ["run", SYSTEM, "--no-progress", "-o"], f"{IN}/other.nc"),
        ("equilibria_over_results", ["equilibria", TANDEM, "-o"], RESULTS),
        ("report_over_case", ["report", RESULTS, "-o"], SYSTEM),
    ]:  # fmt: skip
        expect = {"run_other_results_kind": r"exists and is not a 'seacable simulation results'",
                  "equilibria_over_results": r"exists and is not a 'seacable equilibria' file",
                  "report_over_case": r"'\.yaml' is not one of its names"}.get(
            name, r"is a file this command reads|exists and is not")  # fmt: skip
        out.append((f"output.{name}.side_file", "output paths", expect, [*args, table]))
    return out


# (entry, args, what the message must match) of options given values no command takes
OP1 = ["operability", TANDEM, "--dask", "none", "--current-speed", "1"]  # a grid's map, here
OPTIONS = [
    ("modes_count_negative", ["modes", SYSTEM, "--count", "-3"], r"'--count'.*-3"),
    ("modes_count_zero", ["modes", SYSTEM, "--count", "0"], r"'--count'.*0"),
    ("modes_count_text", ["modes", SYSTEM, "--count", "many"], r"'--count'.*'many'"),
    ("modes_dense_too_large", ["modes", BOX, "--set", "lines.line.sections[0]={type: rope, "
     "length: 24.0, segments: 2000}"], r"modes: the .* rates .*GB.*fewer segments.*--yes"),
    ("plot_every_negative", ["plot", RESULTS, "--every", "-1", "-o", f"{IN}/x.png"],
     r"'--every'.*-1.*above 0"),
    ("plot_every_nan", ["plot", RESULTS, "--every", "nan", "-o", f"{IN}/x.png"],
     r"'--every'.*nan"),
    ("plot_every_zero", ["plot", RESULTS, "--every", "0", "-o", f"{IN}/x.png"], r"'--every'.*0"),
    ("animate_fps_zero", ["animate", RESULTS, "-o", f"{IN}/x.gif", "--fps", "0"], r"'--fps'.*0"),
    ("animate_fps_huge", ["animate", RESULTS, "-o", f"{IN}/x.gif", "--fps", "100000"],
     r"'--fps'.*100000"),
    ("animate_speed_negative", ["animate", RESULTS, "-o", f"{IN}/x.gif", "--speed", "-2"],
     r"'--speed'.*-2"),
    ("animate_speed_inf", ["animate", RESULTS, "-o", f"{IN}/x.gif", "--speed", "inf"],
     r"'--speed'.*inf"),
    ("animate_every_nan", ["animate", RESULTS, "-o", f"{IN}/x.gif", "--every", "nan"],
     r"'--every'.*nan"),
    ("animate_frames_zero", ["animate", RESULTS, "-o", f"{IN}/x.gif", "--max-frames", "0"],
     r"'--max-frames'.*0"),
    ("export_every_negative", ["export", RESULTS, "--vtk", "-o", f"{IN}/x.pvd", "--every",
                               "-5"], r"'--every'.*-5"),
    ("export_no_format", ["export", RESULTS, "-o", f"{IN}/x.pvd"], r"give the format, --vtk"),
    ("stats_storm_nan", ["stats", RESULTS, "--storm", "nan"], r"'--storm'.*nan"),
    ("stats_storm_negative", ["stats", RESULTS, "--storm", "-10"], r"'--storm'.*-10"),
    ("stats_from_nan", ["stats", RESULTS, "--from", "nan"], r"'--from'.*nan"),
    ("stats_from_negative", ["stats", RESULTS, "--from", "-1"], r"'--from'.*-1"),
    ("report_storm_zero", ["report", RESULTS, "-o", f"{IN}/x.html", "--storm", "0"],
     r"'--storm'.*0"),
    ("hydrodb_omega_nan", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--omega", "nan", "3", "30"],
     r"'--omega'.*nan"),
    ("hydrodb_omega_backwards", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--omega", "3", "1",
                                 "30"], r"--omega 3 1 30: give first < last"),
    ("hydrodb_omega_count", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--omega", "0.1", "3",
                             "1e12"], r"'--omega'.*1e12"),
    ("hydrodb_omega_negative", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--omega", "-1", "3",
                                "30"], r"'--omega'.*-1"),
    ("hydrodb_directions", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--directions", "0,nan"],
     r"'--directions'.*'0,nan'"),
    ("hydrodb_directions_text", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--directions", "north"],
     r"'--directions'.*'north'"),
    ("hydrodb_depth_negative", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--depth", "-50"],
     r"'--depth'.*-50"),
    ("hydrodb_rho_zero", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--rho", "0"], r"'--rho'.*0"),
    ("hydrodb_rho_nan", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--rho", "nan"], r"'--rho'.*nan"),
    ("hydrodb_centre_inf", ["hydrodb", HULL, "-o", f"{IN}/x.nc", "--rotation-center", "0",
                            "inf", "0"], r"'--rotation-center'.*inf"),
    ("equilibria_current_nan", ["equilibria", TANDEM, "--current", "nan", "0"],
     r"'--current'.*nan"),
    ("equilibria_current_negative", ["equilibria", TANDEM, "--current", "-1", "0"],
     r"'--current'.*-1"),
    ("equilibria_wind_inf", ["equilibria", TANDEM, "--wind", "10", "inf"], r"'--wind'.*inf"),
    ("equilibria_waves_negative", ["equilibria", TANDEM, "--waves", "-2", "0"],
     r"'--waves'.*-2"),
    ("equilibria_headings_zero", ["equilibria", TANDEM, "--headings", "0"],
     r"'--headings'.*0"),
    ("equilibria_headings_huge", ["equilibria", TANDEM, "--headings", "100000000"],
     r"'--headings'.*100000000"),
    ("continuation_from_nan", ["continuation", TANDEM, "--parameter", "current.speed",
                               "--from", "nan", "--to", "1"], r"'--from'.*nan"),
    ("continuation_to_inf", ["continuation", TANDEM, "--parameter", "current.speed", "--from",
                             "0.5", "--to", "inf"], r"'--to'.*inf"),
    ("continuation_parameter", ["continuation", TANDEM, "--parameter", "tide.height", "--from",
                                "0.5", "--to", "1"], r"tide\.height"),
    ("continuation_cycles", ["continuation", TANDEM, "--parameter", "current.speed", "--from",
                             "0.5", "--to", "1", "--cycles", "-1"], r"'--cycles'.*-1"),
    ("curves_second_nan", ["curves", TANDEM, "--parameter", "current.speed", "--from", "0.5",
                           "--to", "1", "--second", "wind.speed", "--second-from", "nan",
                           "--second-to", "6"], r"'--second-from'.*nan"),
    ("orbit_settle_negative", ["orbit", TANDEM, "--settle", "-100"], r"'--settle'.*-100"),
    ("orbit_value_nan", ["orbit", TANDEM, "--parameter", "current.speed", "--value", "nan"],
     r"'--value'.*nan"),
    ("operability_speed_nan", ["operability", TANDEM, "--current-speed", "nan", "--dask",
                               "none"], r"'--current-speed'.*nan"),
    ("operability_speed_negative", ["operability", TANDEM, "--current-speed", "-1", "--dask",
                                    "none"], r"'--current-speed'.*-1"),
    ("operability_speed_missing", ["operability", TANDEM, "--dask", "none"],
     r"--current-speed: missing"),
    ("operability_zero_step", [*OP1, "--current-towards", "0:360:0"],
     r"--current-towards '0:360:0': the step must be positive"),
    ("operability_inf_range", [*OP1, "--current-towards", "0:inf:10"],
     r"--current-towards '0:inf:10': give finite numbers"),
    ("operability_empty_list", [*OP1, "--wind-towards", ""],
     r"'--wind-towards'.*''"),
    ("operability_nan_angle", [*OP1, "--wind-towards", "0,nan"],
     r"'--wind-towards'.*'0,nan'"),
    ("operability_negative_ratio", [*OP1, "--ratios", "-10"],
     r"--ratios.*every value at least 0"),
    ("operability_huge_grid", [*OP1, "--current-towards", "0:360:0.01", "--wind-towards",
                               "0:360:0.01"], r"more than 1,000,000"),
    ("operability_clearance_nan", [*OP1, "--clearance", "nan"],
     r"'--clearance'.*nan"),
    ("operability_tension_negative", [*OP1, "--tension-limit", "hawser", "-5"],
     r"'--tension-limit'.*-5"),
    ("operability_tension_unknown", [*OP1, "--current-towards", "0", "--wind-towards", "0",
                                     "--ratios", "10", "--tension-limit", "rope", "1e6"],
     r"--tension-limit rope.*hawser"),
    ("operability_simulate_negative", [*OP1, "--simulate", "-60"],
     r"'--simulate'.*-60"),
    ("operability_control", [*OP1, "--control", "maybe"], r"'--control'.*'maybe'"),
    ("compare_duration_zero", ["compare", TANDEM, "--duration", "0"], r"'--duration'.*0"),
    ("compare_duration_nan", ["compare", TANDEM, "--duration", "nan"], r"'--duration'.*nan"),
    ("compare_tension_unknown", ["compare", TANDEM, "--tension-limit", "rope", "1e6"],
     r"--tension-limit rope.*hawser"),
    ("sweep_seeds_zero", ["sweep", SYSTEM, "--seeds", "0", "--dask", "none"],
     r"'--seeds'.*0"),
    ("sweep_storm_nan", ["sweep", SYSTEM, "--vary", "simulation.duration=1,2", "--storm", "nan",
                         "--dask", "none"], r"'--storm'.*nan"),
    ("sweep_vary_no_value", ["sweep", SYSTEM, "--vary", "simulation.duration", "--dask",
                             "none"], r"--vary 'simulation\.duration'"),
    ("sweep_vary_nowhere", ["sweep", SYSTEM, "--vary", "simulation.colour=1,2", "--dask",
                            "none"], r"simulation: unknown key 'colour'"),
    ("sweep_vary_inf_range", ["sweep", SYSTEM, "--vary", "simulation.duration=1:inf:1",
                              "--dask", "none"], r"give finite numbers"),
    ("sweep_dask_address", ["sweep", SYSTEM, "--vary", "simulation.duration=1,2", "--dask",
                            "nowhere://x", "-o", f"{IN}/x.nc"], r"--dask 'nowhere://x'"),
    ("compile_missing", ["compile", f"{IN}/missing.yaml"], r"missing\.yaml.*does not exist"),
    ("compile_not_a_case", ["compile", f"{IN}/push.dat"], r"a case must be a mapping"),
    ("set_no_equals", ["validate", SYSTEM, "--set", "simulation.duration"],
     r"--set 'simulation\.duration'"),
    ("set_nowhere", ["validate", SYSTEM, "--set", "simulation.colour=red"],
     r"simulation.*colour"),
    ("set_bad_value", ["validate", SYSTEM, "--set", "simulation.duration=-5"],
     r"simulation\.duration.*-5"),
    ("set_yaml_tag", ["validate", SYSTEM, "--set", "simulation.duration=!!float abc"],
     r"simulation\.duration"),
]  # fmt: skip


def entries() -> list:
    """(name, kind, expect, args) of every entry of this part of the corpus."""
    out = _outputs()
    out += [(f"option.{name}", "options", expect, args) for name, args, expect in OPTIONS]
    out += _side_files()
    return out


# ---- side files ---------------------------------------------------------------------------------
GOOD_STATES = ("current_speed,current_towards_deg,wind_speed,wind_towards_deg\n"
               "1.0,0,10,0\n1.0,0,10,30\n")  # fmt: skip
STATES = {  # bad tables of weather states (operability --states)
    "latin1": ("# caf\xe9\n" + GOOD_STATES).encode("latin-1"),
    "duplicate_column": b"current_speed,current_speed,current_towards_deg,wind_speed,"
                        b"wind_towards_deg\n1,1,0,10,0\n",
    "unknown_column": b"current_speed,current_towards_deg,wind_speed,wind_towards_deg,tide\n"
                      b"1,0,10,0,2\n",
    "missing_column": b"current_speed,current_towards_deg,wind_speed\n1,0,10\n",
    "nan_speed": GOOD_STATES.replace("1.0,0,10,30", "nan,0,10,30").encode(),
    "negative_speed": GOOD_STATES.replace("1.0,0,10,30", "-1.0,0,10,30").encode(),
    "text_cell": GOOD_STATES.replace("1.0,0,10,30", "fast,0,10,30").encode(),
    "short_row": GOOD_STATES.replace("1.0,0,10,30", "1.0,0").encode(),
    "long_row": GOOD_STATES.replace("1.0,0,10,30", "1.0,0,10,30,5").encode(),
    "header_only": GOOD_STATES.split("\n")[0].encode() + b"\n",
    "empty": b"",
    "huge_cell": GOOD_STATES.encode() + b"1," + b"9" * 200_000 + b",10,0\n",
    "nul_byte": GOOD_STATES.encode() + b"1,0\x00,10,0\n",
    "zero_probability": b"current_speed,current_towards_deg,wind_speed,wind_towards_deg,"
                        b"probability\n1,0,10,0,0\n1,0,10,30,0\n",
    "unclosed_quote": GOOD_STATES.encode() + b'"1,0,10,0\n' + b"2,0,10,0\n" * 3,
}  # fmt: skip
STATES_EXPECT = {
    "latin1": r"not UTF-8 text \(byte 0xe9", "duplicate_column": r"given twice \['current_speed'\]",
    "unknown_column": r"unknown \['tide'\]", "missing_column": r"missing \['wind_towards_deg'\]",
    "nan_speed": r"line 3: current_speed 'nan': give a finite number",
    "negative_speed": r"line 3: current_speed -1 is negative",
    "text_cell": r"line 3: current_speed 'fast' is not a number",
    "short_row": r"line 3: 2 cells for 4 columns", "long_row": r"line 3: 5 cells for 4 columns",
    "header_only": r"no states",
    "empty": r"missing \[",
    "huge_cell": r"line 4: current_towards_deg '9{20}\.\.\.9{8}' \(200,000 characters\)",
    "nul_byte": r"line 4", "zero_probability": r"the probabilities sum to 0",
    "unclosed_quote": r"line \d+",
    "zero_device": r"is not a regular file", "a_folder": r"is a directory",
    "missing": r"does not exist",
}  # fmt: skip
GOOD_LOADS = "environment.current.velocity,name,probability\n0.5,slack,0.5\n1.0,spring,0.5\n"
LOADS = {  # bad tables of load cases (sweep --load-cases)
    "latin1": ("# caf\xe9\n" + GOOD_LOADS).encode("latin-1"),
    "duplicate_column": GOOD_LOADS.replace("name,", "probability,", 1).encode(),
    "nowhere_key": GOOD_LOADS.replace("environment.current.velocity", "environment.tide")
                   .encode(),
    "negative_probability": GOOD_LOADS.replace("slack,0.5", "slack,-0.5").encode(),
    "ragged": GOOD_LOADS.replace("1.0,spring,0.5", "1.0,spring").encode(),
    "header_only": GOOD_LOADS.split("\n")[0].encode() + b"\n",
    "same_names": GOOD_LOADS.replace("spring", "slack").encode(),
    "huge_cell": GOOD_LOADS.encode() + b"0.2,big," + b"9" * 200_000 + b"\n",
    "yaml_tag": GOOD_LOADS.replace("0.5,slack", "!!float abc,slack").encode(),
    "not_csv_name": GOOD_LOADS.encode(),
}  # fmt: skip
LOADS_EXPECT = {
    "latin1": r"not UTF-8 text \(byte 0xe9", "duplicate_column": r"must name each key once",
    "nowhere_key": r"environment: unknown key 'tide'",
    "negative_probability": r"probability", "ragged": r"line 3: 2 cells for 3 columns",
    "header_only": r"no rows", "same_names": r"the names must differ", "huge_cell": r"line 4",
    "yaml_tag": r"abc", "not_csv_name": r"give a CSV table \(\.csv\)",
    "zero_device": r"is not a regular file", "missing": r"does not exist",
}  # fmt: skip


def _box_obj(scale: float = 1.0, drop: int = 0, reverse: bool = False) -> bytes:
    """A box 2 x 1.2 x 1 m about its centre as OBJ (12 triangles; the first ``drop`` left out:
    0 and 1 are the bottom's)."""
    corners = [(x, y, z) for x in (-1.0, 1.0) for y in (-0.6, 0.6) for z in (-0.5, 0.5)]
    quads = [(1, 3, 7, 5), (2, 6, 8, 4), (1, 5, 6, 2), (3, 4, 8, 7), (1, 2, 4, 3), (5, 7, 8, 6)]
    triangles = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))][drop:]
    if reverse:
        triangles = [t[::-1] for t in triangles]
    text = "".join(f"v {x * scale:g} {y * scale:g} {z * scale:g}\n" for x, y, z in corners)
    return (text + "".join(f"f {a} {b} {c}\n" for a, b, c in triangles)).encode()


BOX_OBJ = _box_obj()
MESHES = {  # bad hull meshes (a case's mesh, and seacable hydrodb's)
    "index_out_of_range.obj": BOX_OBJ + b"f 1 2 99\n",
    "index_zero.obj": BOX_OBJ + b"f 0 1 2\n",
    "index_text.obj": BOX_OBJ + b"f 1 two 3\n",
    "nan_vertex.obj": BOX_OBJ.replace(b"v -1", b"v nan", 1),
    "huge_vertex.obj": BOX_OBJ.replace(b"v -1", b"v -1e300", 1),
    "empty.obj": b"",
    "no_faces.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\n",
    "open_bottom.obj": _box_obj(drop=2),
    "tiny.obj": _box_obj(scale=1e-6),
    "garbage.obj": bytes(range(256)) * 4,
    "truncated.stl": b"seacable mesh".ljust(80) + (12).to_bytes(4, "little") + bytes(100),
    "text_number.stl": b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 x\nvertex 1 0 0\n"
                       b"vertex 0 1 0\nendloop\nendfacet\nendsolid a\n",
    "unknown.msh": BOX_OBJ,
    "truncated.gdf": b"a box\n1.0 9.81\n0 0\n12\n-1 -0.6 -0.5 1 -0.6 -0.5 1 0.6 -0.5\n",
    "text.gdf": b"a box\n1.0 9.81\n0 0\ntwelve\n",
    "non_manifold.obj": BOX_OBJ + b"f 1 3 7\n",
}  # fmt: skip
MESHES_EXPECT = {
    "index_out_of_range.obj": r"line 21: face \[1, 2, 99\] names a vertex the file has not",
    "index_zero.obj": r"line 21: face \[0, 1, 2\] names a vertex the file has not given",
    "index_text.obj": r"line 21: a face's vertices are whole numbers \(from 1\): '1 two 3'",
    "nan_vertex.obj": r"NaN or infinite coordinates",
    "huge_vertex.obj": r"the hull is 1e\+300 m across, not between 0\.01 and 10000 m",
    "empty.obj": r"holds no triangles",
    "no_faces.obj": r"holds no triangles", "open_bottom.obj": r"not closed below the waterline",
    "tiny.obj": r"the hull is 2e-06 m across, not between 0\.01 and 10000 m",
    "garbage.obj": r"not a readable OBJ|not UTF-8",
    "truncated.stl": r"not a readable STL", "text_number.stl": r"not a readable STL|'x'",
    "unknown.msh": r"format 'msh' is not known",
    "truncated.gdf": r"not a readable GDF file: 12 panels need 144 coordinates",
    "text.gdf": r"not a readable GDF",
    "non_manifold.obj": r"non_manifold\.obj.*: the edge .* more than two triangles",
    "zero_device.obj": r"not a regular file",
    "missing.obj": r"does not exist",
}  # fmt: skip


def _databases(box_nc) -> dict:
    """Bad hydrodynamic databases made from tests/data/box.nc (an xarray Dataset)."""
    import xarray as xr

    ds = box_nc
    out = {}

    def changed(name, change):
        copy_ = ds.copy(deep=True)
        changed_ = change(copy_)
        out[name] = changed_ if isinstance(changed_, xr.Dataset) else copy_

    changed("renamed_dimension.nc", lambda d: d.rename({"omega": "frequency"}))
    changed("negative_damping.nc", lambda d: d["radiation_damping"].__imul__(-1.0))
    changed("negative_frequencies.nc", lambda d: d.assign_coords(omega=-d["omega"].values))
    changed("one_frequency.nc", lambda d: d.isel(omega=[3]))
    changed(
        "nan_added_mass.nc", lambda d: d["added_mass"][2, 1, 1:2].__setitem__(slice(None), np.nan)
    )
    changed("negative_added_mass.nc", lambda d: d["added_mass"].__imul__(-1.0))
    changed("no_added_mass.nc", lambda d: d.drop_vars("added_mass"))
    changed(
        "repeated_frequency.nc",
        lambda d: d.assign_coords(omega=np.r_[d["omega"].values[:1], d["omega"].values[:-1]]),
    )
    changed(
        "text_values.nc",
        lambda d: d.assign(added_mass=(d["added_mass"].dims, np.full(d["added_mass"].shape, "x"))),
    )
    assert all(isinstance(v, xr.Dataset) for v in out.values())
    return out


def _wamit_negative(text: str) -> str:
    """box.1 with every damping coefficient's sign turned (WAMIT's fifth column)."""
    rows = []
    for line in text.splitlines():
        words = line.split()
        if len(words) == 5:
            words[4] = str(-float(words[4]))
        rows.append("\t".join(words))
    return "\n".join(rows) + "\n"


OTHER_DATABASES = {  # (WAMIT's and HDB files): name -> (how it is made, what the message says)
    "negative.1": (lambda data: _wamit_negative((data / "box.1").read_text()),
                   r"radiation damping of \w+ is negative"),
    "truncated.1": (lambda data: (data / "box.1").read_text()[:1500],
                    r"hydrodynamic database|WAMIT|periods"),
    "garbage.1": (lambda data: "not a wamit file\n" * 3, r"hydrodynamic database|WAMIT"),
    "garbage.hdb": (lambda data: "[SOFT] nothing\n[PERIODS_NUMBER] x\n",
                    r"hydrodynamic database|HDB|PERIODS"),
    "truncated.hdb": (lambda data: (data / "box.hdb").read_text()[:600],
                      r"hydrodynamic database|HDB"),
}  # fmt: skip
WAMIT_SIDES = (".3", ".3sc", ".3fk", ".hst")

DATABASES_EXPECT = {
    "renamed_dimension.nc": r"omega|frequency", "negative_damping.nc": r"damping.*negative",
    "negative_frequencies.nc": r"frequenc.*(negative|positive)",
    "one_frequency.nc": r"one frequency|a single frequency|frequencies",
    "nan_added_mass.nc": r"NaN|not finite", "negative_added_mass.nc": r"added mass.*(negative|"
                                                                      r"positive)",
    "no_added_mass.nc": r"added_mass", "repeated_frequency.nc": r"frequenc.*increas",
    "text_values.nc": r"added_mass|numbers", "external.nc": r"is stored in",
    "not_netcdf.nc": r"not readable NetCDF", "zero_device.nc": r"not a regular file",
    "missing.nc": r"does not exist",
}  # fmt: skip


def decks(good: str) -> dict:
    """Bad MoorDyn decks, from a good v2 deck (``good``: its text)."""
    line = "1    chain     1        4        650.0     40       -"
    return {
        "unknown_type.txt": good.replace(line, line.replace("chain ", "rope  ")),
        "unknown_point.txt": good.replace(line, line.replace("1        4", "9        4")),
        "nan_length.txt": good.replace(line, line.replace("650.0", "nan  ")),
        "negative_segments.txt": good.replace(line, line.replace("  40 ", " -40 ")),
        "text_diameter.txt": good.replace("chain     0.137", "chain     big  "),
        "missing_column.txt": good.replace(line, "1    chain     1        4"),
        "unknown_attachment.txt": good.replace("1    Fixed ", "1    Floating"),
        "huge_depth.txt": good.replace("200.0    WtrDpth", "1e300    WtrDpth"),
        "no_sections.txt": "just some text\nwith no sections\n",
        "binary.txt": bytes(range(256)).decode("latin-1"),
        "empty.txt": "",
    }


DECKS_EXPECT = {
"unknown_type.txt": r"'rope'",
    "unknown_point.txt": r"9", "nan_length.txt": r"nan", "negative_segments.txt": r"-40",
    "text_diameter.txt": r"'big'|big", "missing_column.txt": r"LINES.*(column|row)",
    "unknown_attachment.txt": r"Floating", "huge_depth.txt": r"1e\+300|beyond",
    "no_sections.txt": r"section|MoorDyn|a case must be a mapping",
    "binary.txt": r"section|MoorDyn|not valid YAML",
    "empty.txt": r"section|MoorDyn|empty|a case must be a mapping",
    "zero_device.txt": r"not a regular file",
    "a_folder": r"is a directory",
}  # fmt: skip

# hostile or broken YAML as the case file (validate)
YAML_CASES = {
    "float_tag.yaml": "simulation: !!float abc\n",
    "bool_tag.yaml": "simulation: {duration: !!bool maybe}\n",
    "timestamp_tag.yaml": "simulation: {duration: !!timestamp 2026-13-45}\n",
    "int_tag.yaml": "simulation: {duration: !!int 1.5x}\n",
    "long_integer.yaml": "simulation: {duration: " + "9" * 5000 + "}\n",
    "binary_tag.yaml": "name: !!binary '@@@'\n",
    "set_tag.yaml": "bodies: !!set {a, b}\n",
    "unknown_tag.yaml": "bodies: !custom thing\n",
    "merge_loop.yaml": "a: &a {<<: *a}\n",
    "undefined_alias.yaml": "name: *nothing\n",
    "control_character.yaml": "name: \x07bell\n",
    "document_separator.yaml": "name: a\n---\nname: b\n",
    "nul_byte.yaml": "name: a\x00b\n",
    "huge_float.yaml": "simulation: {duration: 1e999}\n",
    "key_not_text.yaml": "? [1, 2]\n: 3\n",
}
YAML_EXPECT = {name: r"not valid YAML|case file|a case must be|key|required|simulation"
               for name in YAML_CASES}  # fmt: skip
YAML_EXPECT.update({
    "float_tag.yaml": r"!!float|abc", "bool_tag.yaml": r"!!bool|maybe",
    "timestamp_tag.yaml": r"!!timestamp|2026-13-45|timestamp",
    "int_tag.yaml": r"!!int|1\.5x", "long_integer.yaml": r"simulation\.duration|digits",
    "merge_loop.yaml": r"required key is missing", "undefined_alias.yaml": r"alias",
    "document_separator.yaml": r"more than one document|document",
    "huge_float.yaml": r"simulation\.duration.*inf",
})  # fmt: skip

# (entry, --set of the moored box's case, what the message must match): matrices and settings
# no physics allows, and runs too costly to start
BOX_SETTINGS = [
    ("inertia_negative", "bodies.box.inertia=[-200, 450, 500]", r"inertia.*-200"),
    ("inertia_not_symmetric", "bodies.box.inertia=[[200, 50, 0], [0, 450, 0], [0, 0, 500]]",
     r"inertia.*symmetric"),
    ("inertia_not_positive", "bodies.box.inertia=[[200, 400, 0], [400, 450, 0], [0, 0, 500]]",
     r"inertia.*(positive|negative)"),
    ("added_mass_negative", "bodies.box.added_mass=[-1000, -1000, -1000, -100, -100, -100]",
     r"added_mass.*(negative|positive)"),
    ("added_mass_indefinite", "bodies.box.added_mass=[[1000, 0, 0, 0, 5000, 0], "
     "[0, 1000, 0, 0, 0, 0], [0, 0, 1000, 0, 0, 0], [0, 0, 0, 100, 0, 0], "
     "[5000, 0, 0, 0, 100, 0], [0, 0, 0, 0, 0, 100]]", r"added_mass.*(negative|positive)"),
    ("mass_zero", "bodies.box.mass=0", r"mass"),
    ("memory_shorter_than_step", "bodies.box.external forces[2].memory=0.05",
     r"memory.*(step|0\.1)"),
    ("rtol_one", "simulation.rtol=1", r"rtol.*1"),
    ("tiny_max_step", "simulation.max_step=1e-9", r"about 1e\+09 steps.*--yes"),
    ("rk4_tiny_step", "simulation={integrator: rk4, time_step: 1.0e-6, duration: 600.0, "
     "output_interval: 0.5}", r"about 6e\+08 steps of .* states.*--yes"),
    ("implicit_tiny_step", "simulation={integrator: generalized_alpha, time_step: 1.0e-6, "
     "duration: 600.0, output_interval: 0.5}", r"about 6e\+08 steps.*allow_long_run"),
    ("dopri5_fine_segments", "lines.line.sections[0]={type: rope, length: 24.0, "
     "segments: 100000}", r"steps of .* states.*axial motion of line 'line'.*fewer, longer"),
]  # fmt: skip
# crafted or broken results files given to the commands that read them
RESULTS_ATTACKS = {
    "external.nc": r"'time' is stored in",
    "outside_table.nc": r"reads '/etc/hostname', which the file does not carry",
    "no_case.nc": r"no 'case' attribute",
    "nan_times.nc": r"time|NaN",
    "not_hdf5.nc": r"not_hdf5\.nc.*not a readable NetCDF/HDF5 file",
    "truncated.nc": r"truncated\.nc.*not a readable NetCDF/HDF5 file",
    "database.nc": r"not seacable's results( or a sweep's summary)? \(its title|no 'case' attr",
}
RESULT_READERS = [
    ("plot", lambda f: ["plot", f, "-o", f"{IN}/x.png"]),
    ("stats", lambda f: ["stats", f]),
    ("report", lambda f: ["report", f, "-o", f"{IN}/x.html"]),
    ("export", lambda f: ["export", f, "--vtk", "-o", f"{IN}/x.pvd"]),
    ("repeat", lambda f: ["repeat", f, "-o", f"{IN}/x.nc", "--no-progress"]),
    ("animate", lambda f: ["animate", f, "-o", f"{IN}/x.gif", "--no-progress"]),
]


def _side_files() -> list:
    out = []
    states_cases = [*STATES, "zero_device", "a_folder", "missing"]
    for name in states_cases:
        path = {"a_folder": IN, "missing": f"{IN}/states/missing.csv"}.get(
            name, f"{IN}/states/{name}.csv")  # fmt: skip
        out.append((f"states.{name}", "tables of states", STATES_EXPECT[name],
                    ["operability", TANDEM, "--states", path, "--dask", "none"]))  # fmt: skip
    for name in [*LOADS, "zero_device", "missing"]:
        suffix = ".txt" if name == "not_csv_name" else ".csv"
        out.append((f"load_cases.{name}", "tables of load cases", LOADS_EXPECT[name],
                    ["sweep", SYSTEM, "--load-cases", f"{IN}/loads/{name}{suffix}", "--dask",
                     "none", "-o", f"{IN}/x.nc"]))  # fmt: skip
    for name in [*MESHES, "zero_device.obj", "missing.obj"]:
        out.append(
            (
                f"mesh.{name}",
                "meshes",
                MESHES_EXPECT[name],
                ["validate", BOX, "--set", f"bodies.box.mesh.file=meshes/{name}"],
            )
        )
        out.append(
            (
                f"hydrodb_mesh.{name}",
                "meshes",
                MESHES_EXPECT[name],
                ["hydrodb", f"{IN}/meshes/{name}", "-o", f"{IN}/x.nc"],
            )
        )
    for name in DATABASES_EXPECT:
        out.append(
            (
                f"database.{name}",
                "databases",
                DATABASES_EXPECT[name],
                ["validate", BOX, "--set", f"bodies.box.hydrodynamics.file=databases/{name}"],
            )
        )
    for name, (_, expect) in OTHER_DATABASES.items():
        out.append(
            (
                f"database.{name}",
                "databases",
                expect,
                ["validate", BOX, "--set", f"bodies.box.hydrodynamics.file=databases/{name}"],
            )
        )
    for name in DECKS_EXPECT:
        path = IN if name == "a_folder" else f"{IN}/decks/{name}"
        out.append(
            (
                f"deck.{name}",
                "MoorDyn decks",
                DECKS_EXPECT[name],
                ["import", "moordyn", path, "-o", f"{IN}/x.yaml"],
            )
        )
        out.append((f"deck_run.{name}", "MoorDyn decks", DECKS_EXPECT[name], ["validate", path]))
    for name in YAML_CASES:
        out.append(
            (
                f"yaml_case.{name}",
                "hostile or broken YAML",
                YAML_EXPECT[name],
                ["validate", f"{IN}/yaml/{name}"],
            )
        )
    for name, setting, expect in BOX_SETTINGS:
        out.append(
            (f"physics.{name}", "physical sense", expect, ["validate", BOX, "--set", setting])
        )
    for name, expect in RESULTS_ATTACKS.items():
        for command, args in RESULT_READERS:
            if command != "repeat" and name == "outside_table.nc":
                continue  # a case's files matter to repeat only
            if command in ("repeat",) and name in ("nan_times.nc",):
                continue  # repeat reads the case, not the rows
            if command != "repeat" and name == "no_case.nc":
                continue  # the rows are all the others read
            out.append(
                (f"results.{command}.{name}", "results files", expect, args(f"{IN}/results/{name}"))
            )
    return out


NOTES = {".nc": b"my notes\n", ".png": b"my notes\n", ".yaml": b"just: notes\n",
         ".html": b"<html><body>mine</body></html>\n", ".gif": b"my notes\n",
         ".pvd": b"my notes\n"}  # fmt: skip


def _system(base: dict, push: list) -> str:
    data = copy.deepcopy(base)
    where = data
    for key in push[:-1]:
        where = where[key]
    where[push[-1]] = {"kind": "table", "file": "push.dat"}
    data["simulation"].update(duration=1.0, output_interval=0.5)
    return yaml.safe_dump(data, sort_keys=False)


BOX_CASE = """name: a moored box
environment: {water_density: 1025.0, water_depth: 20.0, seabed: {stiffness: 3.0e4}}
bodies:
  - {name: anchor, type: fixed, position: [10.0, 0.0, -20.0]}
  - name: box
    type: rigid
    position: [0.0, 0.0, 0.0]
    mass: 1230.0
    centre_of_gravity: [0.0, 0.0, -0.1]
    inertia: [200.0, 450.0, 500.0]
    mesh: {file: hull.obj}
    hydrodynamics: {file: box.nc}
    points: {fairlead: [1.0, 0.0, -0.5]}
    external forces:
      - {model: gravity}
      - {model: non-linear hydrostatic, free_surface: still}
      - {model: radiation damping, memory: 5.0, memory_step: 0.1}
line_types:
  - {name: rope, diameter: 0.02, mass_per_length: 0.5, axial_stiffness: 1.0e6}
lines:
  - {name: line, model: lumped_mass, from: anchor, to: box.fairlead,
     sections: [{type: rope, length: 24.0, segments: 8}]}
simulation: {duration: 1.0, output_interval: 0.5, integrator: dopri5}
"""


def write_inputs(here, base: dict, push: list) -> None:
    """The good input files of this part of the corpus and its bad side files, in
    ``here/inputs`` (replaced whole); ``base`` the case data the system is made from, ``push``
    where it takes a table."""
    import shutil
    from pathlib import Path

    import h5py
    import xarray as xr

    import seacable

    repo = Path(__file__).resolve().parent.parent.parent
    folder = Path(here) / "inputs"
    shutil.rmtree(folder, ignore_errors=True)
    for sub in ("states", "loads", "meshes", "databases", "decks", "yaml", "results"):
        (folder / sub).mkdir(parents=True)

    def write(name: str, content) -> None:
        path = folder / name
        path.write_bytes(content.encode() if isinstance(content, str) else content)

    def link(name: str, target: str) -> None:
        (folder / name).symlink_to(target)

    write("system.yaml", _system(base, push))
    write("push.dat", "time,force\n0,0\n1,1000\n")
    write("tandem.yaml", (repo / "examples/tandem_offloading_fpso_shuttle.yaml").read_bytes())
    legacy = (repo / "tests/legacy_cases/crane_tip_lowering_imposed_motion.yaml").read_text()
    write("legacy.yaml", legacy.replace("data/vessel_surge.csv", "surge.yaml"))
    write("surge.yaml", (repo / "tests/legacy_cases/data/vessel_surge.csv").read_bytes())
    good_deck = (repo / "tests/data/moordyn_v2_spread.txt").read_text()
    write("deck.txt", good_deck)
    write("hull.obj", BOX_OBJ)
    write("box.yaml", BOX_CASE)
    shutil.copy(repo / "tests/data/box.nc", folder / "box.nc")
    for suffix, content in NOTES.items():
        write(f"notes{suffix}", content)
        link(f"link{suffix}", "push.dat")
    with h5py.File(folder / "other.nc", "w") as f:
        f.attrs["title"] = "someone else's data"
        f["values"] = np.arange(3.0)
    for name, content in STATES.items():
        write(f"states/{name}.csv", content)
    link("states/zero_device.csv", "/dev/zero")
    for name, content in LOADS.items():
        write(f"loads/{name}{'.txt' if name == 'not_csv_name' else '.csv'}", content)
    link("loads/zero_device.csv", "/dev/zero")
    for name, content in MESHES.items():
        write(f"meshes/{name}", content)
    link("meshes/zero_device.obj", "/dev/zero")
    for name, ds in _databases(xr.open_dataset(folder / "box.nc").load()).items():
        ds.to_netcdf(folder / "databases" / name, engine="h5netcdf")
    write("secret.bin", bytes(800))
    with h5py.File(folder / "databases/external.nc", "w") as f:
        f.create_dataset("added_mass", shape=(100,), dtype="f8",
                         external=[("../secret.bin", 0, 800)])  # fmt: skip
    write("databases/not_netcdf.nc", b"not a database\n")
    data = repo / "tests/data"
    for name, (make, _) in OTHER_DATABASES.items():
        write(f"databases/{name}", make(data))
        if name.endswith(".1"):
            for side in WAMIT_SIDES:
                shutil.copy(data / f"box{side}", folder / "databases" / f"{name[:-2]}{side}")
    link("databases/zero_device.nc", "/dev/zero")
    for name, content in decks(good_deck).items():
        write(f"decks/{name}", content)
    link("decks/zero_device.txt", "/dev/zero")
    for name, content in YAML_CASES.items():
        write(f"yaml/{name}", content)
    seacable.simulate(seacable.load_case(folder / "system.yaml"), output=folder / "results.nc",
                      progress=False)  # fmt: skip
    _results_attacks(folder)


def _results_attacks(folder) -> None:
    """Crafted and broken results files (``RESULTS_ATTACKS``) from ``folder/results.nc``."""
    import shutil

    import h5py

    good = folder / "results.nc"
    with h5py.File(folder / "results/external.nc", "w") as f:
        f.attrs["title"] = "seacable simulation results"
        f.create_dataset("time", shape=(100,), dtype="f8", external=[("../secret.bin", 0, 800)])
    for name in ("outside_table.nc", "no_case.nc", "nan_times.nc"):
        shutil.copy(good, folder / "results" / name)
    with h5py.File(folder / "results/outside_table.nc", "r+") as f:
        f.attrs["case"] = str(f.attrs["case"]).replace("file: push.dat", "file: /etc/hostname")
    with h5py.File(folder / "results/no_case.nc", "r+") as f:
        del f.attrs["case"]
    with h5py.File(folder / "results/nan_times.nc", "r+") as f:
        f["time"][1] = np.nan
    (folder / "results/not_hdf5.nc").write_bytes(b"not results\n")
    (folder / "results/truncated.nc").write_bytes(good.read_bytes()[:2000])
    shutil.copy(folder / "box.nc", folder / "results/database.nc")
