"""Hydrodynamic databases: frequency-domain added mass, radiation damping and wave excitation
of a hull (Capytaine's NetCDF output; WAMIT's .1/.3/.hst and the HDB text format of Diodore and
AQUA+ through ``hydrodb_formats``), the retardation functions of radiation memory and Ogilvie's
relations between them.

Conventions (every database read is turned into these; written into files that carry data):

- angular frequency w [rad/s] (not period, not Hz); the earth and body frames z up;
- added mass A [kg, kg m, kg m^2] and damping B [N s/m, ...] as they are, not B/(rho w), indexed
  [force, motion] (F_i = -A_ij x''_j - B_ij x'_j), at ``reference_point`` (body frame [m]);
- excitation per metre of wave amplitude, for a wave travelling towards ``directions`` (rad,
  from +x towards +y, relative to the body's x axis), with the time dependence e^{-i w t}: a
  wave eta = a cos(k (x cos b + y sin b) - w t + p), x and y in the database's frame, gives
  F(t) = Re(X a e^{i p} e^{-i w t}) (kernels.waves's phase): X refers to the wave's phase at
  the frame's origin (Capytaine's, WAMIT's), whatever ``reference_point`` the moments are
  about (``moved`` keeps it there; ``phase_moved`` moves it);
- the retardation function K(t) = (2/pi) int_0^inf B(w) cos(w t) dw, the radiation force
  -int_0^Tc K(tau) nu(t - tau) d tau, Ogilvie: A(w) = A_inf - (1/w) int_0^inf K(t) sin(w t) dt.

B(w) is taken as linear between the database's frequencies and zero at w = 0: K(t) is then that
function's cosine transform exactly (``retardation``), whatever t. Beyond the last frequency w_N,
B is zero (``tail_power=None``), or the power tail B(w) = B(w_N) (w_N / w)^p (p = 2, 3 or 4),
whose cosine transform is added in closed form (``tail_transform``): a database cut where B is
still large then leaves no step in B, whose transform rings as B(w_N) sin(w_N t) / t.

The excitation comes in two parts, diffraction (scattering) and Froude-Krylov, or, when a source
gives only their sum (WAMIT's .3 alone, an HDB's EXCITATION section alone), as that sum
(``excitation_total``): it serves a ``diffraction`` model with ``froude_krylov: true`` only.
Each format's conventions and how they are turned into these: ``hydrodb_formats`` and
docs/conventions.md, "Vessels".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import xarray as xr
from scipy.special import sici

from seacable import files, hydrodb_formats
from seacable.errors import HydroDBError

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
TITLE = files.HYDRODB  # the title of a database seacable writes
CONVENTIONS = {
    "frequency": "angular frequency omega [rad/s]",
    "damping": "B [N s/m, N s, N m s/m, N m s/rad], not B/(rho omega)",
    "time_dependence": "exp(-i omega t)",
    "vertical_axis": "z up",
    "matrices": "[force, motion] at reference_point, body frame",
}

__all__ = [
    "CONVENTIONS", "DOFS", "HydroDB", "HydroDBError", "read", "read_capytaine",
    "tail_transform", "write",
]  # fmt: skip


@dataclass(frozen=True)
class HydroDB:
    omega: np.ndarray  # (n,) [rad/s], increasing
    added_mass: np.ndarray  # (n, 6, 6)
    damping: np.ndarray  # (n, 6, 6)
    directions: np.ndarray  # (m,) [rad], increasing
    diffraction: np.ndarray | None  # (n, m, 6) complex [N/m, N m/m]; None: only the total known
    froude_krylov: np.ndarray | None  # (n, m, 6) complex [N/m, N m/m]; None: as diffraction
    reference_point: np.ndarray  # (3,) body frame [m]
    infinite: np.ndarray | None = None  # A_inf (6, 6), when the source gives it
    rho: float = 1025.0
    gravity: float = 9.81
    depth: float = math.inf
    source: str = ""
    # (6, 6) [N/m, N, N m/m, N m/rad] at reference_point (WAMIT's .hst, an HDB's
    # Hydrostatic_matrix); read for reference, no force model uses it
    hydrostatic_stiffness: np.ndarray | None = None
    excitation_total: np.ndarray | None = None  # (n, m, 6): when the parts are not known

    def moved(self, point) -> HydroDB:
        """The database at another reference point (body frame): matrices H^T M H, forces
        H^T F (moments about the new point), H = [[I, -[r]x], [0, I]], r from the new point
        to the old. The hydrostatic stiffness is kept only when the point stays (moving it needs
        the displaced volume, which a database does not carry)."""
        r = self.reference_point - np.asarray(point, dtype=float)
        h = np.eye(6)
        h[:3, 3:] = -_cross(r)

        def force(f):
            return None if f is None else np.einsum("ji,...j->...i", h, f)

        return replace(
            self,
            added_mass=h.T @ self.added_mass @ h, damping=h.T @ self.damping @ h,
            diffraction=force(self.diffraction), froude_krylov=force(self.froude_krylov),
            excitation_total=force(self.excitation_total),
            infinite=None if self.infinite is None else h.T @ self.infinite @ h,
            hydrostatic_stiffness=self.hydrostatic_stiffness if not np.any(r) else None,
            reference_point=np.asarray(point, dtype=float),
        )  # fmt: skip

    def phase_moved(self, point, wave_number) -> HydroDB:
        """The excitation referred to the incident wave's phase at ``point`` (the database's
        frame [m]; its horizontal part counts) instead of at the frame's origin:
        X e^{-i k (x cos b + y sin b)}, ``wave_number`` k (n,) [rad/m] at the database's
        frequencies (w^2 = g k tanh(k h) of the water the body is in). The matrices stay."""
        x, y = float(point[0]), float(point[1])
        k = np.asarray(wave_number, dtype=float)[:, None, None]
        turn = np.exp(-1j * k * (x * np.cos(self.directions) + y * np.sin(self.directions))[
            None, :, None])  # fmt: skip

        def force(f):
            return None if f is None else f * turn

        return replace(
            self, diffraction=force(self.diffraction), froude_krylov=force(self.froude_krylov),
            excitation_total=force(self.excitation_total),
        )  # fmt: skip

    def retardation(self, times, tail_power: int | None = None) -> np.ndarray:
        """K(t) (len(times), 6, 6) at ``times`` [s]: the exact cosine transform of B taken
        linear between the frequencies and from zero at w = 0; beyond the last frequency w_N,
        B zero (``tail_power`` None) or B(w_N) (w_N / w)^p, p = ``tail_power`` (module
        docstring)."""
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
        if tail_power is not None:  # int_wN^inf B_N (wN / w)^p cos(w t) dw = B_N wN F_p(wN t)
            k = k + w[-1] * tail_transform(tail_power, w[-1] * t) * b[-1].reshape(1, 36)
        return (2.0 / math.pi) * k.reshape(len(t), 6, 6)

    def ogilvie(self, times, kernel=None, tail_power: int | None = None):
        """A_inf from each frequency by Ogilvie's relation with K (``retardation``'s, with
        ``tail_power``, unless ``kernel`` is given) truncated at times[-1] (``times`` uniform
        from 0 [s]): (the mean over frequencies, the estimate at each)."""
        t = np.asarray(times, dtype=float)
        k = self.retardation(t, tail_power) if kernel is None else kernel
        each = np.array([
            a + np.trapezoid(k * np.sin(w * t)[:, None, None], t, axis=0) / w
            for w, a in zip(self.omega, self.added_mass, strict=True)
        ])  # fmt: skip
        return each.mean(axis=0), each

    def added_mass_from_kernel(self, times, infinite, tail_power: int | None = None):
        """A(w) = A_inf - (1/w) int_0^T K(t) sin(w t) dt at the database's frequencies, K
        ``retardation``'s with ``tail_power``."""
        t = np.asarray(times, dtype=float)
        k = self.retardation(t, tail_power)
        return np.array([infinite - np.trapezoid(k * np.sin(w * t)[:, None, None], t, axis=0) / w
                         for w in self.omega])  # fmt: skip

    def excitation(self, froude_krylov: bool) -> np.ndarray:
        """The diffraction part, or the whole linear excitation with ``froude_krylov``
        (n, m, 6) [N/m, N m/m]; a HydroDBError when the database lacks it."""
        if self.diffraction is not None and (not froude_krylov or self.froude_krylov is not None):
            return self.diffraction + self.froude_krylov if froude_krylov else self.diffraction
        if self.excitation_total is not None:
            if froude_krylov:
                return self.excitation_total
            raise HydroDBError(
                f"hydrodynamic database '{self.source}' gives only the total excitation (Froude-"
                "Krylov included): set froude_krylov: true on the diffraction model (and no "
                "non-linear Froude-Krylov), or give the diffraction part (WAMIT .3sc, an HDB's "
                "DIFFRACTION_FORCES_AND_MOMENTS)"
            )
        if self.diffraction is None:
            raise HydroDBError(
                f"hydrodynamic database '{self.source}' has no diffraction forces (Froude-Krylov "
                "only): give a database with them (WAMIT .3 or .3sc, an HDB's "
                "DIFFRACTION_FORCES_AND_MOMENTS or EXCITATION_FORCES_AND_MOMENTS)"
            )
        raise HydroDBError(
            f"hydrodynamic database '{self.source}' has no Froude-Krylov forces: leave "
            "froude_krylov out of the diffraction model (non-linear Froude-Krylov instead)"
        )


