"""Records: named tuples of many arrays that compiled code receives by reference.

The system's parameters and workspace (``system.kernel.SystemParams``, ``SystemWork``) hold
about 155 arrays. numba passes a tuple by value, member by member: each array is a structure of
7 to 11 machine words, so every compiled function that takes the two tuples has about 1,300
arguments to lower, and every call site as many to pass. That cost is paid in compile time by
each of the few hundred functions that take them: 20 trivial functions reading one field of a
115-array tuple compiled in 27.7 s with their Python entries (4.5 s without), against 1.0 s for
the same functions given a reference (numba 0.68, ``docs/architecture.md``, "Compile time").

A class registered here (``register``) stays a named tuple in Python, unchanged for every
Python caller; compiled code sees it as a ``Record``: a pointer to one structure holding the
same fields (a numba ``StructRef``), built once per tuple by a compiled function (``_pack``,
cached on disk) and kept in the tuple's ``__dict__``. The structure shares the tuple's arrays
(what compiled code writes into them Python reads); a tuple made by ``_replace`` gets its own.
Reading a field in compiled code is a load through the pointer: a hot loop reads the array into
a local first (a field read inside the loop is read again at every pass).
"""

from typing import Any, NamedTuple

from numba import njit, typeof, types
from numba.core import cgutils
from numba.experimental import structref
from numba.extending import NativeValue, box, overload, typeof_impl, unbox


class Record(types.StructRef):
    """The numba type of a registered named tuple in compiled code."""

    def preprocess_fields(self, fields):
        return tuple((name, types.unliteral(t)) for name, t in fields)


structref.register(Record)


class RecordHandle(structref.StructRefProxy):
    """The structure compiled code sees for a registered tuple (``handle``); Python reads the
    tuple, not this."""

    __slots__ = ()


_FIELDS: dict[type, type] = {}  # a registered class -> the named tuple class it extends
_KEY = "_record"  # where a tuple keeps its handle
_TYPE_KEY = "_record_type"  # and its type


class Unshared:
    """Mixin of a registered class: its handle is never copied or pickled with it."""

    __slots__ = ()

    def __getstate__(self) -> None:
        return None


def register(cls: type) -> type:
    """Compile ``cls`` (a subclass of a named tuple class, with a ``__dict__``: no
    ``__slots__``) as a ``Record``; returns ``cls``."""
    base = cls.__mro__[1]
    if not (issubclass(base, tuple) and hasattr(base, "_fields")) or not hasattr(cls, "__dict__"):
        raise TypeError(f"{cls.__name__} must extend a named tuple class and have a __dict__")
    _FIELDS[cls] = base

    @typeof_impl.register(cls)
    def _typeof(value, context):
        return record_type(value)

    return cls


def record_type(value: Any) -> Record:
    """The type compiled code sees for ``value`` (a registered tuple), without building its
    structure: a function can be compiled for it before (or in another process than) the one
    that builds it (``system.variants``); kept with the tuple."""
    kept = value.__dict__.get(_TYPE_KEY)
    if kept is None:
        kept = Record(
            [(name, typeof(field)) for name, field in zip(value._fields, value, strict=True)]
        )
        value.__dict__[_TYPE_KEY] = kept
    return kept


def pack_signature(value: Any) -> tuple:
    """The signature ``_pack`` is compiled for to build ``value``'s structure."""
    fields: type[NamedTuple] = _FIELDS[type(value)]
    return (typeof(fields._make(value)),)


def _pack_fields(values):  # pragma: no cover - replaced by its overload in compiled code
    raise NotImplementedError


@overload(_pack_fields)
def _pack_fields_overload(values):
    if not isinstance(values, types.NamedTuple):
        return None
    record = Record(list(zip(values.fields, values.types, strict=True)))
    lines = "".join(f"    r.{name} = values.{name}\n" for name in values.fields)
    text = f"def impl(values):\n    r = new(record)\n{lines}    return r\n"
    scope: dict[str, Any] = {"new": structref.new, "record": record, "__name__": __name__}
    exec(text, scope)  # the field names of a registered class: package code, not user text
    return scope["impl"]


@njit(cache=True)
def _pack(values):
    return _pack_fields(values)


def handle(value: Any) -> RecordHandle:
    """The structure compiled code sees for ``value`` (a registered tuple, or a handle):
    built on first use, then kept with the tuple."""
    if isinstance(value, RecordHandle):
        return value
    kept = value.__dict__.get(_KEY)
    if kept is None:
        fields: type[NamedTuple] = _FIELDS[type(value)]
        kept = _pack(fields._make(value))
        value.__dict__[_KEY] = kept
    return kept


@box(Record)
def _box(typ, val, c):
    """A structure returned to Python: its handle."""
    utils = structref._Utils(c.context, c.builder, typ)
    meminfo = c.box(types.MemInfoPointer(types.voidptr), utils.get_struct_ref(val).meminfo)
    make = c.pyapi.unserialize(c.pyapi.serialize_object(RecordHandle._numba_box_))
    typ_object = c.pyapi.unserialize(c.pyapi.serialize_object(typ))
    result = c.pyapi.call_function_objargs(make, [typ_object, meminfo])
    for obj in (make, typ_object, meminfo):
        c.pyapi.decref(obj)
    return result


@unbox(Record)
def _unbox(typ, obj, c):
    """A registered tuple (or a handle) given to compiled code: its handle's structure, borrowed
    (the tuple keeps the handle)."""
    find = c.pyapi.unserialize(c.pyapi.serialize_object(handle))
    found = c.pyapi.call_function_objargs(find, [obj])
    c.pyapi.decref(find)
    utils = structref._Utils(c.context, c.builder, typ)
    result = cgutils.alloca_once(c.builder, c.context.get_value_type(typ))
    failed = cgutils.is_null(c.builder, found)
    with c.builder.if_then(c.builder.not_(failed), likely=True):
        meminfo_object = c.pyapi.object_getattr_string(found, "_meminfo")
        meminfo = c.unbox(types.MemInfoPointer(types.voidptr), meminfo_object).value
        c.builder.store(utils.new_struct_ref(meminfo)._getvalue(), result)
        c.pyapi.decref(meminfo_object)
        c.pyapi.decref(found)
    return NativeValue(c.builder.load(result), is_error=failed)
