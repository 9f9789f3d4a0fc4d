"""How often the statics start: a family of random spread moorings, each solved by
``seacable.statics`` from its case as a user writes it (default settings), the success rate
printed with every failure's message.

Each mooring (seeded, reproducible): a platform free in surge, sway and yaw (a rigid body; its
heave, roll and pitch held) in water 50 to 1,000 m deep, on 3 to 8 lines spread around it with
some scatter, fairleads 10 to 40 m out and 5 to 20 m down, anchors 0.5 to 5 depths beyond;
its lines all of one type (chain, wire or polyester, 50 to 150 mm), each of its own length, from
nearly taut (2 % of the way from the straight distance) to beyond slack (1.2 times span plus
rise: a heap on the seabed), in segments of 1 to 50 m (log-uniform; at most 200 a line), pushed
by a steady horizontal force of up to the weight in water of one line's suspended part, in any
direction. The target (issue 39): 100 %.

Run: python benchmarks/statics_success.py [--count N] [--seed S] [--only K,...]
(``--only``: those moorings of the family alone, each with its time). ``--family shapes``: the
other geometries issue 39 names, written out (``shapes``): U-shaped lines between buoys,
touching down or hanging clear, a buoy between chains lying slack, a line folded under a buoy,
and a lumped-mass tow from seven first guesses of its towed body. Exit status 0 whatever the
rate.
"""

import argparse
import math
import time

import numpy as np

import seacable

TYPES = {  # name: (mass per length / d^2 [kg/m^3], EA / d^2 [N/m^2], Cd)
    "chain": (19.9e3, 85.4e9, 2.4),
    "wire": (5.0e3, 45.0e9, 1.2),
    "polyester": (1.1e3, 1.2e9, 1.2),  # in water 295 d^2 kg/m: lighter than chain, not buoyant
}


def mooring(rng: np.random.Generator, k: int) -> dict:
    depth = float(rng.uniform(50.0, 1000.0))
    count = int(rng.integers(3, 9))
    kind = str(rng.choice(list(TYPES)))
    diameter = float(rng.uniform(0.05, 0.15))
    density, stiffness, cd = TYPES[kind]
    line_types = [{"name": kind, "diameter": diameter, "mass_per_length": density * diameter**2,
                   "axial_stiffness": stiffness * diameter**2,
                   "drag_coefficient_normal": cd}]  # fmt: skip
    wet = 9.81 * (density - 1025.0 * math.pi / 4) * diameter**2  # [N/m]
    lines, bodies, points = [], [], {}
    suspended = 0.0
    for i in range(count):
        angle = 2 * math.pi * i / count + float(rng.normal(0.0, 0.15))
        radius = float(rng.uniform(10.0, 40.0))
        draft = float(rng.uniform(5.0, 20.0))
        fair = np.array([radius * math.cos(angle), radius * math.sin(angle), -draft])
        span = float(rng.uniform(0.5, 5.0)) * depth
        anchor = fair[:2] + span * np.array([math.cos(angle), math.sin(angle)])
        rise = depth - draft
        straight = math.hypot(span, rise)
        slack = 1.2 * (span + rise)
        length = straight + float(rng.uniform(0.02, 1.0)) * (slack - straight)
        segment = float(np.exp(rng.uniform(math.log(1.0), math.log(50.0))))
        segments = int(min(200, max(2, round(length / segment))))
        suspended = max(suspended, wet * rise)
        bodies.append({"name": f"anchor{i}", "type": "fixed",
                       "position": [float(anchor[0]), float(anchor[1]), -depth]})  # fmt: skip
        points[f"fairlead{i}"] = [float(v) for v in fair]
        section = {"type": kind, "length": length, "segments": segments}
        lines.append({"name": f"line{i}", "model": "lumped_mass", "from": f"anchor{i}",
                      "to": f"platform.fairlead{i}", "sections": [section]})  # fmt: skip
    heading = float(rng.uniform(0.0, 2 * math.pi))
    force = float(rng.uniform(0.0, 1.0)) * suspended
    bodies.append({
        "name": "platform", "type": "rigid", "position": [0.0, 0.0, 0.0], "mass": 1.0e7,
        "inertia": [1e10, 1e10, 1e10], "dofs": ["surge", "sway", "yaw"], "points": points,
        "external forces": [{"model": "applied", "force_x": force * math.cos(heading),
                             "force_y": force * math.sin(heading)}],
    })  # fmt: skip
    return {
        "name": f"random mooring {k}",
        "environment": {"water_depth": depth, "seabed": {"stiffness": 3.0e5}},
        "bodies": bodies, "line_types": line_types, "lines": lines,
        "simulation": {"duration": 10.0, "output_interval": 1.0},
    }  # fmt: skip


CHAIN = {"name": "chain", "diameter": 0.08, "mass_per_length": 120.0, "axial_stiffness": 5e8,
         "drag_coefficient_normal": 1.2, "added_mass_coefficient": 1.0}  # fmt: skip