def tail_transform(power: int, a) -> np.ndarray:
    """F_p(a) = a^(p-1) int_a^inf x^(-p) cos(x) dx [-] for p = 2, 3 or 4 and a >= 0, so that
    int_wN^inf (wN / w)^p cos(w t) dw = wN F_p(wN t); F_p(0) = 1 / (p - 1).

    Closed form: from f_1 = -Ci(a), g_1 = pi/2 - Si(a) (g_p = a^(p-1) int_a^inf x^(-p) sin x dx),
    integration by parts gives f_(q+1) = (cos a - a g_q) / q, g_(q+1) = (sin a + a f_q) / q.
    The rounding error grows as 1e-16 a^(p-2) (against F_p ~ sin(a) / a for large a): for
    p = 4, 5e-12 at a = 72 and 1e-9 at a = 360 (w_N = 6 rad/s, 60 s); p is kept to 4."""
    if power not in (2, 3, 4):
        raise ValueError(f"tail power {power}: 2, 3 or 4 are allowed")
    a = np.asarray(a, dtype=float)
    safe = np.where(a > 0.0, a, 1.0)
    si, ci = sici(safe)
    f, g = -ci, 0.5 * math.pi - si
    for q in range(1, int(power)):
        f, g = (np.cos(safe) - safe * g) / q, (np.sin(safe) + safe * f) / q
    return np.where(a > 0.0, f, 1.0 / (power - 1))


