"""What a finished integration says, for its results' attributes: the integrator's work
counters, the tolerance that governed an adaptive one, an implicit one's error estimate in the
lines' tensions (numerics.system_implicit, ESTIMATE) and the warnings of the run
(``seacable.simulation`` calls ``attributes`` when a run ends, complete or not)."""

import logging

from seacable.numerics import integrators
from seacable.numerics.stability import rk4_step
from seacable.system import failures

log = logging.getLogger("seacable.simulation")


def attributes(run, fixed_step: bool) -> dict:
    """The work counters, the governing tolerance (an adaptive integrator's, not ``fixed_step``),
    the implicit steps' error estimate and what the rows showed that a start would have been
    refused for (``run_warnings``, also logged), for the results' attributes of ``run``
    (``seacable.simulation``'s)."""
    counters = {
        f"solver_{name}": int(v) for name, v in zip(integrators.WORK_NAMES, run.work, strict=True)
    }
    seen = run.watch.warnings()
    estimate, warning = _step_estimate(run)
    if warning:
        seen.append(warning)
    for line in seen:
        log.warning(line)
    released = failures.report(run.p, run.system.case)
    if released:
        log.info("failures: %s", released["failures"])
    return {
        **counters,
        **_tolerance(run, fixed_step),
        **estimate,
        **({"run_warnings": "; ".join(seen)} if seen else {}),
        **released,
    }


def _tolerance(run, fixed_step: bool) -> dict:
    """Which tolerance bounded the adaptive integrator's error, for the results' attributes."""
    if fixed_step or run.samples == 0:
        return {}
    share = 100.0 * run.absolute_governed / run.samples
    if run.sim.atol is None and run.magnitude.size:
        what = (
            "relative: each state's error measured against rtol times the largest magnitude it "
            f"has reached; the floor atol governed {share:.1f} % of the state values at output "
            "times (states that stayed near zero)"
        )
    else:
        which = "absolute (atol)" if share > 50.0 else "relative (rtol |y|)"
        what = (
            f"{which}: atol exceeded rtol |y| for {share:.1f} % of the state values at output times"
        )
    return {
        "solver_atol_smallest": float(run.atol.min()),
        "solver_atol_largest": float(run.atol.max()),
        "solver_tolerance_governing": what,
    }


ESTIMATE_SHARE = 0.5  # an implicit run warns when its steps' local tension error estimate
# (numerics.system_implicit, ESTIMATE) passes this share of the largest tension. The estimate
# is not the error: against dopri5 at rtol 1e-9, the single-line race's runs
# (benchmarks/vs_moordyn.py's line, 20 and 80 segments, 12.5 to 50 ms, spectral radius 0 and
# 0.5) and the moored barge example at 0.05 s were off by 0.4 to 16 % of their estimate's share
# (3.4 % or less where the share passed 0.05; the most where the error was 2e-4 of the peak);
# the race's runs beyond 0.5 were 0.9 to 4.9 % off, the example (0.26) 0.4 %; on the spread
# mooring of benchmarks/vs_moordyn_spread.py (50 segments) 14 % off at a share of 4.1.


def _step_estimate(run) -> tuple[dict, str | None]:
    """An implicit run's largest local tension error estimate [N] and its share of the largest
    tension (numerics.system_implicit, ESTIMATE), and a warning beyond ESTIMATE_SHARE."""
    if run.carry is None or run.p.line_n.shape[0] == 0 or run.carry[1][5] <= 0.0:
        return {}, None
    estimate, largest = float(run.carry[1][4]), float(run.carry[1][5])
    share = estimate / largest
    attrs = {"solver_tension_error_estimate": estimate, "solver_tension_error_share": share}
    if share <= ESTIMATE_SHARE:
        return attrs, None
    sim = run.sim
    return attrs, (
        f"{sim.integrator} at time_step {rk4_step(sim)[0]:g} s: its steps' local error estimate "
        f"in the lumped lines' tensions reaches {estimate / 1e3:.4g} kN, {100 * share:.3g} % of "
        f"the largest tension ({largest / 1e3:.4g} kN); beyond {100 * ESTIMATE_SHARE:g} % the "
        "runs checked were 1 to 5 % off a converged run: the step does not resolve the lines' "
        "motion (a line ringing after a seabed impact or a snap). Run again at half the "
        "time_step and compare, or use dopri5"
    )
