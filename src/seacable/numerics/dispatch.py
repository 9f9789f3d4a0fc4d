"""Which compiled model functions an integrator calls, chosen at compile time by the type of
the parameter tuple (``numba.extending.overload``). This keeps one integrator for every model
and keeps numba's on-disk cache working (passing functions as arguments would defeat it).

A model joins by adding a branch to each overload: ``rhs(t, y, p, w, ydot) -> status`` and
``project(y, p)`` (put the state back on its constraint manifold after a step; a no-op for
models without constraints in their state).
"""

from typing import TYPE_CHECKING

from numba import njit, types
from numba.extending import overload

from seacable.kernels import (
    chain3d,
    chain3d_newton,
    lumped,
    lumped_newton,
    lumped_star,
    natural,
    planar_chain,
    planar_newton,
    star3d,
)
from seacable.kernels.timefn import JIT
from seacable.system import kernel as system_kernel

if TYPE_CHECKING:
    from numba.core.decorators import _JITOptions

# the dispatchers compile with the kernels' options; overload hands every key on to jit, cache
# included, but numba's stubs type jit_options as the keyword options without ``cache``
OVERLOAD_JIT: "_JITOptions" = JIT  # type: ignore[assignment]  # stubs omit overload's cache


def model_rhs(t, y, p, w, ydot):
    """Right-hand side of the model whose parameters are ``p`` (compiled code only)."""
    raise NotImplementedError("model_rhs is only callable from compiled code")


def model_project(y, p):
    """Projection of the state of the model whose parameters are ``p`` (compiled code only)."""
    raise NotImplementedError("model_project is only callable from compiled code")


def _is(p, cls):
    return isinstance(p, types.BaseNamedTuple) and p.instance_class is cls


@overload(model_rhs, jit_options=OVERLOAD_JIT)
def _model_rhs(t, y, p, w, ydot):
    if _is(p, planar_chain.ChainParams):
        return lambda t, y, p, w, ydot: planar_chain.rhs(t, y, p, w, ydot)
    if _is(p, chain3d.Chain3DParams):
        return lambda t, y, p, w, ydot: chain3d.rhs(t, y, p, w, ydot)
    if _is(p, star3d.StarParams):
        return lambda t, y, p, w, ydot: star3d.rhs(t, y, p, w, ydot)
    if _is(p, lumped.LumpedParams):
        return lambda t, y, p, w, ydot: lumped.rhs(t, y, p, w, ydot)
    if _is(p, lumped_star.LumpedStarParams):
        return lambda t, y, p, w, ydot: lumped_star.rhs(t, y, p, w, ydot)
    if _is(p, natural.NaturalParams):
        return lambda t, y, p, w, ydot: natural.rhs(t, y, p, w, ydot)
    if _is(p, system_kernel.SystemParams):
        return lambda t, y, p, w, ydot: system_kernel.rhs(t, y, p, w, ydot)
    return None


@overload(model_project, jit_options=OVERLOAD_JIT)
def _model_project(y, p):
    if _is(p, planar_chain.ChainParams):
        return lambda y, p: None
    if _is(p, chain3d.Chain3DParams):
        return lambda y, p: chain3d.project(y, p)
    if _is(p, star3d.StarParams):
        return lambda y, p: star3d.project(y, p)
    if _is(p, lumped.LumpedParams) or _is(p, lumped_star.LumpedStarParams):
        return lambda y, p: None
    if _is(p, natural.NaturalParams):
        return lambda y, p: natural.project(y, p)
    if _is(p, system_kernel.SystemParams):
        return lambda y, p: system_kernel.project(y, p)
    return None


def model_projects(p):
    """True when the model's projection changes the state (then a first-same-as-last stage
    cannot be reused after a step)."""
    raise NotImplementedError("model_projects is only callable from compiled code")


