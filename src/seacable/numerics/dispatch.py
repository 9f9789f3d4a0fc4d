"""Which compiled model functions an integrator calls, chosen at compile time by the type of
the parameter tuple (``numba.extending.overload``). This keeps one integrator for every model
and keeps numba's on-disk cache working (passing functions as arguments would defeat it).

A model joins by adding a branch to each overload: ``rhs(t, y, p, w, ydot) -> status`` and
``project(y, p)`` (put the state back on its constraint manifold after a step; a no-op for
models without constraints in their state).
"""

from typing import TYPE_CHECKING

from numba import types
from numba.extending import overload

from seacable.kernels import chain3d, lumped, lumped_star, natural, planar_chain, star3d
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
