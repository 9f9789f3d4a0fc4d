"""Validated case parts turned into the flat arrays compiled code reads: the current profile,
a body's shape row (kernels.surface), time-function channels, parameter tuples of exact types."""

import math
import typing
from typing import Any

import numpy as np

from seacable import seastate
from seacable import timefunctions as tfn
from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import surface, waves


def current_arrays(env: schema.Environment):
    """Current profile as (z, u, v) arrays [m, m/s, m/s]; zero current in air."""
    if env.current is None or env.in_air:
        return np.zeros(1), np.zeros(1), np.zeros(1)
    z, speed = env.current.arrays()
    heading = math.radians(env.current.direction_deg)
    return z, speed * math.cos(heading), speed * math.sin(heading)


def wave_fields(env: schema.Environment, build_up: float = 0.0) -> dict:
    """The incident waves' SystemParams fields: every wave's components (seastate), raised
    over ``build_up`` [s] (the simulation's), in one table (kernels.waves.table), the depth
    they feel and the stretching."""
    depth = env.water_depth or waves.DEEP
    rows = [seastate.components(wave, depth, env.gravity, build_up) for wave in env.waves]
    table = waves.table(np.concatenate(rows) if rows else np.zeros((0, waves.GIVEN)), depth)
    stretch = waves.WHEELER if env.wave_stretching == "wheeler" else waves.VERTICAL
    return {"wave": table, "wave_depth": float(depth), "wave_stretch": stretch}


def channel(spec, base_dir, where: str) -> tfn.Piecewise:
    """Compile a time function; a table that cannot be read becomes a CaseError naming it."""
    try:
        return tfn.build(spec, base_dir)
    except ValueError as exc:
        raise CaseError(f"{where}: {exc}") from None


def typed(cls, fields: dict, int_arrays: frozenset[str] = frozenset()):
    """An instance of the NamedTuple ``cls`` with every field of the exact type its compiled
    kernels were built for (a float given as an int would trigger a new compilation): the
    arrays named in ``int_arrays`` (and ``tf_count``) int64, the other arrays float64."""
    out: dict[str, Any] = {}
    for name, annotation in typing.get_type_hints(cls).items():
        value = fields[name]
        if annotation is int:
            out[name] = int(value)
        elif annotation is float:
            out[name] = float(value)
        elif name == "tf_count" or name in int_arrays:
            out[name] = np.ascontiguousarray(value, dtype=np.int64)
        else:
            out[name] = np.ascontiguousarray(value, dtype=np.float64)
    return cls(**out)


def shape_row(shape, width: int) -> np.ndarray:
    """The kernels' shape row (kernels.surface) of a schema shape (None: a point volume)."""
    row = surface.point_row(width)
    if isinstance(shape, schema.Sphere):
        row[:2] = (surface.SPHERE, shape.radius)
    elif isinstance(shape, schema.VerticalCylinder):
        row[:3] = (surface.CYLINDER, shape.radius, shape.height)
    elif isinstance(shape, schema.VolumeTable):
        table = np.array(shape.submerged_volume, dtype=float)
        count = len(table)
        row[:4] = (surface.TABLE, 0.0, 0.0, count)
        row[surface.HEADER : surface.HEADER + count] = table[:, 0]
        row[surface.HEADER + count : surface.HEADER + 2 * count] = table[:, 1] / table[0, 1]
    return row


def transported(matrix: np.ndarray, point) -> np.ndarray:
    """A 6x6 matrix (added mass, damping) expressed at ``point`` (body frame, from the
    reference point; None: at the reference point) moved to the reference point: H^T A H, with
    H = [[I, -[r]], [0, I]] the map from the reference point's (v, w) to the point's velocity
    v + w x r and the same w (a stiffness needs more: the moments of the forces' own
    displacements)."""
    if point is None or not any(point):
        return np.array(matrix, dtype=float)
    rx, ry, rz = point
    h = np.eye(6)
    h[:3, 3:] = -np.array([[0.0, -rz, ry], [rz, 0.0, -rx], [-ry, rx, 0.0]])
    return h.T @ np.asarray(matrix, dtype=float) @ h
