"""Results do not depend on how a run is cut into compiled chunks (the run loop sizes chunks
from wall time, so they would otherwise depend on machine load): every integrator, run with one
output interval per chunk, seven, and all at once, writes the same NetCDF file bit for bit.

The only attribute left out of the comparison is ``created``, the wall-clock time the file was
written (the one timing attribute; the work counters are compared and must agree too)."""

import h5netcdf
import numpy as np
import pytest

import seacable
from helpers import chain_case
from seacable.case import legacy
from seacable.case.loader import load_single_cable


def _as_system(data):
    """The case as a system of bodies and lines (``seacable upgrade``)."""
    return legacy.upgrade(load_single_cable(data))


TIMING_ATTRIBUTES = ("created",)
ALL_AT_ONCE = 10**9


def _lumped_line(integrator, **simulation):
    """An eight-segment mooring chain with part of it on the seabed (contact, friction), its
    fairlead surging: Newton's iteration and the adaptive steps have work to do."""
    return _as_system(
        {
            "environment": {
                "water_depth": 200.0,
                "seabed": {"stiffness": 3.0e5, "damping": 3.0e3, "friction_coefficient": 0.5},
            },
            "cables": [
                {
                    "model": "lumped_mass",
                    "links": 8,
                    "length": 250.0,
                    "diameter": 0.137,
                    "mass_per_length": 126.0,
                    "axial_stiffness": 5.8e8,
                    "axial_damping_time": 0.002,
                    "drag_coefficient_normal": 1.2,
                    "drag_coefficient_tangential": 0.1,
                    "top": {
                        "type": "imposed",
                        "x": {"kind": "sine", "amplitude": 5.0, "period": 2.0},
                        "z": -10.0,
                    },
                    "bottom": {"type": "pinned", "anchor": [-100.0, 0.0, -200.0]},
                    "initial": {"shape": "catenary"},
                }
            ],
            "simulation": {
                "duration": 2.0,
                "output_interval": 0.1,
                "integrator": integrator,
                **simulation,
            },
        }
    )


def _lumped_line_in_waves(integrator, **simulation):
    """The chain of ``_lumped_line`` in an irregular sea: an implicit step's residuals reuse
    the water's kinematics they recorded at its end time (kernels.lumped LAGGED), which the
    outputs evaluated where a chunk ends must not disturb."""
    data = _lumped_line(integrator, **simulation)
    data["environment"]["waves"] = [{"kind": "jonswap", "significant_height": 3.0,
                                     "peak_period": 8.0, "frequencies": 20, "seed": 3}]  # fmt: skip
    return data


def _rigid_chain(integrator, **simulation):
    """A planar chain of six rigid links swinging in water from a heaving floating structure:
    the implicit schemes keep its factorised Newton matrix from step to step."""
    return _as_system(chain_case(
        n=6,
        environment={"water_density": 1025.0},
        top={
            "type": "floating_structure",
            "mass": 100.0,
            "heave_stiffness": 2.0e3,
            "force": {"kind": "sine", "amplitude": 300.0, "period": 1.5},
        },
        initial={"shape": "arc", "top_angle_deg": 30.0, "bottom_angle_deg": 60.0},
        simulation={"duration": 2.0, "output_interval": 0.1, "integrator": integrator,
                    **simulation},
    ))  # fmt: skip


def _buoys(integrator, **simulation):
    """Two moored buoys joined by a hawser (a loop of lumped lines through point bodies), the
    first 2 s: the implicit schemes' border of body unknowns."""
    case = seacable.load_case("examples/two_buoys_moored_with_hawser.yaml")
    data = case.model_dump(mode="json", by_alias=True, exclude_unset=True)
    data["start"] = "as_given"  # lines at rest between the buoys where the case puts them
    data["simulation"] = {"duration": 2.0, "output_interval": 0.1, "integrator": integrator,
                          **simulation}  # fmt: skip
    return data


def _servo(integrator, **simulation):
    """The towed umbilical whose end a servo holds on its target, K refreshed every 0.5 s (the
    run stops its chunks there; a dopri5 chunk cut inside an interval must not refresh)."""
    case = seacable.load_case("examples/jacquot_marichal_trajectory_servo.yaml")
    data = case.model_dump(mode="json", by_alias=True, exclude_unset=True)
    for body in data["bodies"]:
        for force in body.get("external forces", []):
            if force["model"] == "servo":
                force["recompute_interval"] = 0.5
    data["simulation"] = {"duration": 2.0, "output_interval": 0.1, "integrator": integrator,
                          **simulation}  # fmt: skip
    return data


