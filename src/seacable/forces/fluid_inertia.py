"""Fluid inertia of a body without a hull mesh or database (Morison's inertia term at the
body's reference point, as OrcaFlex's buoys and MoorDyn's rods have it): the water's
acceleration a [m/s^2] there (kernels.waves, with the environment's stretching) acts on

- the displaced water, rho V f a [N] at the centre of buoyancy (Froude-Krylov: the pressure
  gradient of the undisturbed wave on the body's volume, as buoyancy is that of the still
  water's);
- the body's own added mass A (its 6x6 at the reference point, body frame; per earth axis for
  a point body), f A [a_b; 0] with a_b = R^T a (the added mass meets the water's acceleration
  as it meets the body's own: G. I. Taylor's result for a body in an accelerating flow).

f is the body's submerged fraction (1 for a plain volume). A neutrally buoyant body
(m = rho V) with this model and no drag is carried by the water: its acceleration is the
water's. The row is the body's own added mass A (36 floats, row by row; without its rods',
which load their own part: forces.rod); the model reads the body's volume and centre of
buoyancy. Nothing in still water (statics) or in air.
"""

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.kernels import waves
from seacable.kernels.jit import inner


@inner
def add(volume, cob, row, fraction, pos, rot, rho, t, wave, depth, stretch, trig, rhs):
    if wave.shape[1] == 0:
        return
    _, acc = waves.kinematics(wave, t, pos[0], pos[1], pos[2], depth, stretch, trig)
    displaced = rho * volume * fraction
    arm = turn(rot, (cob[0], cob[1], cob[2]))
    add_force(arm, displaced * acc[0], displaced * acc[1], displaced * acc[2], rhs)
    # the added mass on the water's acceleration in the body frame, turned back
    ab = (
        rot[0, 0] * acc[0] + rot[1, 0] * acc[1] + rot[2, 0] * acc[2],
        rot[0, 1] * acc[0] + rot[1, 1] * acc[1] + rot[2, 1] * acc[2],
        rot[0, 2] * acc[0] + rot[1, 2] * acc[1] + rot[2, 2] * acc[2],
    )
    for half in range(2):  # the force, then the moment, of A [a_b; 0]
        f0 = f1 = f2 = 0.0
        for c in range(3):
            f0 += row[6 * (3 * half) + c] * ab[c]
            f1 += row[6 * (3 * half + 1) + c] * ab[c]
            f2 += row[6 * (3 * half + 2) + c] * ab[c]
        f = (fraction * f0, fraction * f1, fraction * f2)
        for q in range(3):
            rhs[3 * half + q] += rot[q, 0] * f[0] + rot[q, 1] * f[1] + rot[q, 2] * f[2]
