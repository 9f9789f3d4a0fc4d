"""A body's hull: its mesh read, placed in its body frame and checked (``seacable.meshes``),
the row the mesh force models carry (kernels.hull); its hydrodynamic database moved to its
reference point (``seacable.hydrodb``), the rows of radiation memory (kernels.memory) and its
infinite-frequency added mass."""

import logging
import math
from dataclasses import dataclass, replace

import numpy as np

from seacable import hydrodb, packing, realization, seastate
from seacable.bodies import kinematics
from seacable.case.document import Z_DOWN  # a z-down body frame (y to starboard) to ours
from seacable.case.forces import RadiationDamping
from seacable.errors import CaseError
from seacable.forces import diffraction, radiation
from seacable.forces.kinds import RADIATION_DAMPING
from seacable.kernels import memory, waves
from seacable.meshes import Mesh, MeshError, checked, hydrostatics, read
from seacable.packing import transported

log = logging.getLogger("seacable")
TAIL = 0.01  # a retardation function above this part of its peak at the cut-off is reported


def _matrix(angles_deg) -> np.ndarray:
    out = np.zeros((3, 3))
    kinematics.rotation(*kinematics.euler_quaternion(*(math.radians(a) for a in angles_deg)),
                        out)  # fmt: skip
    return out


def body_mesh(body, base_dir, where: str) -> Mesh:
    """The mesh of ``body`` in its body frame [m] (vertices relative to its reference point),
    wound outward, checked closed below the still-water surface at the body's start pose: a
    CaseError naming ``where`` (the body) otherwise."""
    spec = body.mesh
    try:
        mesh = read(spec.path(base_dir), spec.format)
    except MeshError as exc:
        raise CaseError(f"{where}.mesh.file: {exc}") from None
    turn = _matrix(spec.orientation_deg)
    if spec.axes == "z_down":
        turn = turn @ Z_DOWN
    mesh = mesh.moved(spec.position, turn, spec.scale)
    try:
        return checked(mesh, body.position, _matrix(body.orientation_deg),
                       where=f"{where}.mesh ({spec.file})")  # fmt: skip
    except MeshError as exc:
        raise CaseError(str(exc)) from None


def document_added_mass(body, base_dir, where: str, rho: float) -> tuple[np.ndarray, str]:
    """The added mass of the ship-simulator document's ``dynamics`` block at the body's
    reference point, in seacable's body frame: turned from the document's z-down body frame
    (T A T, T = diag(Z_DOWN, Z_DOWN): a half turn about x, proper, so that angular motions
    turn as linear ones) and moved from the centre of buoyancy: the body's
    ``centre_of_buoyancy``, or the still-water one of its mesh (``still_water``), whatever
    pose the body starts in. Returns the matrix and a line saying which point was used."""
    added = body.dynamics.added_mass.turned()
    if "centre_of_buoyancy" in body.model_fields_set:
        centre = np.asarray(body.centre_of_buoyancy, dtype=float)
        how = "the body's centre_of_buoyancy"
    else:
        floating = still_water(body_mesh(body, base_dir, where), body.mass, rho,
                               body.centre_of_gravity, where)  # fmt: skip
        centre = floating.centre_of_buoyancy
        how = (
            "the still-water centre of buoyancy of its mesh (the hull at rest in calm water, "
            f"carrying its weight: reference point at z = {floating.height:.6g} m, roll "
            f"{floating.roll_deg:.6g} deg, pitch {floating.pitch_deg:.6g} deg)"
        )
    note = f"{body.name}: [{', '.join(f'{c:.10g}' for c in centre)}] m, body frame, {how}"
    log.info("%s: the document's added mass is moved from %s", where, note)
    return transported(added, centre), note


@dataclass(frozen=True)
class Floating:
    """A hull at rest in calm water: its reference point's height [m], its roll and pitch
    [deg] (yaw and the horizontal position do not matter), its centre of buoyancy in the body
    frame [m]."""

    height: float
    roll_deg: float
    pitch_deg: float
    centre_of_buoyancy: np.ndarray


FLOAT_TOLERANCE = 1e-12  # relative: buoyancy and weight, and their lever arms, balanced to this