@overload(model_projects, jit_options=OVERLOAD_JIT, inline="always")
def _model_projects(p):
    if _is(p, planar_chain.ChainParams) or _is(p, lumped.LumpedParams):
        return lambda p: False
    if _is(p, lumped_star.LumpedStarParams):
        return lambda p: False
    if _is(p, chain3d.Chain3DParams) or _is(p, star3d.StarParams):
        return lambda p: True
    if _is(p, natural.NaturalParams):
        return lambda p: p.cartesian == 1
    if _is(p, system_kernel.SystemParams):
        return lambda p: system_kernel.projects(p)  # quaternions of rigid bodies
    return None


def model_newton(t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix):
    """Residual and block-tridiagonal matrix of an implicit step's Newton iteration (compiled
    code only; second-order models with node blocks, see
    ``kernels.lumped_newton.newton_system``)."""
    raise NotImplementedError("model_newton is only callable from compiled code")


def model_prescribe(t, y, acc, p, w):
    """Write the prescribed nodes' exact motion at time t into the state and accelerations
    (compiled code only)."""
    raise NotImplementedError("model_prescribe is only callable from compiled code")


@overload(model_newton, jit_options=OVERLOAD_JIT)
def _model_newton(t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix):
    if _is(p, lumped.LumpedParams):
        return lambda t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix: (
            lumped_newton.newton_system(
                t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix
            )
        )
    if _is(p, chain3d.Chain3DParams):
        return lambda t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix: (
            chain3d_newton.newton_system(
                t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix
            )
        )
    if _is(p, planar_chain.ChainParams):
        return lambda t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix: (
            planar_newton.newton_system(
                t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix
            )
        )
    if _is(p, lumped_star.LumpedStarParams):
        return lambda t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix: (
            lumped_star.newton_system(
                t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix
            )
        )
    if _is(p, natural.NaturalParams):
        return lambda t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix: (
            natural.newton_system(
                t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix
            )
        )
    return None


def model_block(p):
    """Variables per node of a model with a node-block Newton matrix (compiled code only)."""
    raise NotImplementedError("model_block is only callable from compiled code")


@overload(model_block, jit_options=OVERLOAD_JIT, inline="always")
def _model_block(p):
    if _is(p, lumped.LumpedParams) or _is(p, lumped_star.LumpedStarParams):
        return lambda p: 3
    if _is(p, natural.NaturalParams):
        return lambda p: 3 if p.cartesian == 1 else 2
    return None


@overload(model_prescribe, jit_options=OVERLOAD_JIT)
def _model_prescribe(t, y, acc, p, w):
    if _is(p, lumped.LumpedParams):
        return lambda t, y, acc, p, w: lumped_newton.prescribe(t, y, acc, p)
    if _is(p, lumped_star.LumpedStarParams):
        return lambda t, y, acc, p, w: lumped_star.prescribe(t, y, acc, p, w)
    if _is(p, natural.NaturalParams) or _is(p, planar_chain.ChainParams):
        return lambda t, y, acc, p, w: None  # no prescribed variables (or kept by the kernel)
    if _is(p, chain3d.Chain3DParams):
        return lambda t, y, acc, p, w: None
    return None


def model_newton_cost(p):
    """Right-hand-side evaluations in one ``model_newton`` call (compiled code only)."""
    raise NotImplementedError("model_newton_cost is only callable from compiled code")


@overload(model_newton_cost, jit_options=OVERLOAD_JIT, inline="always")
def _model_newton_cost(p):
    if _is(p, lumped.LumpedParams) or _is(p, planar_chain.ChainParams):
        return lambda p: 1  # analytic Jacobian
    if _is(p, lumped_star.LumpedStarParams):
        return lambda p: 1
    if _is(p, chain3d.Chain3DParams):
        return lambda p: 1  # analytic but for local differences of the joint moments
    if _is(p, natural.NaturalParams):
        # coloured differences: 3 colours x B variables x (positions, velocities), + 2
        return lambda p: 6 * (3 if p.cartesian == 1 else 2) + 2
    return None


