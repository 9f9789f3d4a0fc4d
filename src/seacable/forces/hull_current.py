"""A ship hull's forces in the horizontal plane from the water flowing past it, at any drift
angle, with yaw-rate terms: ``model: short-wing`` and ``model: cross-flow``.

Notation: L the length between perpendiculars, B the beam, T the draught, C_B the block
coefficient [-], S the wetted area [m^2], rho the water's density; (u, v) [m/s] the ship's
velocity relative to the water at the model's ``point`` P (midship), body frame (x forward, y
to port), V = sqrt(u^2 + v^2), r [rad/s] the yaw rate (about the body's z, up). Forces along
the body's x and y act at P, N is the moment about the body's z through P:

    X = 1/2 rho L T x(u, v),   Y = 1/2 rho L T y(u, v, r),   N = 1/2 rho L^2 T n(u, v, r)

Surge friction, both models: x_f = -(1 + k) C_F(Re) S / (L T) u V (the short-wing model's)
or u |u| (the cross-flow model's), C_F = 0.075 / (log10 Re - 2)^2 (ITTC 1957), Re = V L / nu
(at least 1e5), k the form factor (0.25: the 0.09375 of Leite et al.).

``short-wing`` -- Leite, Aranha, Umeda and de Conti, "Current forces in tankers and
bifurcation of equilibrium of turret systems: hydrodynamic model and experiments", Applied
Ocean Research 20 (1998) 145-156. With psi the direction the flow goes relative to the ship
(towards the bow: 0, towards port: 90 deg), their coefficients C_1, C_2, C_6 (X = 1/2 rho V^2
L T C_1 ...), written here in u and v (V cos psi = -u, V sin psi = -v):

    C_1 = (1 + k) C_F S/(L T) cos psi + pi T/(8 L) (cos 3psi - cos psi)
    C_2 = (C_Y - pi T/(2 L)) sin psi |sin psi| + pi T/(2 L) sin^3 psi
          + pi T/L (1 + 0.4 C_B B/T) sin psi |cos psi|
    C_6 = (x_Y/L) C_Y sin psi |sin psi| - pi T/L sin psi cos psi
          - ((1 + |cos psi|)/2)^2 pi T/L (1/2 - 2.4 T/L) sin psi |cos psi|

C_Y the cross-flow drag coefficient (beam flow), x_Y the position [m, forward of P] where
the beam flow's force acts (their l_Y is -x_Y). The last terms are a short wing's lift (span
2T, chord L) and Munk's moment; at a small drift angle ahead they are the linear derivatives of
Clarke, Gedling and Hine (1983), Y'_v and N'_v below (tests/test_hull_current.py). Note the
minus before the last term of C_6: with a plus, N'_v ahead is -pi (T/L)^2 (3/2 - 2.4 T/L),
about twice Clarke's for a tanker, and a turret-moored ship turns unstable far too early.

``cross-flow`` -- the low-speed manoeuvring model of the MMG kind (Yoshimura's "unified"
model: linear lift terms that vanish in beam flow, plus the cross-flow drag integrated along
the hull, valid at any drift angle):

    y = y_v |u| v - C_Y v |v| (+ the yaw-rate terms)
    n = n_v u v - (x_Y / L) C_Y v |v| (+ the yaw-rate terms)

with y_v = (L/T) Y'_v and n_v = (L/T) N'_v, Clarke's derivatives for the hull unless given.

Yaw-rate terms, both models: the lift's linear terms |u| r, Clarke's Y'_r and N'_r
(y_r = (L/T) Y'_r, n_r = (L/T) N'_r, per r L), and the cross-flow drag of each station x
(from -L/2 to L/2 about P) moving sideways at v + r x:

    Y += 1/2 rho L^2 T y_r |u| r - 1/2 rho T C_Y (I_0(v, r) - L v |v|)
    N += 1/2 rho L^3 T n_r |u| r - 1/2 rho T C_Y I_1(v, r)
    I_0 = int (v + r x)|v + r x| dx,   I_1 = int x (v + r x)|v + r x| dx

in closed form (split where v + r x changes sign). At r = 0 they vanish; a ship turning on the
spot feels N = -1/2 rho T C_Y r |r| L^4 / 32. Clarke, Gedling and Hine, "The application of
manoeuvring criteria in hull design using linear theory", Trans. RINA 125 (1983) 45-68, with
a = pi (T/L)^2 and forces per 1/2 rho L^2 U^2, moments per 1/2 rho L^3 U^2, v' = v/U,
r' = r L/U:

    -Y'_v = a (1 + 0.40 C_B B/T)         -Y'_r = a (-1/2 + 2.2 B/L - 0.080 B/T)
    -N'_v = a (1/2 + 2.4 T/L)            -N'_r = a (1/4 + 0.039 B/T - 0.56 B/L)
    -Y'_vdot = a (1 + 0.16 C_B B/T - 5.1 (B/L)^2)   -N'_rdot = a (1/12 + 0.017 C_B B/T - 0.33 B/L)
    -Y'_rdot = a (0.67 B/L - 0.0033 (B/T)^2)        -N'_vdot = a (1.1 B/L - 0.041 B/T)

(the acceleration derivatives per 1/2 rho L^3 and 1/2 rho L^4: the added masses, for the
body's ``added_mass``; ``clarke`` gives all eight). Munk's moment of the added mass is inside
N'_v: give such a hull ``coriolis: rigid_body`` (the default), not ``exact``.

Row: P (3), L, B, T, C_B, S, C_Y, x_Y, nu, 1 + k, the form (SHORT_WING, CROSS_FLOW), y_v,
n_v, y_r, n_r.
"""