def still_water(mesh: Mesh, mass: float, rho: float, cog, where: str) -> Floating:
    """The hull ``mesh`` floating free in calm water with the weight of ``mass`` [kg] at
    ``cog`` (body frame [m]): the displaced volume mass / rho, the centre of buoyancy on the
    centre of gravity's vertical (buoyancy and weight balance, so do their moments), its heave,
    roll and pitch by Newton's method from upright at the draft that floats it (the
    equilibrium nearest to upright). A CaseError naming ``where`` when the hull cannot float
    with that mass or no equilibrium is found."""
    if mass <= 0.0:
        raise CaseError(f"{where}: the document's added mass is at the still-water centre of "
                        f"buoyancy, where the hull floats carrying its weight, and its mass is "
                        f"{mass:g} kg; give the mass, or 'centre_of_buoyancy'")  # fmt: skip
    volume = mass / rho
    size = float(np.ptp(mesh.vertices, axis=0).max())
    gravity_centre = np.asarray(cog, dtype=float)

    def residual(state):
        height, roll, pitch = state
        rotation = _matrix((math.degrees(roll), math.degrees(pitch), 0.0))
        stat = hydrostatics(mesh, (0.0, 0.0, height), rotation)
        arm = stat.volume * np.asarray(stat.centre_of_buoyancy) - volume * (
            rotation @ gravity_centre
        )
        return np.array([stat.volume / volume - 1.0, *(arm[:2] / (volume * size))]), stat, rotation

    state = np.array([_upright_height(mesh, volume, where), 0.0, 0.0])
    steps = np.array([1e-6 * size, 1e-6, 1e-6])
    for _ in range(60):
        r, stat, rotation = residual(state)
        if np.abs(r).max() <= FLOAT_TOLERANCE:
            return Floating(float(state[0]), math.degrees(state[1]), math.degrees(state[2]),
                            rotation.T @ np.asarray(stat.centre_of_buoyancy))  # fmt: skip
        jacobian = np.column_stack([(residual(state + np.eye(3)[k] * steps[k])[0] - r) / steps[k]
                                    for k in range(3)])  # fmt: skip
        move = np.linalg.lstsq(jacobian, -r, rcond=None)[0]
        limit = max(np.abs(move[1:]).max() / 0.2, abs(move[0]) / (0.1 * size), 1.0)
        state = state + move / limit
    raise CaseError(f"{where}: no still-water equilibrium of the hull near upright was found "
                    f"(buoyancy and weight still off by {np.abs(r).max():.3g} after 60 Newton "
                    "steps), for the document's added mass; check the mesh, the mass and the "
                    "centre of gravity, or give 'centre_of_buoyancy'")  # fmt: skip


def _upright_height(mesh: Mesh, volume: float, where: str) -> float:
    """The height of the reference point at which the upright hull displaces ``volume``
    [m^3] (bisection: the displaced volume falls as the hull rises)."""
    low, high = -float(mesh.vertices[:, 2].max()), -float(mesh.vertices[:, 2].min())
    submerged = hydrostatics(mesh, (0.0, 0.0, low))
    if not submerged.closed():
        raise CaseError(f"{where}: the hull is open above its waterline, and seacable finds the "
                        "still-water draft of a closed hull only (the document's added mass is "
                        "at the still-water centre of buoyancy); close the mesh, or give "
                        "'centre_of_buoyancy'")  # fmt: skip
    most = submerged.volume
    if most < volume:
        raise CaseError(f"{where}: the hull displaces {most:.6g} m^3 wholly submerged and its "
                        f"weight needs {volume:.6g} m^3: it cannot float, and the document's "
                        "added mass is at the still-water centre of buoyancy; check the mass "
                        "and the mesh's scale, or give 'centre_of_buoyancy'")  # fmt: skip
    for _ in range(60):
        middle = 0.5 * (low + high)
        if hydrostatics(mesh, (0.0, 0.0, middle)).volume > volume:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