def _cross(r) -> np.ndarray:
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def read(path: str | Path, rho: float = 1025.0, gravity: float = 9.81,
         length_scale: float = 1.0, phase_unit: str = "rad") -> HydroDB:  # fmt: skip
    """A database file, by its suffix: Capytaine's NetCDF (``.nc``, ``.h5``), WAMIT's ``.1``
    (or the run's stem, or another of its files: ``.3``, ``.3sc``, ``.3fk`` and ``.hst`` are
    read beside it), an HDB file (``.hdb``, Diodore or AQUA+). WAMIT's nondimensional values are
    dimensionalised with ``rho`` [kg/m^3], ``gravity`` [m/s^2] and WAMIT's ULEN,
    ``length_scale`` [m]; ``phase_unit`` ("rad" or "deg") is the HDB file's phases' unit.
    Every format's conventions are turned into ours (module docstring; hydrodb_formats); a
    database no solver writes is refused (``checked``)."""
    return checked(_read(Path(path), rho, gravity, length_scale, phase_unit), f"hydrodynamic "
                   f"database '{path}'")  # fmt: skip


NEGATIVE = 0.01  # a diagonal below -NEGATIVE times its largest magnitude is no solver's noise


def checked(db: HydroDB, where: str) -> HydroDB:
    """``db``, or HydroDBError naming ``where`` when it is nonsense: frequencies not positive
    and increasing, values that are not finite numbers, a radiation damping that gives energy
    to the body (a negative diagonal, beyond a solver's noise: NEGATIVE of its largest), an
    added mass negative at the highest frequency (or infinite frequency)."""
    w = np.asarray(db.omega)
    if w.ndim != 1 or len(w) == 0 or not np.issubdtype(w.dtype, np.number):
        raise HydroDBError(f"{where}: no frequencies")
    if not np.all(np.isfinite(w)) or w.min() <= 0.0 or np.any(np.diff(w) <= 0.0):
        raise HydroDBError(f"{where}: its frequencies ({_listed(w)} rad/s) must be positive, "
                           "finite and increasing, each once")  # fmt: skip
    arrays = {
        "added_mass": db.added_mass,
        "radiation_damping": db.damping,
        "diffraction_force": db.diffraction,
        "Froude_Krylov_force": db.froude_krylov,
        "excitation_force": db.excitation_total,
        "added_mass_infinite": db.infinite,
    }
    for name, values in arrays.items():
        if values is None:
            continue
        a = np.asarray(values)
        if not np.issubdtype(a.dtype, np.number):
            raise HydroDBError(f"{where}: {name} holds {a.dtype} values, not numbers")
        if not np.all(np.isfinite(a)):
            k = np.argwhere(~np.isfinite(a))[0]
            at = f" at {w[k[0]]:.4g} rad/s" if a.ndim == 3 else ""
            raise HydroDBError(f"{where}: {name} is NaN or infinite{at} (index {k.tolist()}); "
                               "give the database as its solver wrote it")  # fmt: skip
    for i, dof in enumerate(DOFS):
        b = np.asarray(db.damping)[:, i, i]
        if b.min() < -NEGATIVE * np.abs(b).max():
            k = int(np.argmin(b))
            raise HydroDBError(
                f"{where}: the radiation damping of {dof} is negative at {w[k]:.4g} rad/s "
                f"({b[k]:.4g}), which would give the body energy; check the database (its "
                "sign convention, irregular frequencies of the solver)"
            )
        for name, matrix in (("at its highest frequency", np.asarray(db.added_mass)[-1]),
                             ("at infinite frequency", db.infinite)):  # fmt: skip
            if matrix is None:
                continue
            a = np.asarray(matrix)[i, i]
            if a < -NEGATIVE * np.abs(np.asarray(db.added_mass)[:, i, i]).max():
                raise HydroDBError(f"{where}: the added mass of {dof} is negative {name} "
                                   f"({a:.4g}); check the database's signs")  # fmt: skip
    return db