import math

from numba import njit

from seacable.bodies.kinematics import turn
from seacable.forces.coefficients import add_plane_load, relative_flow
from seacable.kernels import chain3d as c3
from seacable.kernels.jit import JIT, inner

SHORT_WING, CROSS_FLOW = 0, 1
FORMS = {"short-wing": SHORT_WING, "cross-flow": CROSS_FLOW}
SMALLEST_REYNOLDS = 1e5


def clarke(length: float, beam: float, draught: float, block: float) -> dict[str, float]:
    """Clarke, Gedling and Hine's (1983) linear derivatives of a hull (module docstring):
    Y_v, Y_r, N_v, N_r, Y_vdot, Y_rdot, N_vdot, N_rdot, non-dimensional (prime) per 1/2 rho
    L^2 U (Y_v), 1/2 rho L^3 U (Y_r, N_v), 1/2 rho L^4 U (N_r), 1/2 rho L^3 (Y_vdot),
    1/2 rho L^4 (Y_rdot, N_vdot) and 1/2 rho L^5 (N_rdot)."""
    a = math.pi * (draught / length) ** 2
    b_l, b_t, t_l = beam / length, beam / draught, draught / length
    return {
        "Y_v": -a * (1.0 + 0.40 * block * b_t),
        "Y_r": -a * (-0.5 + 2.2 * b_l - 0.080 * b_t),
        "N_v": -a * (0.5 + 2.4 * t_l),
        "N_r": -a * (0.25 + 0.039 * b_t - 0.56 * b_l),
        "Y_vdot": -a * (1.0 + 0.16 * block * b_t - 5.1 * b_l**2),
        "Y_rdot": -a * (0.67 * b_l - 0.0033 * b_t**2),
        "N_vdot": -a * (1.1 * b_l - 0.041 * b_t),
        "N_rdot": -a * (1.0 / 12.0 + 0.017 * block * b_t - 0.33 * b_l),
    }


def added_mass(length: float, beam: float, draught: float, block: float, rho: float = 1025.0
               ) -> tuple[float, float, float, float]:  # fmt: skip
    """The sway and yaw added masses of Clarke's acceleration derivatives, about midship:
    (m22 [kg], m26 [kg m], m62 [kg m], m66 [kg m^2]) = -(Y'_vdot 1/2 rho L^3, Y'_rdot 1/2 rho
    L^4, N'_vdot 1/2 rho L^4, N'_rdot 1/2 rho L^5)."""
    d = clarke(length, beam, draught, block)
    h = 0.5 * rho
    return (-d["Y_vdot"] * h * length**3, -d["Y_rdot"] * h * length**4,
            -d["N_vdot"] * h * length**4, -d["N_rdot"] * h * length**5)  # fmt: skip


def pack(
    form: str, point, length, beam, draught, block, wetted_area, cross_flow_drag,
    cross_flow_centre, kinematic_viscosity, form_factor, derivatives,
) -> list[float]:  # fmt: skip
    """The row of a ``short-wing`` or ``cross-flow`` model (lengths [m], ``wetted_area`` S
    [m^2] or None for Denny-Mumford's 1.7 L T + C_B L B, ``kinematic_viscosity`` [m^2/s],
    ``derivatives``: Clarke's prime Y_v, N_v, Y_r, N_r replacing the defaults, by name)."""
    d = clarke(length, beam, draught, block)
    d.update(derivatives or {})
    s = wetted_area if wetted_area is not None else 1.7 * length * draught + block * length * beam
    per = length / draught
    return [*(float(v) for v in point), float(length), float(beam), float(draught),
            float(block), float(s),
            float(cross_flow_drag), float(cross_flow_centre), float(kinematic_viscosity),
            1.0 + float(form_factor), float(FORMS[form]), per * d["Y_v"], per * d["N_v"],
            per * d["Y_r"], per * d["N_r"]]  # fmt: skip