def body_database(body, base_dir, where: str, environment) -> hydrodb.HydroDB:
    """The body's hydrodynamic database moved to its reference point, its excitation referred
    to the wave's phase there (forces.diffraction takes the phase at the reference point; the
    database's origin is at ``position`` in the body frame), a nondimensional one (WAMIT's) made
    dimensional with the ``environment``'s water density and gravity; or a CaseError naming
    ``where``."""
    spec = body.hydrodynamics
    try:
        db = hydrodb.read(spec.path(base_dir), environment.water_density, environment.gravity,
                          spec.length_scale, spec.phase_unit)  # fmt: skip
    except hydrodb.HydroDBError as exc:
        raise CaseError(f"{where}.hydrodynamics.file: {exc}") from None
    origin = np.asarray(spec.position, float)
    db = replace(db, reference_point=db.reference_point + origin)
    if np.any(origin[:2]):
        depth = environment.water_depth or waves.DEEP
        db = db.phase_moved(-origin, seastate.wave_number(db.omega, depth, environment.gravity))
    return db.moved((0.0, 0.0, 0.0))


def radiation_row(db: hydrodb.HydroDB, spec, where: str) -> list[float]:
    """forces.radiation's row: K sampled every ``spec.memory_step`` over ``spec.memory``
    seconds, convolved (kernels.memory's row, its history block's offset set by
    ``memory_offsets``) or fitted by state spaces (``state_space_entries``); a kernel above 1 %
    of its peak at the cut-off is reported."""
    if len(db.omega) < 2:
        raise CaseError(f"{where}: the radiation memory's retardation function is made from the "
                        f"damping over frequencies, at least two, and {_named(db)} has one "
                        f"({db.omega[0]:.6g} rad/s); give one computed at many (30 or more, to the "
                        "damping's decay: seacable hydrodb --omega FIRST LAST COUNT)")  # fmt: skip
    count = int(round(spec.memory / spec.memory_step)) + 1
    times = np.arange(count) * spec.memory_step
    k = db.retardation(times, tail_power(spec))
    peak = np.abs(k).max()
    tail = np.abs(k[-1]).max()
    if peak > 0.0 and tail > TAIL * peak:
        log.warning(
            "%s: the retardation function is still %.1f %% of its peak at the cut-off "
            "(memory %.4g s); lengthen 'memory' or check the database's frequencies",
            where, 100 * tail / peak, spec.memory,
        )  # fmt: skip
    if spec.method == "state_space":
        return radiation.pack_state_space(state_space_entries(times, k, spec, where))
    return radiation.pack_convolution(count, spec.memory_step, k)


def state_space_entries(times, kernel, spec, where: str) -> list:
    """(i, j, A, B, C) of every non-negligible entry of ``kernel`` (len(times), 6, 6) fitted
    within ``spec.tolerance`` with at most ``spec.order`` states (seacable.realization); an
    entry whose fit stays above the tolerance is reported with its error."""
    fits = realization.fit_matrix(times, kernel, spec.order, spec.tolerance)
    for (i, j), fit in fits.items():
        if fit.error > spec.tolerance:
            log.warning(
                "%s: the state space of K_%s%s (%s on %s) fits it within %.2g %% only with %d "
                "states (tolerance %.2g %%); raise 'order' or 'tolerance', or use 'method: "
                "convolution'", where, i + 1, j + 1, hydrodb.DOFS[i], hydrodb.DOFS[j],
                100 * fit.error, fit.order, 100 * spec.tolerance,
            )  # fmt: skip
    return [(i, j, fit.a, fit.b, fit.c) for (i, j), fit in fits.items()]


def tail_power(spec) -> int | None:
    """The power p of the damping's tail beyond the database's frequencies (hydrodb), or None
    (no tail) for a ``radiation damping`` model ``spec``."""
    return spec.tail_power if spec.high_frequency_tail == "power" else None


def infinite_added_mass(db: hydrodb.HydroDB, memory: float, step: float,
                        tail: int | None = None) -> np.ndarray:  # fmt: skip
    """A_inf: the database's (a solver's, seacable hydrodb's), or Ogilvie's estimate with K
    (its damping's tail of power ``tail``, or none) over ``memory`` seconds sampled every
    ``step`` [s]; a HydroDBError for a database of one frequency without it."""
    if db.infinite is not None:
        return db.infinite
    if len(db.omega) < 2:
        raise hydrodb.HydroDBError(
            f"{_named(db)} has no added mass at infinite frequency, and Ogilvie's relation "
            f"cannot estimate it from one frequency ({db.omega[0]:.6g} rad/s); give the body's "
            "added_mass, or a database with added_mass_infinite (seacable hydrodb writes it) or "
            "computed at many frequencies"
        )
    times = np.arange(int(round(memory / step)) + 1) * step
    return db.ogilvie(times, tail_power=tail)[0]


