"""Print the figures behind the physics tests: energy drift, heavy-chain frequencies, the three
models of a seabed-fixed end (each single cable run as the system ``seacable upgrade`` writes).
Run: python benchmarks/physics_checks.py"""

import sys
from pathlib import Path

import numpy as np
from scipy.special import jn_zeros

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from helpers import chain_case, rows, run_rows, upgraded  # noqa: E402
from seacable.analysis import system_modes  # noqa: E402
from test_chain3d import _angles, critical_angle, towing_case  # noqa: E402
from test_chain_physics import SEABED_BOTTOMS, _seabed_case  # noqa: E402
from test_moorpy_catenary import _case, _moorpy, _ours  # noqa: E402


def _drift(res):
    e = res["total_energy"]
    return np.max(np.abs(e - e[0])) / np.ptp(res["kinetic_energy"])


def energy_drift():
    print("energy drift (no damping, in air; max |E - E0| / kinetic-energy swing)")
    for dt in (0.002, 0.001, 0.0005):
        data = chain_case(
            n=30, initial={"shape": "arc", "top_angle_deg": 60.0},
            bottom={"type": "free", "body": {"mass": 2.0}}, joint_stiffness=5.0,
            simulation={"duration": 5.0, "output_interval": 0.05, "time_step": dt},
        )  # fmt: skip
        print(f"  rk4 dt = {dt:<7g} s: {_drift(run_rows(data)):.3e}")
    data["simulation"] = {"duration": 5.0, "output_interval": 0.05, "integrator": "dopri5",
                          "rtol": 1e-9, "atol": 1e-11}  # fmt: skip
    print(f"  dopri5 rtol 1e-9     : {_drift(run_rows(data)):.3e}")


def frequencies():
    exact = jn_zeros(0, 4) / 2 * np.sqrt(9.81 / 10.0)
    print("hanging chain, 10 m: omega_k / heavy-chain value - 1 (modes 1..4)")
    print("  exact [rad/s]:", np.array2string(exact, precision=5))
    for n in (10, 25, 50, 100, 200):
        f = system_modes(upgraded(chain_case(n=n)), count=4)["frequency"].values
        print(f"  n = {n:4d}:", np.array2string(f[:4] / exact - 1, precision=3))


def seabed():
    runs = {name: run_rows(_seabed_case(bottom)) for name, bottom in SEABED_BOTTOMS.items()}
    pinned = runs.pop("pinned")
    print("seabed-fixed end, 100 m cable, 8 s: largest node-position gap to the exact pin")
    for name, r in runs.items():
        gap = np.max(
            np.hypot(
                pinned["node_x"] - r["node_x"],
                pinned["node_z"] - r["node_z"],
            )
        )
        print(f"  {name:10s}: {gap * 1000:.3f} mm")
    print(f"  pin constraint error: {np.max(pinned['constraint_error']):.2e} m")


def towing_statics():
    print(f"towed 500 m cable at 2.5 m/s: critical angle (closed form) {critical_angle():.6f} deg")
    angles = _angles(towing_case(n=100, body=False))
    gap = np.abs(angles - critical_angle()).max()
    print(f"  no body, 100 segments: max |angle - closed form| = {gap:.1e} deg")
    angles = _angles(towing_case(n=100))
    print(f"  with a towed body: top segment {angles[0]:.6f} deg, bottom {angles[-1]:.3f} deg")
    expected = np.abs(_moorpy((60.0, 20.0, -10.0)))
    print("catenary between two points against MoorPy (max relative end-tension difference):")
    for n in (25, 50, 100, 200):
        error = np.max(np.abs(_ours(rows(_case(n))) / expected - 1))
        print(f"  {n:4d} segments: {error:.2e}")


if __name__ == "__main__":
    energy_drift()
    frequencies()
    seabed()
    towing_statics()
