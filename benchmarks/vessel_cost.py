"""What a vessel costs: the moored barge of examples/moored_barge_irregular_sea.yaml (a box
barge of 1,568 triangles, radiation memory over 25 s, database excitation of 180 wave
components, three chains of 40 segments) and the vessel alone with the document's non-linear
models on a finer hull (exact clipped hydrostatics and Froude-Krylov on 2,000-odd triangles,
radiation memory).

1. The cost of one right-hand-side evaluation, split by what it evaluates: each case is built
   again without one of its parts (the hull mesh models, the radiation memory, the wave
   excitation, the lines), and the part's share is the time it takes away. A compiled loop
   evaluates ``system.kernel.evaluate`` ``--count`` times at the start state; each variant keeps its
   fastest of ``--repeat`` rounds (thread CPU time).
2. How the cost grows: with the hull's triangles, the kernel's length (memory / memory_step)
   and the lines' segments.
3. The real-time factor (simulated seconds per second of CPU) of ``--duration`` seconds of each
   case beyond its setup (the CPU time of a 2 s run: reading the database and the mesh, the
   statics), with the integrators its users would choose: dopri5 at rtol 1e-6 and
   generalized-alpha at 0.025 to 0.1 s (implicit, at steps of the size implicit codes take
   for moored vessels; Newton to 1e-9 of a segment, the default, and 1e-7, the example's),
   each with its fairlead-tension and heave errors against dopri5 at rtol 1e-9.
4. Issue 43's FPSO (``--fpso-only``; also at the end of part 3): a box hull of 310 m x 58 m x
   32 m at 20.5 m draught in 1,296 triangles in the barge's sea (180 components, 100 m of
   water), with gravity, exact clipped hydrostatics and Froude-Krylov on the mesh, linear
   heave, roll and pitch damping for the radiation it has no database for, and a spread
   mooring's stiffness: its real-time factor with dopri5 at rtol 1e-6, and that of the same
   case without the Froude-Krylov force, measured in the same run (their ratio is what the
   force costs, whatever the machine's load); then the same with the radiation memory and
   diffraction of the barge's database (a cost, not a model of this hull).
5. Issue 43's case as filed (``--fpso-only``): a moored FPSO of 1,296 triangles, 1,200 s
   "with a database" against Froude-Krylov on the mesh. Its file was not kept: here, the
   moored barge example with part 4's hull, mass and inertia, the three chains from the
   FPSO's ends (the example's lines moved with their fairleads), the barge database's
   radiation memory and diffraction (a cost, not a model of this hull), on the example's
   integrator (generalized-alpha, 0.05 s, Newton to 1e-7): the excitation from the mesh
   (clipped hydrostatics at the waves, Froude-Krylov) or from the database.

Run: python benchmarks/vessel_cost.py [--count N] [--repeat R] [--duration S] [--fpso-only]
"""

import argparse
import copy
import logging
import os
import time
from pathlib import Path

import numpy as np
import yaml
from numba import njit

import seacable
from seacable import meshes
from seacable.errors import SimulationDiverged
from seacable.system import kernel
from seacable.system import model as system_model

HERE = Path(__file__).resolve().parent
EXAMPLE = HERE.parent / "examples" / "moored_barge_irregular_sea.yaml"
MESH_MODELS = ("non-linear hydrostatic", "non-linear Froude-Krylov")


@njit
def _loop(t, y, p, w, ydot, count):
    status = 0
    for i in range(count):  # each at its own time: a mesh is placed again (kernels.hull.place)
        status |= kernel.evaluate(t + 1e-9 * i, y, p, w, ydot)
    return status


def _raw(path: Path = EXAMPLE) -> dict:
    raw = yaml.safe_load(path.read_text())
    for body in raw["bodies"]:  # absolute paths: the variants are loaded from a dict
        for key in ("mesh", "hydrodynamics"):
            if key in body:
                body[key]["file"] = str(path.parent / body[key]["file"])
    return raw


def _barge(raw: dict) -> dict:
    return next(b for b in raw["bodies"] if b["name"] == "barge")