def model_solver(p, nq):
    """(blocks, block size) of the model's block-tridiagonal Newton system for ``nq``
    accelerations (compiled code only)."""
    raise NotImplementedError("model_solver is only callable from compiled code")


@overload(model_solver, jit_options=OVERLOAD_JIT, inline="always")
def _model_solver(p, nq):
    if _is(p, lumped.LumpedParams) or _is(p, lumped_star.LumpedStarParams):
        return lambda p, nq: (nq // 3, 3)
    if _is(p, natural.NaturalParams):
        return lambda p, nq: (nq // (3 if p.cartesian == 1 else 2), 3)
    if _is(p, planar_chain.ChainParams):
        return lambda p, nq: (p.n + 1, planar_newton.NEWTON_BLOCK)
    if _is(p, chain3d.Chain3DParams):
        return lambda p, nq: (p.n + 1, chain3d_newton.NEWTON_BLOCK)
    return None


def model_correct(p, da, a1):
    """Subtract the Newton correction ``da`` (the solver's unknowns) from the accelerations
    ``a1``; returns the largest correction as a length per squared second (compiled code
    only)."""
    raise NotImplementedError("model_correct is only callable from compiled code")


@njit(**JIT)
def _correct_nodes(b_node, da, a1):
    """Node-block models: the solver holds three entries per node, the first b_node used."""
    largest = 0.0
    for i in range(a1.shape[0]):
        d = da[3 * (i // b_node) + i % b_node]
        a1[i] -= d
        largest = max(largest, abs(d))
    return largest


@overload(model_correct, jit_options=OVERLOAD_JIT, inline="always")
def _model_correct(p, da, a1):
    if _is(p, lumped.LumpedParams) or _is(p, natural.NaturalParams):
        return lambda p, da, a1: _correct_nodes(model_block(p), da, a1)
    if _is(p, lumped_star.LumpedStarParams):
        return lambda p, da, a1: _correct_nodes(3, da, a1)
    if _is(p, planar_chain.ChainParams):
        return lambda p, da, a1: planar_newton.newton_correct(p.length, da, a1)
    if _is(p, chain3d.Chain3DParams):
        return lambda p, da, a1: chain3d_newton.newton_correct(p.length, da, a1)
    return None


def model_positions(p, ny):
    """Number of position variables in a state of length ``ny`` (velocities follow them; any
    further entries are first-order states the implicit schemes keep unchanged)."""
    raise NotImplementedError("model_positions is only callable from compiled code")


@overload(model_positions, jit_options=OVERLOAD_JIT, inline="always")
def _model_positions(p, ny):
    if _is(p, chain3d.Chain3DParams):
        return lambda p, ny: 3 * p.n + 1  # directors and heave; the servo force follows
    if _is(p, lumped.LumpedParams):
        return lambda p, ny: 3 * (p.n + 1)  # nodes; a servo's force follows the velocities
    return lambda p, ny: ny // 2


def model_keeps_matrix(p):
    """True when the model's Newton matrix is costly enough (against the iterations a stale one
    adds) to keep from step to step (compiled code only)."""
    raise NotImplementedError("model_keeps_matrix is only callable from compiled code")


@overload(model_keeps_matrix, jit_options=OVERLOAD_JIT, inline="always")
def _model_keeps_matrix(p):
    if _is(p, planar_chain.ChainParams) or _is(p, chain3d.Chain3DParams):
        return lambda p: True  # 5x5 or 9x9 blocks, joint differences
    return lambda p: False  # analytic 3x3 blocks: a fresh matrix per step is cheaper


def model_chain(p):
    """Nodes per chain of a star-shaped Newton matrix (``kernels.lumped_star``: chains coupled
    through a last, shared node); 0 for one block-tridiagonal chain (compiled code only)."""
    raise NotImplementedError("model_chain is only callable from compiled code")


@overload(model_chain, jit_options=OVERLOAD_JIT, inline="always")
def _model_chain(p):
    if _is(p, lumped_star.LumpedStarParams):
        return lambda p: p.n
    return lambda p: 0
