"""The contract of the body kinds, as Protocols with their rules (``tests/test_contracts.py``
checks ``bodies.kinematics`` and ``bodies.dynamics`` against them, rules included,
numerically). A body's kind (``kinematics.FIXED``, ``IMPOSED``, ``DYNAMIC``, ``TIP``) is a
value the compiled functions branch on, not a module: a new kind is a new value with a branch
in each function below, under these rules."""

from collections.abc import Callable
from typing import Any, Protocol, runtime_checkable


@runtime_checkable
class BodyKinematics(Protocol):
    """Where every body and point is (``bodies.kinematics``). A pose is the reference point's
    position and the unit quaternion q turning body-frame vectors into the earth frame; a
    twist the reference point's velocity and the angular velocity omega, earth frame; ``acc``
    (6) the reference point's acceleration and the angular acceleration, earth frame.

    1. FIXED: its pose is the case's at every time; twist and ``acc`` zero.
    2. IMPOSED: pose, twist and ``acc`` from its channels (time functions, a ship's track),
       offset from a parent imposed body's reference point when it has one; the twist is the
       pose's time derivative (dq/dt = 1/2 (0, omega) q) and ``acc`` the twist's, exactly (the
       time functions' own derivatives, not differences).
    3. DYNAMIC: pose and twist are states (position and quaternion at ``q``, velocity and
       omega at ``v``; a point body has no quaternion and does not turn); its rates are the
       twist (the quaternion's as in 2) and ``acc``, from ``BodyDynamics``.
    4. TIP: no state of its own; its line (``lines.rigid_segments``) puts it at its last node
       with that node's velocity, and its mass and loads join the line's sweep.
    5. Every point is carried rigidly: p = x + R r_body, v = v_ref + omega x r and
       a = acc + alpha x r + omega x (omega x r) (``point_state``, ``point_acceleration``).
    6. ``has_mass``: the kinds that forces accelerate (DYNAMIC, TIP); a line's end on any other
       kind only reads its motion.
    """

    FIXED: int
    IMPOSED: int
    DYNAMIC: int
    TIP: int
    body_states: Callable[..., Any]
    point_state: Callable[..., Any]
    point_acceleration: Callable[..., Any]
    has_mass: Callable[..., Any]


@runtime_checkable
class BodyDynamics(Protocol):
    """How a dynamic body accelerates (``bodies.dynamics``): Newton-Euler at its reference
    point, in the earth frame.

    1. ``rigid_mass``: its 6x6 mass matrix M at the reference point (mass, inertia about the
       centre of gravity, the added-mass matrix turned into the earth frame) and the
       gyroscopic and centripetal ``bias``, so that M acc + bias is the rate of its momentum
       and of its moment of momentum about the reference point.
    2. ``add_force``: a force acting at an arm from the reference point adds itself and its
       moment arm x f; every load (force models, ties, rigid lines' ends) enters that way.
    3. ``add_point_mass``: a mass carried rigidly at a point (a lumped line's end node) adds
       Phi^T m Phi to M and Phi^T (f - m omega x (omega x r)) to the loads: the body and the
       node move as one rigid whole.
    4. ``solve_free``: acc solves M acc = loads - bias on the free degrees of freedom (``dofs``,
       earth axes at the reference point) with acc = 0 on the held ones; the held rows'
       reactions are not computed. False when M is singular on the free ones.
    """

    rigid_mass: Callable[..., Any]
    add_force: Callable[..., Any]
    add_point_mass: Callable[..., Any]
    solve_free: Callable[..., Any]