def _without(raw: dict, part: str) -> dict:
    """The case without ``part``: mesh, radiation, excitation, lines or nothing, started as
    given (the same nodes in each: a static start would move them by the part's loads)."""
    raw = copy.deepcopy(raw)
    barge = _barge(raw)
    forces = barge["external forces"]
    if part == "mesh":
        barge["external forces"] = [f for f in forces if f["model"] not in MESH_MODELS]
        barge["volume"] = 12960.0  # a stand-in for the buoyancy the mesh gave
        barge["centre_of_buoyancy"] = [0.0, 0.0, -3.0]
        barge["external forces"].append({"model": "buoyancy"})
    elif part == "radiation":
        barge["external forces"] = [f for f in forces if f["model"] != "radiation damping"]
    elif part == "excitation":
        barge["external forces"] = [f for f in forces if f["model"] != "diffraction"]
        barge["external forces"] = [
            f for f in barge["external forces"] if f["model"] != "non-linear Froude-Krylov"
        ]
    elif part == "lines":
        raw["lines"] = []
        raw["line_types"] = []
        raw["bodies"] = [b for b in raw["bodies"] if b["type"] != "fixed"]
        barge["external forces"].append(
            {"model": "linear_stiffness", "diagonal": [3e5, 3e5, 0, 0, 0, 1e8]}
        )
    raw["start"] = "as_given"
    return raw


def _alone(raw: dict, panel: float, tmp: Path) -> dict:
    """The vessel alone with the document's non-linear models on a hull of ``panel`` [m]."""
    raw = _without(raw, "lines")
    hull = tmp / f"barge_{panel:g}.stl"
    if not hull.exists():
        meshes.write_stl(meshes.barge(90.0, 24.0, 12.0, panel), hull)
    barge = _barge(raw)
    barge["mesh"]["file"] = str(hull)
    barge["external forces"] = [
        {"model": "gravity"}, {"model": "non-linear hydrostatic"},
        {"model": "non-linear Froude-Krylov"}, {"model": "diffraction"},
        {"model": "radiation damping", "memory": 25.0, "memory_step": 0.1},
        {"model": "quadratic_damping", "diagonal": [1e5, 4e5, 0, 0, 0, 2e10]},
        {"model": "linear_stiffness", "diagonal": [3e5, 3e5, 0, 0, 0, 1e8]},
    ]  # fmt: skip
    return raw


def _fpso(raw: dict, tmp: Path, froude_krylov: bool = True, memory: bool = False) -> dict:
    """Issue 43's FPSO (part 4 of the module docstring), with or without Froude-Krylov, and
    with the barge's database's radiation memory and diffraction (``memory``) in place of the
    linear heave, roll and pitch damping."""
    raw = _without(raw, "lines")
    hull = tmp / "fpso_1296.stl"
    if not hull.exists():
        meshes.write_stl(meshes.barge(310.0, 58.0, 32.0, 10.5), hull)  # 30 x 6 x 4 panels
    fpso = _barge(raw)
    del fpso["points"]
    if not memory:
        del fpso["hydrodynamics"]
    mass = 1025.0 * 310.0 * 58.0 * 20.5  # kg: floating at 20.5 m
    fpso.update(position=[0.0, 0.0, 16.0 - 20.5], mass=mass, mesh={"file": str(hull)},
                inertia=[mass * 20.0**2, mass * 78.0**2, mass * 78.0**2])  # fmt: skip
    radiation = (
        [
            {"model": "radiation damping", "memory": 25.0, "memory_step": 0.1},
            {"model": "diffraction"},
        ]
        if memory
        else [{"model": "linear_damping", "diagonal": [0, 0, 5e7, 0, 7e9, 8e12]}]
    )
    fpso["external forces"] = [
        {"model": "gravity"}, {"model": "non-linear hydrostatic"},
        *([{"model": "non-linear Froude-Krylov"}] if froude_krylov else []),
        *radiation,  # the linear damping: about 5 % of critical
        {"model": "quadratic_damping", "diagonal": [1e6, 4e6, 0, 0, 0, 2e12]},
        {"model": "linear_stiffness", "diagonal": [1e6, 1e6, 0, 0, 0, 1e10]},
    ]  # fmt: skip
    return raw


