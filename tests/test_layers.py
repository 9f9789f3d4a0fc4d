"""The layers of docs/architecture.md: imports point one way, top to bottom."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).parent.parent / "src" / "seacable"

# module (or subpackage) -> seacable modules it may import
LAYER = {
    "cli": 14, "cli_sweep": 13.5, "cli_ships": 13, "cli_types": 12.9,
    "sweep": 12.5, "sweep_summary": 12.4, "cluster": 10.5,
    "report": 12.8, "export": 12.8, "fatigue": 11.5,
    "viz": 12, "ahead": 12, "coupling": 12,
    "__init__": 12,
    "simulation": 11, "run_report": 10.9, "analysis": 11, "stability": 11, "stats": 11,
    "natural_periods": 10.8,
    "case.loader": 10, "results": 10, "case.reference": 9.5,
    "numerics": 8,
    "system": 7,
    "lines": 6, "forces": 6,
    "bodies": 5,
    "packing": 4,
    "case.units": 4,
    "case.system": 3, "case.bodies": 2.5, "case.schema": 3, "timefunctions": 3, "meshes": 3,
    "seastate": 3,
    "hydrodb": 3, "realization": 3, "bem": 4,
    "case.legacy": 10,
    "case.legacy_sections": 9, "case.moordyn": 9, "case.moordyn_tables": 8.5,
    "case.forces": 2, "case.environment": 2, "case.sweep": 2, "case.fatigue": 2,
    "case.ship_forces": 1.5, "case.document": 1.5,
    "case.base": 1, "hydrodb_formats": 1,
    "kernels": 0, "errors": 0, "files": 0.5,
}  # fmt: skip
SUBPACKAGES_BY_MODULE = {"case"}  # units inside these are their modules
ALLOWED_UP = {("results", "__init__")}  # results reads the version number only


def _unit(path: Path) -> str:
    rel = path.relative_to(PACKAGE)
    if len(rel.parts) == 1:
        return rel.stem
    if rel.parts[0] in SUBPACKAGES_BY_MODULE:
        return f"{rel.parts[0]}.{rel.stem}"
    return rel.parts[0]


def _target(dotted: str) -> str | None:
    """The layer unit of an imported dotted name (None when it is not ours)."""
    parts = dotted.split(".")
    if parts[0] != "seacable":
        return None
    if len(parts) == 1:
        return "__init__"
    if parts[1] in SUBPACKAGES_BY_MODULE and len(parts) > 2:
        return f"{parts[1]}.{parts[2]}"
    if parts[1] not in LAYER and parts[1] not in SUBPACKAGES_BY_MODULE:
        return "__init__"  # a name re-exported by the package
    return parts[1]


def _imports(path: Path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            yield from (f"{node.module}.{alias.name}" for alias in node.names)


def test_imports_follow_layers():
    problems = []
    for path in PACKAGE.rglob("*.py"):
        unit = _unit(path)
        for name in _imports(path):
            target = _target(name)
            if target is None:
                continue
            if target == unit or (unit, target) in ALLOWED_UP:
                continue
            if LAYER[target] > LAYER[unit] or (LAYER[target] == LAYER[unit] and target != "errors"):
                problems.append(f"{path.relative_to(PACKAGE)} imports {name}")
    assert not problems, "imports against the layers:\n" + "\n".join(problems)


def test_kernels_import_nothing_of_ours_but_kernels():
    for path in (PACKAGE / "kernels").glob("*.py"):
        for name in _imports(path):
            if name.startswith("seacable"):
                assert name.startswith("seacable.kernels"), f"{path.name} imports {name}"


def test_no_import_inside_functions_except_lazy_optional():
    lazy_ok = {"matplotlib", "matplotlib.pyplot", "tqdm", "seacable", "matplotlib.animation"}
    lazy_ok |= {"sksundae.cvode"}  # SUNDIALS, loaded when a case asks for integrator: cvode
    lazy_ok |= {"PIL"}  # Pillow, loaded when an animation is written
    lazy_ok |= {"capytaine"}  # the [bem] extra, loaded when a database is computed
    lazy_ok |= {"distributed"}  # the [dask] extra, loaded when a map runs on Dask
    lazy_ok |= {"plotly.offline"}  # the [report] extra, loaded when a report is written
    # the operability map's picture: its cells and its legend's marks
    lazy_ok |= {"matplotlib.colors", "matplotlib.patches", "matplotlib.lines"}
    # SciPy's slow imports, loaded where used (docs/architecture.md, "Compile time"): a run with
    # rk4, dopri5 or the implicit schemes needs none of them
    lazy_ok |= {"scipy", "scipy.integrate", "scipy.interpolate", "scipy.optimize"}
    lazy_ok |= {"scipy.spatial", "scipy.spatial.transform", "scipy.linalg", "scipy.stats"}
    lazy_ok |= {"scipy.signal"}  # Welch's spectra (seacable.stats)
    for path in PACKAGE.rglob("*.py"):
        tree = ast.parse(path.read_text())
        for func in ast.walk(tree):
            if isinstance(func, ast.FunctionDef):
                for node in ast.walk(func):
                    if isinstance(node, ast.Import | ast.ImportFrom):
                        if isinstance(node, ast.Import):
                            names = [a.name for a in node.names]
                        else:
                            names = [node.module]
                        assert set(names) <= lazy_ok, f"{path.name}:{func.name} imports {names}"


def test_a_run_imports_no_analysis():
    """``seacable.simulate`` and ``load_case`` import neither the analyses nor SciPy's optimisers
    (seacable's public names are imported on first use: every command's start pays for what it
    uses only)."""
    import subprocess
    import sys

    heavy = "('seacable.analysis', 'seacable.stability.api', 'seacable.stability.plane', " \
        "'scipy.optimize', 'seacable.viz')"  # fmt: skip
    code = ("import sys, seacable; seacable.simulate; seacable.load_case; "
            f"print(sorted(m for m in {heavy} if m in sys.modules))")  # fmt: skip
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]", out.stdout
    import seacable

    assert callable(seacable.statics) and callable(seacable.equilibria)  # still there, lazily
    assert "continuation" in dir(seacable)
