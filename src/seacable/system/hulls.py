"""A body's hull mesh read, placed in its body frame and checked (``seacable.meshes``): the
row the mesh force models carry (kernels.hull)."""

import math

import numpy as np

from seacable.bodies import kinematics
from seacable.errors import CaseError
from seacable.meshes import Mesh, MeshError, checked, read

Z_DOWN = np.diag([1.0, -1.0, -1.0])  # a z-down body frame (x, y to starboard, z down) to ours


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