CASES = {
    "dopri5 servo": (_servo, "dopri5", {}),
    "rk4 rigid": (_rigid_chain, "rk4", {"time_step": 0.002}),
    "dopri5 rigid": (_rigid_chain, "dopri5", {"rtol": 1e-7}),
    "dopri5 lumped": (_lumped_line, "dopri5", {}),
    "newmark point body": (_buoys, "newmark", {"time_step": 0.01}),
    "implicit_euler lumped": (_lumped_line, "implicit_euler", {"time_step": 0.01}),
    "theta lumped": (_lumped_line, "theta", {"time_step": 0.01, "theta": 0.6}),
    "newmark lumped": (_lumped_line, "newmark", {"time_step": 0.01}),
    "generalized_alpha lumped": (_lumped_line, "generalized_alpha", {"time_step": 0.01}),
    # steps of three output intervals, the last past the end (numerics.dense)
    "generalized_alpha lumped long steps": (_lumped_line, "generalized_alpha", {"time_step": 0.3}),
    "generalized_alpha lumped waves long steps": (
        _lumped_line_in_waves,
        "generalized_alpha",
        {"time_step": 0.2},
    ),  # fmt: skip
    "generalized_alpha lumped waves": (
        _lumped_line_in_waves,
        "generalized_alpha",
        {"time_step": 0.05},
    ),  # fmt: skip
    "newmark rigid": (_rigid_chain, "newmark", {"time_step": 0.01}),
    "generalized_alpha rigid": (_rigid_chain, "generalized_alpha", {"time_step": 0.01}),
    "bdf lumped": (_lumped_line, "bdf", {}),
    "radau lumped": (_lumped_line, "radau", {}),
    "lsoda lumped": (_lumped_line, "lsoda", {}),
    "cvode lumped": (_lumped_line, "cvode", {}),
}


def _read(path):
    """Every variable's bytes (coordinates included) and every attribute of a results file."""
    with h5netcdf.File(path, "r") as f:
        variables = {name: np.asarray(v[...]) for name, v in f.variables.items()}
        attrs = dict(f.attrs)
    return variables, attrs


@pytest.mark.parametrize("name", list(CASES))
def test_results_are_bitwise_independent_of_chunk_sizes(name, tmp_path):
    build, integrator, simulation = CASES[name]
    case = seacable.load_case(build(integrator, **simulation))
    files = {}
    for chunk in (1, 7, None, ALL_AT_ONCE):  # None: sized by wall time, first chunks cut
        path = tmp_path / f"chunks_{chunk}.nc"  # inside an interval (one step, ten dopri5 steps)
        results = seacable.simulate(case, output=path, chunk_outputs=chunk)
        assert results.complete, results.message
        files[chunk] = _read(path)
    variables, attrs = files[ALL_AT_ONCE]
    assert len(variables["time"]) == 21
    assert attrs["solver_accepted_steps"] != 0
    for chunk in (1, 7, None):
        other_variables, other_attrs = files[chunk]
        assert set(other_variables) == set(variables)
        for key, values in variables.items():
            other = other_variables[key]
            assert other.shape == values.shape and other.tobytes() == values.tobytes(), (
                f"{name}: variable {key} differs with {chunk}-output chunks "
                f"(largest difference {np.nanmax(np.abs(other - values)):.3g})"
            )
        kept = {k: v for k, v in attrs.items() if k not in TIMING_ATTRIBUTES}
        other_kept = {k: v for k, v in other_attrs.items() if k not in TIMING_ATTRIBUTES}
        assert set(other_kept) == set(kept)
        for key, value in kept.items():
            assert np.array_equal(other_kept[key], value), (key, other_kept[key], value)


def test_chunk_outputs_must_be_positive():
    case = seacable.load_case(_rigid_chain("rk4", time_step=0.002))
    with pytest.raises(ValueError, match="chunk_outputs must be a positive integer"):
        seacable.simulate(case, chunk_outputs=0)