def _fpso_moored(raw: dict, tmp: Path, froude_krylov: bool) -> dict:
    """Issue 43's case as filed (part 5 of the module docstring): the moored barge of the
    example with the FPSO's hull, mass and inertia (part 4), its fairleads at the FPSO's ends
    and its anchors moved with them, the excitation the Froude-Krylov force on the mesh (and
    the database's diffraction) or the database's (diffraction and Froude-Krylov)."""
    raw = copy.deepcopy(raw)
    hull = tmp / "fpso_1296.stl"
    if not hull.exists():
        meshes.write_stl(meshes.barge(310.0, 58.0, 32.0, 10.5), hull)  # 30 x 6 x 4 panels
    fpso = _barge(raw)
    mass = 1025.0 * 310.0 * 58.0 * 20.5  # kg: floating at 20.5 m
    fpso.update(position=[0.0, 0.0, 16.0 - 20.5], mass=mass, mesh={"file": str(hull)},
                inertia=[mass * 20.0**2, mass * 78.0**2, mass * 78.0**2])  # fmt: skip
    shift = {"bow": (110.0, 0.0), "port": (-110.0, 17.0), "starboard": (-110.0, -17.0)}
    for name, (dx, dy) in shift.items():  # the example's lines, from the FPSO's ends
        x, y, _ = fpso["points"][f"fairlead_{name}"]
        fpso["points"][f"fairlead_{name}"] = [x + dx, y + dy, 0.5]  # 4 m under the water
        anchor = next(b for b in raw["bodies"] if b["name"] == f"anchor_{name}")
        anchor["position"] = [anchor["position"][0] + dx, anchor["position"][1] + dy, -100.0]
    excitation = [
        {"model": "non-linear hydrostatic"}, {"model": "non-linear Froude-Krylov"},
        {"model": "diffraction", "froude_krylov": False},
    ] if froude_krylov else [
        {"model": "non-linear hydrostatic", "free_surface": "still"},
        {"model": "diffraction", "froude_krylov": True},
    ]  # fmt: skip
    fpso["external forces"] = [
        {"model": "gravity"}, *excitation,
        {"model": "radiation damping", "memory": 25.0, "memory_step": 0.1},
        {"model": "quadratic_damping", "diagonal": [1e6, 4e6, 0, 0, 0, 2e12]},
    ]  # fmt: skip
    return raw