def shapes() -> list[tuple[str, dict]]:
    """The hand-written geometries of ``--family shapes`` (module docstring), by name."""

    def buoy(name, x, volume=40.0):
        return {"name": name, "type": "point", "position": [x, 0.0, -20.0], "mass": 5000.0,
                "volume": volume,
                "external forces": [{"model": "gravity"}, {"model": "buoyancy"}]}  # fmt: skip

    def fixed(name, x, z):
        return {"name": name, "type": "fixed", "position": [x, 0.0, z]}

    def chain(name, a, b, length, segments):
        return {
            "name": name,
            "model": "lumped_mass",
            "from": a,
            "to": b,
            "sections": [{"type": "chain", "length": length, "segments": segments}],
        }

    def case(depth, bodies, lines):
        return {"environment": {"water_depth": depth,
                                "seabed": {"stiffness": 1e5, "damping": 1e3}},
                "line_types": [CHAIN], "bodies": bodies, "lines": lines,
                "simulation": {"duration": 1.0, "output_interval": 0.1}}  # fmt: skip

    out = []
    for u, what in ((260.0, "touching down"), (140.0, "hanging clear")):
        out.append((f"a U {what} between two tethered buoys", case(100.0, [
            buoy("b1", -60.0), buoy("b2", 60.0), fixed("a1", -60.0, -100.0),
            fixed("a2", 60.0, -100.0)], [chain("t1", "a1", "b1", 85.0, 17),
            chain("t2", "a2", "b2", 85.0, 17), chain("u", "b1", "b2", u, 40)])))  # fmt: skip
    for u in (300.0, 500.0):
        out.append((f"a U of {u:g} m lying slack between buoys on vertical tethers", case(
            60.0, [buoy("b1", -60.0), buoy("b2", 60.0), fixed("a1", -60.0, -60.0),
                   fixed("a2", 60.0, -60.0)], [chain("t1", "a1", "b1", 45.0, 9),
                   chain("t2", "a2", "b2", 45.0, 9), chain("u", "b1", "b2", u, 60)])))  # fmt: skip
    out.append(("a buoy between two chains lying slack", case(100.0, [
        fixed("a1", -100.0, -100.0), fixed("a2", 100.0, -100.0), buoy("b1", 0.0, 20.0)],
        [chain("l1", "a1", "b1", 200.0, 40), chain("l2", "b1", "a2", 200.0, 40)])))  # fmt: skip
    out.append(("a line folded under a buoy", case(100.0, [
        buoy("b1", 0.0, 60.0), fixed("a1", 0.0, -100.0)],
        [chain("l1", "b1", "a1", 79.0, 40), chain("hang", "b1", "b1", 60.0, 40)])))  # fmt: skip
    for guess in ([0, 0, -500], [-500, 0, 0], [-400, 0, -300], [300, 0, -200], [-100, 80, -50],
                  [0, 0, -50], [-200, 0, -10]):  # fmt: skip
        out.append((f"a lumped tow from the guess {guess}", _tow([float(v) for v in guess])))
    return out


def _tow(guess: list[float]) -> dict:
    """Jacquot and Marichal's towed cable (500 m, 2.5 m/s) as a lumped-mass line (EA 2e7 N),
    its 300 kg towed body first placed at ``guess`` [m]."""
    cable = {"name": "cable", "diameter": 0.02, "mass_per_length": 1.47,
             "axial_stiffness": 2e7, "drag_coefficient_normal": 1.8,
             "friction_coefficient": 0.02, "added_mass_coefficient": 1.0}  # fmt: skip
    return {
        "environment": {"water_density": 1025.0},
        "bodies": [{"name": "top", "type": "imposed",
                    "track": {"start": [0.0, 0.0], "heading_deg": 0.0,
                              "distance": {"kind": "acceleration_profile",
                                           "initial_velocity": 2.5,
                                           "phases": [{"duration": 10.0, "acceleration": 0.0}]}}},
                   {"name": "end", "type": "point", "position": guess, "mass": 300.0,
                    "volume": 0.15, "added_mass": [100.0, 100.0, 100.0],
                    "external forces": [{"model": "gravity"}, {"model": "buoyancy"},
                                        {"model": "drag", "drag_coefficient": 1.0,
                                         "area": [0.3, 0.3, 0.3]}]}],
        "line_types": [cable],
        "lines": [{"name": "cable", "model": "lumped_mass", "from": "top", "to": "end",
                   "sections": [{"type": "cable", "segments": 100, "length": 500.0}]}],
        "simulation": {"duration": 1.0, "output_interval": 0.1},
    }  # fmt: skip


def _shapes_family() -> None:
    found, start = 0, time.perf_counter()
    cases = shapes()
    for name, case in cases:
        began = time.perf_counter()
        try:
            seacable.statics(seacable.load_case(case))
            found, outcome = found + 1, "found"
        except Exception as exc:  # every failure is counted and printed
            outcome = f"{type(exc).__name__}: {str(exc)[:200]}"
        print(f"{name}: {outcome} ({time.perf_counter() - began:.1f} s)", flush=True)
    print(f"statics found for {found} of {len(cases)} shapes, "
          f"{time.perf_counter() - start:.0f} s")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--count", type=int, default=200)
    parser.add_argument("--seed", type=int, default=39)
    parser.add_argument("--only", type=str, default="", help="moorings K,... of the family")
    parser.add_argument("--family", choices=("random", "shapes"), default="random")
    args = parser.parse_args()
    if args.family == "shapes":
        _shapes_family()
        return
    only = {int(k) for k in args.only.split(",")} if args.only else None
    rng = np.random.default_rng(args.seed)
    failures = []
    tried = 0
    start = time.perf_counter()
    for k in range(max(only) + 1 if only else args.count):
        case = mooring(rng, k)  # drawn in turn: the family is the same whatever is run
        if only is not None and k not in only:
            continue
        tried += 1
        began = time.perf_counter()
        try:
            seacable.statics(seacable.load_case(case))
        except Exception as exc:  # every failure is counted and printed
            failures.append((k, f"{type(exc).__name__}: {exc}"))
            print(f"mooring {k}: {failures[-1][1][:300]}", flush=True)
        if only is not None:
            print(f"mooring {k}: {time.perf_counter() - began:.1f} s", flush=True)
    took = time.perf_counter() - start
    done = tried - len(failures)
    print(f"statics found for {done} of {tried} random moorings "
          f"({100.0 * done / tried:.1f} %), seed {args.seed}, {took:.0f} s")  # fmt: skip


if __name__ == "__main__":
    main()