def _listed(values) -> str:
    shown = ", ".join(f"{v:.4g}" for v in values[:6])
    return shown + (f", ... ({len(values)} in all)" if len(values) > 6 else "")


def _read(path: Path, rho: float, gravity: float, length_scale: float,
          phase_unit: str) -> HydroDB:  # fmt: skip
    """A database file as ``read`` reads it, not yet checked."""
    stem = hydrodb_formats.wamit_stem(path)
    suffix = path.suffix.lower()
    if stem is None and not path.exists():
        raise HydroDBError(f"hydrodynamic database '{path}' does not exist; check the path")
    if suffix in (".nc", ".h5", ".netcdf"):
        return read_capytaine(path)
    if stem is not None:
        fields = hydrodb_formats.read_wamit(stem, rho, gravity, length_scale)
    elif suffix == ".hdb":
        fields = hydrodb_formats.read_hdb(path, rho, gravity, phase_unit)
    else:
        raise HydroDBError(
            f"hydrodynamic database '{path}': format '{path.suffix}' is not known; give "
            "Capytaine's NetCDF (.nc), WAMIT's .1 (with .3 and .hst beside it) or an HDB "
            "file (.hdb)"
        )
    return HydroDB(**_parts(fields))


def _parts(fields: dict) -> dict:
    """The excitation's diffraction and Froude-Krylov parts, the missing one from the total
    when two of the three are known; the total kept only when the parts are not."""
    total, diffraction, fk = (fields[k] for k in ("excitation_total", "diffraction",
                                                  "froude_krylov"))  # fmt: skip
    if total is not None and diffraction is not None and fk is None:
        fk = total - diffraction
    elif total is not None and fk is not None and diffraction is None:
        diffraction = total - fk
    if diffraction is not None and fk is not None:
        total = None
    return {**fields, "excitation_total": total, "diffraction": diffraction, "froude_krylov": fk}


