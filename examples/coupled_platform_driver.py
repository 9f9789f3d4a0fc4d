"""Drive seacable's mooring from your own floating-body solver (seacable.coupling.Coupling, the
stepping interface MoorDyn's users know: init, then step(x, v, t, dt) -> forces).

The mooring is the three-chain spread of examples/platform_three_catenary_lines.yaml, its
platform an imposed body whose motion this script gives: a 1.5e7 kg platform (with its surge
added mass) moving in surge under a wind load ramped to 1 MN over 30 s, with linear damping,
integrated here by semi-implicit Euler at the coupling step, the mooring's force taken from
seacable at each step. ``native()`` runs the same platform as a seacable rigid body free in
surge, for comparison (tests/test_coupling.py).

Run: python examples/coupled_platform_driver.py
"""

from pathlib import Path

import numpy as np
import yaml

from seacable.coupling import Coupling

HERE = Path(__file__).parent
MASS = 1.0e7 + 5.0e6  # [kg] platform and its surge added mass
DAMPING = 2.0e5  # [N s/m]


def wind(t: float) -> float:
    """The wind load along x [N]: 0 to 1 MN over 30 s."""
    return 1.0e6 * min(t / 30.0, 1.0)


def mooring() -> dict:
    """The example's case with its platform imposed (its motion given by the driver)."""
    case = yaml.safe_load((HERE / "platform_three_catenary_lines.yaml").read_text())
    platform = case["bodies"][3]
    case["bodies"][3] = {"name": "platform", "type": "imposed", "points": platform["points"]}
    case["simulation"] = {"duration": 1.0, "output_interval": 0.1, "integrator": "rk4",
                          "time_step": 0.002}  # fmt: skip
    return case


def coupled(duration: float = 120.0, dt: float = 0.05) -> np.ndarray:
    """(time, surge [m], mooring force along x [N]) rows of the coupled run."""
    coupling = Coupling(mooring())
    x, v = np.zeros(6), np.zeros(6)  # x, y, z, roll, pitch, yaw of the platform
    force = coupling.init(x, v)
    rows = [(0.0, x[0], force[0])]
    for k in range(round(duration / dt)):
        t = k * dt
        force = coupling.step(x, v, t, dt)  # the lines' force at t + dt, the platform moving at v
        acceleration = (wind(t + dt) + force[0] - DAMPING * v[0]) / MASS
        v[0] += acceleration * dt
        x[0] += v[0] * dt
        rows.append((t + dt, x[0], force[0]))
    return np.array(rows)


def native(duration: float = 120.0) -> np.ndarray:
    """The same platform as a seacable rigid body free in surge: (time, surge) rows."""
    import seacable

    case = yaml.safe_load((HERE / "platform_three_catenary_lines.yaml").read_text())
    platform = case["bodies"][3]
    platform["dofs"] = ["surge"]
    platform["added_mass"] = [5.0e6, 0.0, 0.0, 0.0, 0.0, 0.0]
    platform["external forces"] = [
        {"model": "linear_damping", "diagonal": [DAMPING, 0.0, 0.0, 0.0, 0.0, 0.0]},
        {"model": "applied", "point": "wind_centre",
         "force_x": {"kind": "ramp", "start_time": 0.0, "end_time": 30.0, "end_value": 1.0e6}},
    ]  # fmt: skip
    case["simulation"] = {"duration": duration, "output_interval": 0.5, "integrator": "rk4",
                          "time_step": 0.002}  # fmt: skip
    ds = seacable.simulate(seacable.load_case(case)).dataset["bodies/platform"].to_dataset()
    return np.column_stack([ds["time"].values, ds["position_x"].values])


if __name__ == "__main__":
    rows = coupled()
    for t, surge, force in rows[:: round(10.0 / 0.05)]:
        print(f"t = {t:6.1f} s  surge {surge:8.3f} m  mooring force {force / 1e3:9.1f} kN")
