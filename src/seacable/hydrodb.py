"""Hydrodynamic databases: frequency-domain added mass, radiation damping and wave excitation
of a hull (from Capytaine's NetCDF output), the retardation functions of radiation memory and
Ogilvie's relations between them.

Conventions (every database read is turned into these; written into files that carry data):

- angular frequency w [rad/s] (not period, not Hz); the earth and body frames z up;
- added mass A [kg, kg m, kg m^2] and damping B [N s/m, ...] as they are, not B/(rho w), indexed
  [force, motion] (F_i = -A_ij x''_j - B_ij x'_j), at ``reference_point`` (body frame [m]);
- excitation per metre of wave amplitude, for a wave travelling towards ``directions`` (rad,
  from +x towards +y, relative to the body's x axis), with the time dependence e^{-i w t}: a
  wave eta = a cos(k (x cos b + y sin b) - w t + p) at the reference point's place gives
  F(t) = Re(X a e^{i p} e^{-i w t}) (kernels.waves's phase);
- the retardation function K(t) = (2/pi) int_0^inf B(w) cos(w t) dw, the radiation force
  -int_0^Tc K(tau) nu(t - tau) d tau, Ogilvie: A(w) = A_inf - (1/w) int_0^inf K(t) sin(w t) dt.

B(w) is taken as linear between the database's frequencies and zero at w = 0: K(t) is then that
function's cosine transform exactly (``retardation``), whatever t.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import xarray as xr

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
CONVENTIONS = {
    "frequency": "angular frequency omega [rad/s]",
    "damping": "B [N s/m, N s, N m s/m, N m s/rad], not B/(rho omega)",
    "time_dependence": "exp(-i omega t)",
    "vertical_axis": "z up",
    "matrices": "[force, motion] at reference_point, body frame",
}


class HydroDBError(ValueError):
    """A database that cannot be read or used: the message says why and what to do."""


@dataclass(frozen=True)
class HydroDB:
    omega: np.ndarray  # (n,) [rad/s], increasing
    added_mass: np.ndarray  # (n, 6, 6)
    damping: np.ndarray  # (n, 6, 6)
    directions: np.ndarray  # (m,) [rad], increasing
    diffraction: np.ndarray  # (n, m, 6) complex [N/m, N m/m]
    froude_krylov: np.ndarray  # (n, m, 6) complex
    reference_point: np.ndarray  # (3,) body frame [m]
    infinite: np.ndarray | None = None  # A_inf (6, 6), when the source gives it
    rho: float = 1025.0
    gravity: float = 9.81
    depth: float = math.inf
    source: str = ""

    def moved(self, point) -> HydroDB:
        """The database at another reference point (body frame): matrices H^T M H, forces
        H^T F (moments about the new point), H = [[I, -[r]x], [0, I]], r from the new point
        to the old."""
        r = self.reference_point - np.asarray(point, dtype=float)
        h = np.eye(6)
        h[:3, 3:] = -_cross(r)
        forces = np.einsum("ji,...j->...i", h, self.diffraction)
        return replace(
            self,
            added_mass=h.T @ self.added_mass @ h, damping=h.T @ self.damping @ h,
            diffraction=forces, froude_krylov=np.einsum("ji,...j->...i", h, self.froude_krylov),
            infinite=None if self.infinite is None else h.T @ self.infinite @ h,
            reference_point=np.asarray(point, dtype=float),
        )  # fmt: skip

    def retardation(self, times) -> np.ndarray:
        """K(t) (len(times), 6, 6): the exact cosine transform of B taken linear between the
        frequencies and from zero at w = 0."""
        w = np.concatenate([[0.0], self.omega]) if self.omega[0] > 0.0 else self.omega
        b = self.damping
        if self.omega[0] > 0.0:
            b = np.concatenate([np.zeros((1, 6, 6)), b])
        t = np.asarray(times, dtype=float)[:, None]
        slope = np.diff(b, axis=0) / np.diff(w)[:, None, None]  # (segments, 6, 6)
        safe = np.where(t == 0.0, 1.0, t)
        # int over a segment of (b0 + s (w - w0)) cos(w t) dw, summed by parts:
        # [B sin(w t) / t]_ends + sum_s s (cos(w1 t) - cos(w0 t)) / t^2
        ends = (np.sin(w[-1] * safe) * b[-1].reshape(1, 36) - np.sin(w[0] * safe) * b[0].reshape(
            1, 36)) / safe  # fmt: skip
        cos = np.cos(w[None, :] * safe)  # (nt, n)
        parts = (np.diff(cos, axis=1) @ slope.reshape(-1, 36)) / safe**2
        k = ends + parts
        trapezoid = np.trapezoid(b.reshape(len(w), 36), w, axis=0)
        k = np.where(t == 0.0, trapezoid[None, :], k)
        return (2.0 / math.pi) * k.reshape(len(t), 6, 6)

    def ogilvie(self, times, kernel=None):
        """A_inf from each frequency by Ogilvie's relation with K truncated at times[-1]
        (``times`` uniform from 0): (the mean over frequencies, the estimate at each)."""
        t = np.asarray(times, dtype=float)
        k = self.retardation(t) if kernel is None else kernel
        each = np.array([
            a + np.trapezoid(k * np.sin(w * t)[:, None, None], t, axis=0) / w
            for w, a in zip(self.omega, self.added_mass, strict=True)
        ])  # fmt: skip
        return each.mean(axis=0), each

    def added_mass_from_kernel(self, times, infinite) -> np.ndarray:
        """A(w) = A_inf - (1/w) int_0^T K(t) sin(w t) dt at the database's frequencies."""
        t = np.asarray(times, dtype=float)
        k = self.retardation(t)
        return np.array([infinite - np.trapezoid(k * np.sin(w * t)[:, None, None], t, axis=0) / w
                         for w in self.omega])  # fmt: skip

    def excitation(self, froude_krylov: bool) -> np.ndarray:
        return self.diffraction + self.froude_krylov if froude_krylov else self.diffraction