def read_capytaine(path: str | Path) -> HydroDB:
    """Capytaine's NetCDF (``capytaine.export_dataset(..., format="netcdf")``, complex values
    split along a ``complex`` dimension, or xarray's own): added_mass and radiation_damping
    (omega, influenced_dof, radiating_dof), diffraction_force and Froude_Krylov_force (omega,
    wave_direction, influenced_dof) or their sum excitation_force, rotation_center,
    hydrostatic_stiffness when there. Capytaine's frame is z up and its time dependence
    e^{-i w t}: both ours."""
    files.regular_file(path, "hydrodynamic database", HydroDBError)
    files.self_contained(path)
    try:
        ds = xr.open_dataset(path)
    except (OSError, ValueError) as exc:
        raise HydroDBError(
            f"hydrodynamic database '{path}' is not readable NetCDF: {exc}"
        ) from None
    with ds:
        missing = [v for v in ("added_mass", "radiation_damping") if v not in ds]
        if not any(v in ds for v in ("diffraction_force", "Froude_Krylov_force",
                                     "excitation_force")):  # fmt: skip
            missing.append("diffraction_force")
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
            if name not in ds:
                return None
            v = ds[name]
            if "complex" in v.dims:
                v = v.sel(complex="re") + 1j * v.sel(complex="im")
            return np.asarray(v.transpose("omega", "wave_direction", "influenced_dof").values)

        infinite = None
        if "added_mass_infinite" in ds:
            infinite = ds["added_mass_infinite"].transpose("influenced_dof", "radiating_dof").values
        stiffness = None
        if "hydrostatic_stiffness" in ds:
            stiffness = ds["hydrostatic_stiffness"].transpose(
                "influenced_dof", "radiating_dof").values  # fmt: skip
        centre = ds.coords.get("rotation_center")
        depth = float(ds.coords["water_depth"]) if "water_depth" in ds.coords else math.inf
        return HydroDB(**_parts(dict(
            omega=np.asarray(ds.coords["omega"].values, dtype=float),
            added_mass=matrix("added_mass"), damping=matrix("radiation_damping"),
            directions=np.asarray(ds.coords["wave_direction"].values, dtype=float),
            diffraction=force("diffraction_force"), froude_krylov=force("Froude_Krylov_force"),
            excitation_total=force("excitation_force"),
            reference_point=np.zeros(3) if centre is None else np.asarray(centre.values, float),
            rho=float(ds.coords["rho"]) if "rho" in ds.coords else 1025.0,
            gravity=float(ds.coords["g"]) if "g" in ds.coords else 9.81,
            depth=depth, source=f"capytaine:{path}", infinite=infinite,
            hydrostatic_stiffness=stiffness,
        )))  # fmt: skip


def write(db: HydroDB, path: str | Path) -> None:
    """A database as NetCDF in Capytaine's layout (complex values split along ``complex``),
    with seacable's conventions in its attributes (``CONVENTIONS``); the excitation's parts,
    or their sum (``excitation_force``) when only that is known."""
    dofs = list(DOFS)
    coords = {"omega": db.omega, "influenced_dof": dofs, "radiating_dof": dofs,
              "wave_direction": db.directions, "complex": ["re", "im"],
              "space_coordinate": ["x", "y", "z"]}  # fmt: skip

    def split(force):
        return (("complex", "omega", "wave_direction", "influenced_dof"),
                np.stack([force.real, force.imag]))  # fmt: skip

    matrix = ("omega", "influenced_dof", "radiating_dof")
    forces = {name: split(f) for name, f in (("diffraction_force", db.diffraction),
                                             ("Froude_Krylov_force", db.froude_krylov),
                                             ("excitation_force", db.excitation_total))
              if f is not None}  # fmt: skip
    ds = xr.Dataset(
        {"added_mass": (matrix, db.added_mass), "radiation_damping": (matrix, db.damping),
         **forces},
        coords={**coords, "rotation_center": ("space_coordinate", db.reference_point),
                "rho": db.rho, "g": db.gravity, "water_depth": db.depth},
        attrs={**CONVENTIONS, "source": db.source or "seacable"},
    )  # fmt: skip
    if db.infinite is not None:
        ds["added_mass_infinite"] = (("influenced_dof", "radiating_dof"), db.infinite)
    if db.hydrostatic_stiffness is not None:
        ds["hydrostatic_stiffness"] = (("influenced_dof", "radiating_dof"),
                                       db.hydrostatic_stiffness)  # fmt: skip
    ds.attrs["title"] = TITLE
    with files.replacing(path) as aside:
        ds.to_netcdf(aside, engine="h5netcdf")
