"""Poth (2002) string pendulum: CPU time against EA for each formulation and each integrator
(the paper's figures 9 and 10), and the agreement of the formulations on the end mass.

A string of 10 m, 1 kg/m, carrying a 10 kg end mass, with Kelvin-Voigt damping alpha = 1e-3 s
and no compression, is released horizontal and unstretched from a fixed pivot and swings for 2 s
in air; k = 40 elements. The paper gives neither the string's length, mass and end mass nor
alpha: these are our choices. As in the paper: EA from 1e4 to 1e8, fixed step 0.005 s (400
steps) for the fixed-step schemes (theta = 1/2, Newmark gamma = 1/2, beta = 1/4), tolerances
1e-7 for the adaptive ones and for Newton's iteration.

Formulations: displacement variables (``lumped_mass``), natural variables with cartesian tangent
(eps, t) and with an angle (eps, phi) (``natural_string``), each run as a system of bodies and
lines: the fixed body ``pivot``, the point body ``end`` (the end mass, gravity its one force
model) and the line ``string`` between them (a lumped line started ``straight``, a natural
string at 90 degrees); the end mass's position is ``bodies/end/position_x, _z``. Integrators:
SUNDIALS CVODE (BDF, the successor of the DASSL the paper found fastest), SciPy BDF, Radau and
LSODA, and seacable's compiled implicit Euler, theta-method, Newmark and generalized-alpha
(Newton's matrix from finite differences over colour groups, ``numerics.system_implicit``).
CPU times are wall times of the whole run (kernels compiled beforehand), scaled like the
paper's figures by the (eps, phi) formulation with CVODE at EA = 1e4.
Run: ``python benchmarks/string_pendulum.py [--quick]``.
"""

import argparse
import logging
import math
import time

import numpy as np

import seacable

LENGTH, MU, END_MASS, ALPHA, K = 10.0, 1.0, 10.0, 1e-3, 40
DURATION, STEP, TOL = 2.0, 0.005, 1e-7
FORMULATIONS = {
    "displacement": ("lumped_mass", None),
    "eps, t": ("natural_string", "cartesian"),
    "eps, phi": ("natural_string", "angle"),
}
ADAPTIVE = ("cvode", "bdf", "radau", "lsoda")
FIXED = ("implicit_euler", "theta", "newmark", "generalized_alpha")


def case(formulation, ea, integrator, duration=DURATION):
    """The pendulum as a system: the fixed body ``pivot``, the point body ``end`` (the end mass,
    at the end of the horizontal string) and the line ``string`` between them, at rest and
    unstretched (a lumped line ``straight`` between its ends; a natural string at 90 deg)."""
    model, tangent = FORMULATIONS[formulation]
    line = {
        "name": "string",
        "model": model,
        "from": "pivot",
        "to": "end",
        "sections": [{"type": "string", "segments": K, "length": LENGTH}],
    }
    if tangent:
        line.update(tangent=tangent, initial={"arc_deg": [90.0, 90.0]})
    else:
        line["initial"] = "straight"
    simulation = {"duration": duration, "output_interval": 0.1, "integrator": integrator}
    if integrator in FIXED:
        simulation.update(time_step=STEP, newton_tolerance=TOL, max_newton_iterations=20)
    else:
        simulation.update(rtol=TOL, atol=TOL)
    return seacable.load_case(
        {
            "environment": {"in_air": True},
            "bodies": [
                {"name": "pivot", "type": "fixed", "position": [0.0, 0.0, 0.0]},
                {
                    "name": "end",
                    "type": "point",
                    "position": [LENGTH, 0.0, 0.0],
                    "mass": END_MASS,
                    "external forces": [{"model": "gravity"}],
                },
            ],
            "line_types": [
                {
                    "name": "string",
                    "diameter": 0.01,
                    "mass_per_length": MU,
                    "axial_stiffness": ea,
                    "axial_damping_time": ALPHA,
                }
            ],
            "lines": [line],
            "start": "as_given",
            "simulation": simulation,
        }
    )


def run(formulation, ea, integrator):
    """(wall time [s], end mass x, z at the end, work attributes) or None when it fails."""
    try:
        seacable.simulate(case(formulation, ea, integrator, duration=0.1))  # compile first
        start = time.perf_counter()
        ds = seacable.simulate(case(formulation, ea, integrator)).dataset
    except seacable.SimulationDiverged:  # a failing first step fails the short run too
        return None
    wall = time.perf_counter() - start
    x, z = (ds[f"bodies/end/position_{a}"].values[-1] for a in "xz")
    return wall, x, z, dict(ds.attrs)


def table(title, rows, columns, values, scale):
    print(title)
    print(f"{'EA [N]':>8} | " + " | ".join(f"{c:>17}" for c in columns))
    for ea in rows:
        cells = []
        for c in columns:
            v = values.get((ea, c))
            cells.append(f"{'failed':>17}" if v is None else f"{v[0]:8.4f} s {v[0] / scale:6.1f}")
        print(f"{ea:8.0e} | " + " | ".join(cells))
    print()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="EA 1e4 and 1e6 only")
    args = parser.parse_args(argv)
    logging.getLogger("seacable").setLevel(logging.ERROR)
    stiffness = (1e4, 1e6) if args.quick else (1e4, 1e5, 1e6, 1e7, 1e8)
    figure9 = {(ea, f): run(f, ea, "cvode") for ea in stiffness for f in FORMULATIONS}
    scale = figure9[(stiffness[0], "eps, phi")][0]
    table(
        "Figure 9: CPU time against EA per formulation (CVODE), seconds and relative to "
        "(eps, phi) at EA = 1e4",
        stiffness, list(FORMULATIONS), figure9, scale,
    )  # fmt: skip
    integrators = ADAPTIVE + FIXED
    figure10 = {(ea, i): run("eps, t", ea, i) for ea in stiffness for i in integrators}
    table(
        "Figure 10: CPU time against EA per integrator, (eps, t) formulation",
        stiffness, integrators, figure10, scale,
    )  # fmt: skip
    displacement = {(ea, i): run("displacement", ea, i) for ea in stiffness for i in FIXED}
    table(
        "Fixed-step schemes on the displacement formulation (Newton matrix from differences)",
        stiffness, FIXED, displacement, scale,
    )  # fmt: skip
    print("End mass at t = 2 s: distance between formulations (CVODE) and to the (eps, phi) run")
    print(f"{'EA [N]':>8} | {'x [m]':>9} {'z [m]':>9} | {'eps,t':>9} {'displ.':>9} | worst scheme")
    for ea in stiffness:
        ref = figure9[(ea, "eps, phi")]
        gaps = {
            f: math.hypot(v[1] - ref[1], v[2] - ref[2])
            for f in ("eps, t", "displacement")
            if (v := figure9[(ea, f)]) is not None
        }
        scheme_gaps = {
            i: math.hypot(v[1] - ref[1], v[2] - ref[2])
            for i in integrators
            if (v := figure10[(ea, i)]) is not None
        }
        worst = max(scheme_gaps, key=scheme_gaps.get)
        print(
            f"{ea:8.0e} | {ref[1]:9.5f} {ref[2]:9.5f} | {gaps.get('eps, t', np.nan):9.2e} "
            f"{gaps.get('displacement', np.nan):9.2e} | {worst} {scheme_gaps[worst]:.2e} m"
        )


if __name__ == "__main__":
    main()