def _cross(r) -> np.ndarray:
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def read(path: str | Path) -> HydroDB:
    """A database file: Capytaine's NetCDF (``.nc``)."""
    path = Path(path)
    if not path.exists():
        raise HydroDBError(f"hydrodynamic database '{path}' does not exist")
    if path.suffix.lower() not in (".nc", ".h5", ".netcdf"):
        raise HydroDBError(
            f"hydrodynamic database '{path}': format '{path.suffix}' is not known; give "
            "Capytaine's NetCDF output (.nc)"
        )
    return read_capytaine(path)


def read_capytaine(path: str | Path) -> HydroDB:
    """Capytaine's NetCDF (``capytaine.export_dataset(..., format="netcdf")``, complex values
    split along a ``complex`` dimension, or xarray's own): added_mass and radiation_damping
    (omega, influenced_dof, radiating_dof), diffraction_force and Froude_Krylov_force (omega,
    wave_direction, influenced_dof), rotation_center. Capytaine's frame is z up and its time
    dependence e^{-i w t}: both ours."""
    try:
        ds = xr.open_dataset(path)
    except (OSError, ValueError) as exc:
        raise HydroDBError(
            f"hydrodynamic database '{path}' is not readable NetCDF: {exc}"
        ) from None
    with ds:
        missing = [v for v in ("added_mass", "radiation_damping", "diffraction_force",
                               "Froude_Krylov_force") if v not in ds]  # fmt: skip
        if missing or "omega" not in ds.coords:
            raise HydroDBError(
                f"hydrodynamic database '{path}' lacks {missing or ['omega']}: solve radiation "
                "and diffraction problems for the six rigid-body motions (seacable hydrodb)"
            )
        dofs = [str(d) for d in ds.coords["radiating_dof"].values]
        if sorted(dofs) != sorted(DOFS):
            raise HydroDBError(f"hydrodynamic database '{path}': degrees of freedom {dofs}; the "
                               f"six rigid-body ones are needed {list(DOFS)}")  # fmt: skip
        order = {"radiating_dof": list(DOFS), "influenced_dof": list(DOFS)}
        ds = ds.sel(order).sortby("omega").sortby("wave_direction")

        def matrix(name):
            return ds[name].transpose("omega", "influenced_dof", "radiating_dof").values

        def force(name):
            v = ds[name]
            if "complex" in v.dims:
                v = v.sel(complex="re") + 1j * v.sel(complex="im")
            return np.asarray(v.transpose("omega", "wave_direction", "influenced_dof").values)

        infinite = None
        if "added_mass_infinite" in ds:
            infinite = ds["added_mass_infinite"].transpose("influenced_dof", "radiating_dof").values
        centre = ds.coords.get("rotation_center")
        depth = float(ds.coords["water_depth"]) if "water_depth" in ds.coords else math.inf
        return HydroDB(
            omega=np.asarray(ds.coords["omega"].values, dtype=float),
            added_mass=matrix("added_mass"), damping=matrix("radiation_damping"),
            directions=np.asarray(ds.coords["wave_direction"].values, dtype=float),
            diffraction=force("diffraction_force"), froude_krylov=force("Froude_Krylov_force"),
            reference_point=np.zeros(3) if centre is None else np.asarray(centre.values, float),
            rho=float(ds.coords["rho"]) if "rho" in ds.coords else 1025.0,
            gravity=float(ds.coords["g"]) if "g" in ds.coords else 9.81,
            depth=depth, source=f"capytaine:{path}", infinite=infinite,
        )  # fmt: skip


def write(db: HydroDB, path: str | Path) -> None:
    """A database as NetCDF in Capytaine's layout (complex values split along ``complex``),
    with seacable's conventions in its attributes (``CONVENTIONS``)."""
    dofs = list(DOFS)
    coords = {"omega": db.omega, "influenced_dof": dofs, "radiating_dof": dofs,
              "wave_direction": db.directions, "complex": ["re", "im"],
              "space_coordinate": ["x", "y", "z"]}  # fmt: skip

    def split(force):
        return (("complex", "omega", "wave_direction", "influenced_dof"),
                np.stack([force.real, force.imag]))  # fmt: skip

    matrix = ("omega", "influenced_dof", "radiating_dof")
    ds = xr.Dataset(
        {"added_mass": (matrix, db.added_mass), "radiation_damping": (matrix, db.damping),
         "diffraction_force": split(db.diffraction),
         "Froude_Krylov_force": split(db.froude_krylov)},
        coords={**coords, "rotation_center": ("space_coordinate", db.reference_point),
                "rho": db.rho, "g": db.gravity, "water_depth": db.depth},
        attrs={**CONVENTIONS, "source": db.source or "seacable"},
    )  # fmt: skip
    if db.infinite is not None:
        ds["added_mass_infinite"] = (("influenced_dof", "radiating_dof"), db.infinite)
    ds.to_netcdf(path, engine="h5netcdf")
