"""Calling a compiled function by its address, so that the caller does not compile it in.

numba compiles each function into a library of its own, and a function that calls another links
the callee's library into its own and optimises and generates code for the whole again: the
system's evaluation (``system.evaluation``), called by every integrator's chunk, the outputs,
the statics and the analyses, was optimised once per caller (docs/architecture.md, "Compile
time"). ``call2`` to ``call8`` instead call the function at an address the caller receives at
run time (a field of the system's parameters, ``system.kernel.SystemParams.entries``), with
numba's own calling convention: the callee is compiled once, in its own library, and the
caller's code holds one indirect call.

The address is the entry of a function compiled for exactly the argument types of the call:
``system.variants`` compiles it for the types of the system's parameter and work tuples, and
every argument here must be a C-contiguous array, a tuple of such arrays and scalars, or a
scalar (checked when the caller is typed; a strided view would be read as contiguous by the
callee). The return type is an int64 (a status).
"""

from numba import types
from numba.core import cgutils
from numba.core.errors import TypingError
from numba.extending import intrinsic


def _contiguous(ty) -> bool:
    """Whether every array in ``ty`` (an argument's numba type) is C-contiguous."""
    if isinstance(ty, types.Array):
        return ty.layout == "C"
    if isinstance(ty, types.BaseTuple):
        return all(_contiguous(member) for member in getattr(ty, "types", ()))
    return True


def _typed(address, args):
    """The signature of a call with ``args`` (their numba types), or a TypingError."""
    if not isinstance(address, types.Integer):
        raise TypingError(f"indirect: the address must be an integer, got {address}")
    if not all(_contiguous(t) for t in args):
        raise TypingError(f"indirect: the arguments must be C-contiguous arrays, tuples of "
                          f"them and scalars, got {args}")  # fmt: skip
    return types.int64(address, *args)


def _codegen(context, builder, sig, llargs):
    """Call the function at ``llargs[0]`` with the other arguments; its int64 result."""
    argtys = list(sig.args[1:])
    fnty = context.call_conv.get_function_type(types.int64, argtys)
    callee = builder.inttoptr(llargs[0], fnty.as_pointer())
    status, result = context.call_conv.call_function(builder, callee, types.int64, argtys,
                                                     list(llargs[1:]))  # fmt: skip
    with cgutils.if_unlikely(builder, status.is_error):
        context.call_conv.return_status_propagate(builder, status)
    return result


@intrinsic
def call2(typingctx, address, a, b):
    """``call5`` with two arguments."""
    return _typed(address, (a, b)), _codegen


@intrinsic
def call4(typingctx, address, a, b, c, d):
    """``call5`` with four arguments."""
    return _typed(address, (a, b, c, d)), _codegen


@intrinsic
def call5(typingctx, address, a, b, c, d, e):
    """``call5(address, a, b, c, d, e)``: the compiled function at ``address`` (an integer)
    called with five arguments; its int64 result. An exception the callee raises propagates to
    the caller as from a direct call."""
    return _typed(address, (a, b, c, d, e)), _codegen


@intrinsic
def call8(typingctx, address, a, b, c, d, e, f, g, h):
    """``call5`` with eight arguments."""
    return _typed(address, (a, b, c, d, e, f, g, h)), _codegen