@inner
def _piece(v, r, x1, x2):
    """(int w^2 dx, int x w^2 dx) over [x1, x2], w = v + r x."""
    w1, w2 = v + r * x1, v + r * x2
    i0 = (x2 - x1) * (w1 * w1 + w1 * w2 + w2 * w2) / 3.0
    i1 = (v * v * (x2 * x2 - x1 * x1) / 2.0 + 2.0 * v * r * (x2**3 - x1**3) / 3.0
          + r * r * (x2**4 - x1**4) / 4.0)  # fmt: skip
    return i0, i1


@njit(**JIT)
def cross_flow(v, r, half):
    """(I_0, I_1) = (int w |w| dx, int x w |w| dx) over [-half, half], w = v + r x, exact."""
    w1, w2 = v - r * half, v + r * half
    if w1 * w2 >= 0.0:
        s = 1.0 if w1 + w2 >= 0.0 else -1.0
        i0, i1 = _piece(v, r, -half, half)
        return s * i0, s * i1
    x0 = -v / r  # inside: w changes sign there
    a0, a1 = _piece(v, r, -half, x0)
    b0, b1 = _piece(v, r, x0, half)
    s = 1.0 if w2 > 0.0 else -1.0  # the sign past x0
    return s * (b0 - a0), s * (b1 - a1)


@njit(**JIT)
def coefficients(row, u, v, r):
    """(x, y, n): the non-dimensional loads (module docstring) of the ship moving at (u, v)
    [m/s] relative to the water at P, turning at r [rad/s]."""
    length, beam, draught, block = row[3], row[4], row[5], row[6]
    wetted, cy, xy, nu, form_k, form = row[7], row[8], row[9], row[10], row[11], row[12]
    speed = math.sqrt(u * u + v * v)
    if speed == 0.0 and r == 0.0:
        return 0.0, 0.0, 0.0
    reynolds = max(speed * length / nu, SMALLEST_REYNOLDS)
    friction = form_k * 0.075 / (math.log10(reynolds) - 2.0) ** 2 * wetted / (length * draught)
    wing = math.pi * draught / length
    au = abs(u)
    if int(form) == SHORT_WING:
        x = -friction * u * speed
        y = -(cy - 0.5 * wing) * v * abs(v) - wing * (1.0 + 0.4 * block * beam / draught) * v * au
        n = -(xy / length) * cy * v * abs(v) - wing * u * v
        if speed > 0.0:
            x += 0.5 * wing * u * v * v / speed
            y -= 0.5 * wing * v * v * v / speed
            lift = (speed + au) / (2.0 * speed)
            n += lift * lift * wing * (0.5 - 2.4 * draught / length) * v * au
    else:
        x = -friction * u * au
        y = row[13] * au * v - cy * v * abs(v)
        n = row[14] * u * v - (xy / length) * cy * v * abs(v)
    y += row[15] * au * r * length
    n += row[16] * au * r * length
    if r != 0.0:
        i0, i1 = cross_flow(v, r, 0.5 * length)
        y -= cy * (i0 - length * v * abs(v)) / length
        n -= cy * i1 / (length * length)
    return x, y, n


@njit(inline="always", **JIT)
def add(row, rho, pos, rot, vel, omega, current_z, current_u, current_v, rhs):
    """The hull's load at P, in the earth frame, added to ``rhs``."""
    arm = turn(rot, (row[0], row[1], row[2]))
    cx, cy = c3._current(current_z, current_u, current_v, pos[2] + arm[2])
    w = relative_flow(arm, rot, vel, omega, cx, cy)  # the water relative to P, body frame
    r = rot[0, 2] * omega[0] + rot[1, 2] * omega[1] + rot[2, 2] * omega[2]
    x, y, n = coefficients(row, -w[0], -w[1], r)
    scale = 0.5 * rho * row[3] * row[5]
    add_plane_load(rot, arm, scale * x, scale * y, scale * row[3] * n, rhs)