def _fpso_realtime(raw: dict, args, tmp: Path) -> None:
    """Part 4 of the module docstring."""
    dopri5 = {"integrator": "dopri5", "rtol": 1e-6}
    for memory in (False, True):
        factors = []
        label = " + the barge's radiation memory and diffraction" if memory else ""
        for froude_krylov in (True, False):
            case = _fpso(raw, tmp, froude_krylov, memory)
            cost = _evaluation(case, max(10, args.count // 40), args.repeat)
            setup, factor, steps, evaluations, _ = _realtime(case, args.duration, dopri5)
            factors.append(factor)
            print(f"  FPSO, 1,296 triangles{label}, {'with' if froude_krylov else 'without'} "
                  f"Froude-Krylov, dopri5 rtol 1e-6: {factor:6.2f} (CPU "
                  f"{(args.duration - SETUP) / factor:.1f} s; setup {setup:4.1f} s; {steps} "
                  f"steps, {evaluations} evaluations of {cost:.0f} us)")  # fmt: skip
        print(
            f"  FPSO{label}: Froude-Krylov on the mesh costs {factors[1] / factors[0]:.2f} "
            "times the run"
        )
    implicit = {"integrator": "generalized_alpha", "time_step": 0.05, "newton_tolerance": 1e-7}
    factors = []
    for froude_krylov in (True, False):
        case = _fpso_moored(raw, tmp, froude_krylov)
        cost = _evaluation(case, max(10, args.count // 40), args.repeat)
        setup, factor, steps, evaluations, results = _realtime(case, args.duration, implicit)
        factors.append(factor)
        jacobians = int(results.dataset.attrs.get("solver_jacobian_evaluations", 0))
        tension = _tension(results)
        print(
            f"  moored FPSO, {'Froude-Krylov on the mesh' if froude_krylov else 'database'}"
            f", generalized-alpha 0.05 s, Newton 1e-7: {factor:6.2f} (CPU "
            f"{(args.duration - SETUP) / factor:.1f} s; setup {setup:4.1f} s; {steps} steps, "
            f"{evaluations} evaluations of {cost:.0f} us, {jacobians} Newton matrices; "
            f"fairlead tensions {tension.min() / 1e3:.0f} to {tension.max() / 1e3:.0f} kN)"
        )
    print(
        f"  moored FPSO: Froude-Krylov on the mesh costs {factors[1] / factors[0]:.2f} times "
        "the run"
    )


def _evaluation(raw: dict, count: int, repeat: int) -> float:
    """CPU microseconds of one evaluation (the fastest round)."""
    built = system_model.build(seacable.load_case(raw))
    p, y = built.params, built.y0.copy()
    w = kernel.make_work(p)
    ydot = np.zeros_like(y)
    _loop(1.0, y, p, w, ydot, 2)
    best = np.inf
    for _ in range(repeat):
        start = time.thread_time()
        _loop(1.0, y, p, w, ydot, count)
        best = min(best, time.thread_time() - start)
    return 1e6 * best / count


SETUP = 2.0  # s: the short run whose CPU time is the setup's (statics, database, mesh)


def _run(raw: dict, duration: float, settings: dict) -> tuple[float, object]:
    """CPU seconds of a run of ``duration`` [s] with the simulation ``settings``, and its
    results."""
    raw = copy.deepcopy(raw)
    for key in ("integrator", "rtol", "time_step", "newton_tolerance"):  # the example's
        raw["simulation"].pop(key, None)
    raw["simulation"].update(duration=duration, **settings)
    case = seacable.load_case(raw)
    start = time.process_time()
    results = seacable.simulate(case)
    return time.process_time() - start, results


def _realtime(raw: dict, duration: float, settings: dict) -> tuple:
    """The setup's CPU seconds (a run of SETUP s, compiled beforehand) and the real-time factor
    of the rest (simulated seconds per CPU second beyond it: what a long storm costs), with
    the run's accepted steps, evaluations and results."""
    _run(raw, 1.0, settings)  # compiled before the clock starts
    setup, _ = _run(raw, SETUP, settings)
    spent, results = _run(raw, duration, settings)
    attrs = results.dataset.attrs
    steps, evaluations = int(attrs["solver_accepted_steps"]), int(attrs["solver_rhs_evaluations"])
    return setup, (duration - SETUP) / (spent - setup), steps, evaluations, results


def _tension(results) -> np.ndarray:
    """The fairlead tensions [N] (time, line) of the moored barge's three lines."""
    tree = results.dataset
    return np.stack([np.sqrt(sum(tree[f"lines/{name}/to_force_{c}"].values ** 2 for c in "xyz"))
                     for name in ("bow", "port", "starboard")], axis=1)  # fmt: skip


def _errors(results, reference) -> tuple[float, float]:
    """The largest fairlead-tension error against the reference run's, relative to its peak,
    and the largest heave error [m]."""
    tension, exact = _tension(results), _tension(reference)
    heave = results.dataset["bodies/barge/position_z"].values
    return (
        float(np.abs(tension - exact).max() / np.abs(exact).max()),
        float(np.abs(heave - reference.dataset["bodies/barge/position_z"].values).max()),
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--count", type=int, default=2000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--duration", type=float, default=200.0)
    parser.add_argument("--realtime-only", action="store_true", help="only part 3")
    parser.add_argument("--costs-only", action="store_true", help="only parts 1 and 2")
    parser.add_argument("--fpso-only", action="store_true", help="only parts 4 and 5")
    args = parser.parse_args()
    logging.getLogger("seacable").setLevel(logging.ERROR)  # the example's kernel-tail warning
    tmp = Path(os.environ.get("TMPDIR", "/tmp")) / "seacable_vessel_cost"
    tmp.mkdir(exist_ok=True)
    raw = _raw()
    print(f"load average {os.getloadavg()[0]:.2f}; CPU time, fastest of {args.repeat}")
    if args.fpso_only:
        print(f"\nreal-time factor over {args.duration:g} s (beyond a {SETUP:g} s setup):")
        _fpso_realtime(raw, args, tmp)
        return
    if not args.realtime_only:
        _costs(raw, args, tmp)
    if not args.costs_only:
        _realtimes(raw, args, tmp)


def _costs(raw: dict, args, tmp: Path) -> None:
    """Parts 1 and 2 of the module docstring."""
    whole = _evaluation(_without(raw, "nothing"), args.count, args.repeat)  # as the parts start
    print(f"\nmoored barge, one evaluation: {whole:8.1f} us")
    for part in ("mesh", "radiation", "excitation", "lines"):
        less = _evaluation(_without(raw, part), args.count, args.repeat)
        print(f"  {part:10s} {whole - less:8.1f} us  ({100 * (whole - less) / whole:5.1f} %)")
    print("\nvessel alone (non-linear hydrostatics and Froude-Krylov, radiation, diffraction):")
    for panel in (6.0, 4.0, 3.0, 2.2):
        case = _alone(raw, panel, tmp)
        triangles = len(meshes.read(_barge(case)["mesh"]["file"]).triangles)
        cost = _evaluation(case, max(10, args.count // 40), args.repeat)
        print(f"  {triangles:6d} triangles: {cost:8.1f} us")
    print("\nmoored barge, by the kernel's length (memory 25 s):")
    for step in (0.2, 0.1, 0.05):
        case = copy.deepcopy(raw)
        for f in _barge(case)["external forces"]:
            if f["model"] == "radiation damping":
                f["memory_step"] = step
        samples = int(round(25.0 / step)) + 1
        print(f"  {samples:5d} samples: {_evaluation(case, args.count, args.repeat):8.1f} us")
    print("\nmoored barge, by the lines' segments:")
    for segments in (20, 40, 80):
        case = copy.deepcopy(raw)
        for line in case["lines"]:
            line["sections"][0]["segments"] = segments
        case["start"] = "as_given"  # the cost of an evaluation, not the statics
        print(f"  {segments:3d} segments a line: "
              f"{_evaluation(case, args.count, args.repeat):8.1f} us")  # fmt: skip


def _realtimes(raw: dict, args, tmp: Path) -> None:
    """Part 3 of the module docstring."""
    print(
        f"\nreal-time factor over {args.duration:g} s (simulated s per CPU s, beyond the "
        f"setup: a run of {SETUP:g} s, its CPU s given); errors against dopri5 at rtol 1e-9:"
    )
    _, _, _, _, reference = _realtime(raw, args.duration, {"integrator": "dopri5", "rtol": 1e-9})
    tension, tree = _tension(reference), reference.dataset
    offsets = [tree[f"bodies/barge/position_{c}"].values for c in "xy"]
    print(f"  the reference: surge {offsets[0].min():.1f} to {offsets[0].max():.1f} m, sway "
          f"{offsets[1].min():.1f} to {offsets[1].max():.1f} m, fairlead tensions "
          f"{tension.min() / 1e3:.0f} to {tension.max() / 1e3:.0f} kN")  # fmt: skip
    implicit = {"integrator": "generalized_alpha"}
    for label, settings in (
        ("dopri5 rtol 1e-6", {"integrator": "dopri5", "rtol": 1e-6}),
        (
            "generalized-alpha 0.05 s, Newton 1e-9",
            {**implicit, "time_step": 0.05, "newton_tolerance": 1e-9},
        ),
        (
            "generalized-alpha 0.025 s, Newton 1e-7",
            {**implicit, "time_step": 0.025, "newton_tolerance": 1e-7},
        ),
        (
            "generalized-alpha 0.05 s, Newton 1e-7",
            {**implicit, "time_step": 0.05, "newton_tolerance": 1e-7},
        ),
        (
            "generalized-alpha 0.1 s, Newton 1e-7",
            {**implicit, "time_step": 0.1, "newton_tolerance": 1e-7},
        ),
    ):
        try:
            setup, factor, steps, evaluations, results = _realtime(raw, args.duration, settings)
        except SimulationDiverged as error:  # a run that fails is a row, not a lost benchmark
            print(f"  moored barge, {label}: {str(error).split(';')[0]}")
            continue
        tension, heave = _errors(results, reference)
        jacobians = int(results.dataset.attrs.get("solver_jacobian_evaluations", 0))
        print(f"  moored barge, {label}: {factor:6.1f} (setup {setup:4.1f} s; {steps} steps, "
              f"{evaluations} evaluations, {jacobians} Newton matrices; fairlead tension "
              f"error {tension:.1e} of its peak, heave {heave:.1e} m)")  # fmt: skip
    setup, factor, steps, evaluations, _ = _realtime(
        _alone(raw, 2.2, tmp), args.duration, {"integrator": "dopri5", "rtol": 1e-6}
    )
    print(f"  vessel alone, 3,052 triangles, dopri5 rtol 1e-6: {factor:6.2f} (setup {setup:4.1f}"
          f" s; {steps} steps, {evaluations} evaluations)")  # fmt: skip
    _fpso_realtime(raw, args, tmp)


if __name__ == "__main__":
    main()