def database_row(case, body, spec, base_dir, where: str) -> list[float]:
    """The row of a database force model (``radiation damping``: kernels.memory's, its
    history block's offset set by ``memory_offsets``; ``diffraction``: forces.diffraction's
    for the case's wave components)."""
    db = body_database(body, base_dir, where.split(".")[0], case.environment)
    if spec.model == "radiation damping":
        if case.simulation.integrator == "cvode" and spec.method == "convolution":
            raise CaseError(
                f"{where}: radiation memory is recorded after each accepted step, and SUNDIALS "
                "keeps its steps to itself; use method: state_space, or integrator bdf, radau, "
                "dopri5, rk4 or an implicit scheme"
            )
        return radiation_row(db, spec, where)
    wave = packing.wave_fields(case.environment, case.simulation.build_up)["wave"]
    try:
        return diffraction.pack(at_one_frequency(db, wave[waves.W]), wave, spec.froude_krylov)
    except hydrodb.HydroDBError as exc:
        raise CaseError(f"{where}: {exc}") from None


ONE_FREQUENCY = 1e-4  # relative: a wave this close to a one-frequency database's is at it


def at_one_frequency(db: hydrodb.HydroDB, omega) -> hydrodb.HydroDB:
    """A database of several frequencies as it is; one of one frequency w0 serving waves at
    w0 (``omega`` [rad/s], within ONE_FREQUENCY of it) as the same values at w0 (1 -+
    ONE_FREQUENCY), between which forces.diffraction interpolates; a HydroDBError naming the
    waves' frequencies otherwise (forces.diffraction would give them no force)."""
    if len(db.omega) > 1:
        return db
    w0 = float(db.omega[0])
    off = np.asarray(omega, dtype=float)[np.abs(np.asarray(omega) / w0 - 1.0) > ONE_FREQUENCY]
    if len(off):
        shown = ", ".join(f"{w:.6g}" for w in off[:4]) + (", ..." if len(off) > 4 else "")
        raise hydrodb.HydroDBError(
            f"{_named(db)} holds one frequency, {w0:.6g} rad/s (period "
            f"{2 * math.pi / w0:.10g} s), and the waves have components at {shown} rad/s, "
            "whose excitation it cannot give; use regular waves of that period, or a database "
            "computed over the waves' frequencies (seacable hydrodb --omega FIRST LAST COUNT)"
        )

    def twice(values):
        return None if values is None else np.repeat(values, 2, axis=0)

    return replace(
        db, omega=w0 * np.array([1.0 - ONE_FREQUENCY, 1.0 + ONE_FREQUENCY]),
        added_mass=twice(db.added_mass), damping=twice(db.damping),
        diffraction=twice(db.diffraction), froude_krylov=twice(db.froude_krylov),
        excitation_total=twice(db.excitation_total),
    )  # fmt: skip


def _named(db: hydrodb.HydroDB) -> str:
    """The database by its file (its ``source``: "format:path")."""
    return f"hydrodynamic database '{db.source.split(':', 1)[-1]}'"


def database_added_mass(body, base_dir, where: str, environment) -> np.ndarray:
    """A_inf of the body's database, for a body with a database and no added mass (a
    CaseError naming the file when it has neither A_inf nor the frequencies to estimate it)."""
    radiation = [f for f in body.external_forces if f.model == "radiation damping"]
    spec = radiation[0] if radiation else RadiationDamping(model="radiation damping")
    try:
        return infinite_added_mass(body_database(body, base_dir, where, environment),
                                   spec.memory, spec.memory_step, tail_power(spec))  # fmt: skip
    except hydrodb.HydroDBError as exc:
        raise CaseError(f"{where}.hydrodynamics.file: {exc}") from None


def memory_offsets(kinds_: list[int], at: list[int], data: list[float]) -> None:
    """Each radiation convolution's history block laid out after the one before
    (kernels.memory)."""
    offset = memory.SCRATCH
    for kind, first in zip(kinds_, at, strict=True):
        if kind == RADIATION_DAMPING and radiation.uses_history(data[first : first + 1]):
            row = first + radiation.MEMORY
            data[row + 2] = float(offset)
            offset += memory.block_size(int(data[row]))
