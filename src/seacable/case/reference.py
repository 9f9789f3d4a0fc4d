"""The case file's reference, generated from the schema: every key of every part, grouped as
the file is, with its type, unit, default, limits and meaning (the field's docstring, which
starts with its unit in brackets: ``"[m] Radius of the sphere."``).

``case_file_rst()`` writes the page the documentation builds (docs/conf.py);
``link(model, key)`` is the address of a key's entry, which the loader's error lines give, and
``link_for(message, case)`` the entry of the key a later check's message names (the command
line adds it).
"""

import inspect
import re
import types
import typing
from dataclasses import dataclass
from typing import Any, Literal

import annotated_types
from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from seacable.case.base import TimeFunction
from seacable.case.system import SystemCase

DOCS_URL = "https://seacable.readthedocs.io/en/latest/"
PAGE = "reference/case_file"
TAGS = ("type", "model", "kind")  # the discriminators: a part's kind is its value
FORCES = "external forces"  # a body's force models: a group of their own
TIME_FUNCTIONS = "time functions"  # the group of the parts a time function may be
TIME_FUNCTION = "number or time function"  # the type of a key that takes one
Part = type[BaseModel]  # a part of the case file: one model of the schema
_UNIT = re.compile(r"^\[([^\]]*)\]\s*")


@dataclass(frozen=True)
class Key:
    """One key of a part of the case file, as the reference prints it."""

    name: str  # as the file writes it (the alias)
    type: str  # readable, with links to parts written as :ref: roles
    unit: str  # "" where the key is not a number
    default: str  # "required" or the default, as YAML writes it
    limits: str
    meaning: str
    anchor: str


def anchor(model: Part, key: str | None = None) -> str:
    """The label of a part's section, or of one of its keys."""
    text = model.__name__.lower() if key is None else f"{model.__name__}-{key}".lower()
    return "case-" + re.sub(r"[^a-z0-9]+", "-", text).strip("-")


def link(model: Part, key: str | None = None) -> str:
    """The address of a part's or a key's entry in the published reference."""
    return f"{DOCS_URL}{PAGE}.html#{anchor(model, key)}"


_STEP = re.compile(r"^([A-Za-z_ ]+?)(?:\[(\d+)\])?(?: \(([^)]*)\))?$")


def link_for(message: str, case: BaseModel) -> str | None:
    """The address of the entry of the key a message starts with (``bodies[4] (buoy).mass:``,
    ``lines (cable).sections[0].type:``, as the checks after the schema's name them), found
    in ``case``, the case it is about; the entry of the part it names when the key is not
    one; None when the message names none."""
    head = message.split(":", 1)[0] if ":" in message else ""
    here: Any = case
    model, key = None, None
    for token in head.split(".") if head else []:
        found = _STEP.match(token.strip())
        if found is None or not isinstance(here, BaseModel):
            break
        name, index, label = found.groups()
        fields = {f.alias or n: n for n, f in type(here).model_fields.items()}
        if name not in fields:
            break
        model, key = type(here), name
        value = getattr(here, fields[name])
        if index is not None and isinstance(value, list) and int(index) < len(value):
            value = value[int(index)]
        elif label is not None and isinstance(value, list):
            value = next((v for v in value if getattr(v, "name", None) == label), None)
        if isinstance(value, BaseModel):
            here, model, key = value, type(value), None
        elif index is not None or label is not None:
            break
    return None if model is None else link(model, key)


def unit_and_meaning(description: str | None) -> tuple[str, str]:
    """A field docstring's unit (without brackets; "" when it has none) and its meaning."""
    text = " ".join((description or "").split())
    found = _UNIT.match(text)
    if found is None:
        return "", text
    return found.group(1), text[found.end() :]


def tag(model: Part) -> tuple[str, tuple[str, ...]] | None:
    """(discriminator, values) that select this part in a list of parts of several kinds."""
    for name in TAGS:
        field = model.model_fields.get(name)
        if field is not None and typing.get_origin(field.annotation) is Literal:
            return name, tuple(str(v) for v in typing.get_args(field.annotation))
    return None


def title(model: Part) -> str:
    found = tag(model)
    if found is None:
        return model.__name__
    return f"{model.__name__} ({found[0]}: {' or '.join(found[1])})"


def parts(model: Part = SystemCase) -> list[Part]:
    """Every model reachable from ``model``, depth first, in the order the fields name them."""
    out: list[Part] = []

    def walk(annotation) -> None:
        if isinstance(annotation, type) and issubclass(annotation, BaseModel):
            if annotation in out:
                return
            out.append(annotation)
            for field in annotation.model_fields.values():
                walk(field.annotation)
            return
        for arg in typing.get_args(annotation):
            walk(arg)

    walk(model)
    return out


def sections() -> list[tuple[str, list[Part]]]:
    """The parts grouped by the top-level key they are reached from, as the file is laid out
    (a body's force models in a group of their own); the parts reached from two of them in the
    last group, "time functions" when they are those."""
    root = SystemCase
    reached: dict[Part, set[str]] = {}
    order: list[tuple[str, list[Part]]] = []
    for name, field in root.model_fields.items():
        found = [p for p in _parts_under(field.annotation) if p is not root]
        order.append((field.alias or name, found))
        for p in found:
            reached.setdefault(p, set()).add(field.alias or name)
    grouped: list[tuple[str, list[Part]]] = [("top level", [root])]
    for key, found in order:
        mine = [p for p in found if len(reached[p]) == 1]
        forces = [p for p in mine if p in _reached_by(mine, FORCES)]
        for name, group in ((key, [p for p in mine if p not in forces]), (FORCES, forces)):
            if group:
                grouped.append((name, group))
    shared = [p for p in parts(root) if len(reached.get(p, ())) > 1]
    name = TIME_FUNCTIONS if set(shared) == set(_parts_under(TimeFunction)) else "shared parts"
    return grouped + ([(name, shared)] if shared else [])


def _reached_by(models: list[Part], key: str) -> list[Part]:
    """The parts under the fields called ``key`` of these models."""
    out: list[Part] = []
    for model in models:
        for name, field in model.model_fields.items():
            if (field.alias or name) == key:
                out.extend(p for p in _parts_under(field.annotation) if p not in out)
    return out


def _parts_under(annotation) -> list[Part]:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return parts(annotation)
    out: list[Part] = []
    for arg in typing.get_args(annotation):
        out.extend(p for p in _parts_under(arg) if p not in out)
    return out


def keys(model: Part) -> list[Key]:
    """The reference's entries of a part's keys, in the schema's order (its tag first)."""
    out = []
    for name, field in model.model_fields.items():
        key = field.alias or name
        found = tag(model)
        if found is not None and found[0] == key and not field.description:
            unit, meaning = "", "Selects this kind of part."
        else:
            unit, meaning = unit_and_meaning(field.description)
        text, nested = type_text(field.annotation)
        out.append(
            Key(
                name=key,
                type=text,
                unit=unit,
                default=_default(field),
                limits=", ".join([*_limits(field.metadata), *nested]),
                meaning=meaning,
                anchor=anchor(model, key),
            )
        )
    return out


def _default(field) -> str:
    if field.is_required():
        return "required"
    value = field.default_factory() if field.default_factory else field.default
    if value is PydanticUndefined:
        return "required"
    if isinstance(value, BaseModel):
        return "its parts' defaults"
    return _yaml(value)


def _yaml(value: Any) -> str:
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_yaml(v) for v in value) + "]"
    return repr(value)


_BOUNDS = (("gt", ">"), ("ge", "≥"), ("lt", "<"), ("le", "≤"))


def _limits(metadata) -> list[str]:
    out = []
    for item in metadata:
        for attr, sign in _BOUNDS:
            value = getattr(item, attr, None)
            if value is not None:
                out.append(f"{sign} {value:g}")
        if isinstance(item, annotated_types.MinLen) and item.min_length:
            out.append(f"at least {item.min_length} item{'s' * (item.min_length > 1)}")
        if isinstance(item, annotated_types.MaxLen):
            out.append(f"at most {item.max_length} items")
    return out


_NAMES = {float: "number", int: "integer", str: "text", bool: "true or false", Any: "anything"}


def type_text(annotation) -> tuple[str, list[str]]:
    """A type as the reference writes it, and the limits on the numbers inside it."""
    origin = typing.get_origin(annotation)
    args = typing.get_args(annotation)
    if annotation in (TimeFunction, typing.get_args(TimeFunction)[0]):
        return f":ref:`{TIME_FUNCTION} <case-group-time-functions>`", []
    if origin is typing.Annotated:
        text, limits = type_text(args[0])
        return text, [*_limits(args[1:]), *limits]
    if annotation in _NAMES:
        return _NAMES[annotation], []
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return _ref(annotation), []
    if origin is Literal:
        return "one of " + ", ".join(f"``{v}``" for v in args), []
    if origin in (typing.Union, types.UnionType):
        members = [a for a in args if a is not type(None)]
        models = [m for m in members if isinstance(m, type) and issubclass(m, BaseModel)]
        if len(models) == len(members) > 1 and tag(models[0]) is not None:
            return "one of " + ", ".join(_ref(m) for m in models), []
        pairs = [type_text(m) for m in members]
        unique = list(dict.fromkeys(text for text, _ in pairs))
        return " or ".join(unique), [x for _, found in pairs for x in found]
    if origin is list:
        text, limits = type_text(args[0])
        return f"list of {text}", limits
    if origin is tuple:
        if len(args) == 2 and args[1] is Ellipsis:
            text, limits = type_text(args[0])
            return f"list of {text}", limits
        pairs = [type_text(a) for a in args]
        found = list(dict.fromkeys(x for _, limits in pairs for x in limits))
        if len({text for text, _ in pairs}) == 1:
            return f"[{len(args)} {_plural(pairs[0][0])}]", found
        return "[" + ", ".join(text for text, _ in pairs) + "]", found
    if origin is dict:
        return f"mapping of {type_text(args[0])[0]} to {type_text(args[1])[0]}", []
    return str(annotation), []


def _plural(text: str) -> str:
    return {"number": "numbers", "integer": "integers", "text": "texts"}.get(text, f"× {text}")


def _ref(model: Part) -> str:
    return f":ref:`{title(model)} <{anchor(model)}>`"


def case_file_rst() -> str:
    """The reference page of the case file, in reStructuredText."""
    out = [
        ".. This page is generated from the schema by seacable.case.reference: edit the",
        "   docstrings of src/seacable/case, not this file.",
        "",
        ".. _case-file-reference:",
        "",
        "Case-file reference",
        "===================",
        "",
        "Every key of a case file, grouped as the file is: its type, unit, default, limits and",
        "meaning. Units are SI; angles in degrees where the key ends in ``_deg`` (the frames and",
        "signs: :doc:`../conventions`). A part that can be of several kinds is chosen by its",
        "``type``, ``model`` or ``kind`` key. ``seacable validate case.yaml`` checks a file",
        "against all of this; its error lines link to the entries below.",
        "",
    ]
    for group, models in sections():
        label = "case-group-" + re.sub(r"[^a-z0-9]+", "-", group)
        out += [f".. _{label}:", "", group.capitalize(), "-" * len(group), ""]
        for model in models:
            out += _part_rst(model, headed=_name(model.__name__) != _name(group))
    return "\n".join(out) + "\n"


def _name(text: str) -> str:
    return re.sub(r"[^a-z]", "", text.lower())


def _part_rst(model: Part, headed: bool = True) -> list[str]:
    """A part's section: its docstring, then one entry per key (its facts on the first line,
    its meaning below)."""
    heading = title(model)
    doc = _plain(inspect.cleandoc(model.__doc__ or ""))
    out = [f".. _{anchor(model)}:", ""]
    out += [heading, "~" * len(heading), ""] if headed and model is not SystemCase else []
    out += [doc, ""]
    for key in keys(model):
        facts = [key.type]
        if key.unit:
            facts.append(f"[{key.unit}]")
        if key.limits:
            facts.append(key.limits)
        facts.append(key.default if key.default == "required" else f"default {key.default}")
        out += [
            f".. _{key.anchor}:",
            "",
            f"``{key.name}`` · {' · '.join(facts)}",
            f"   {_plain(key.meaning)}",
            "",
        ]
    return out


def _plain(text: str) -> str:
    """Docstring text as reStructuredText: a |v| is an absolute value, not a substitution."""
    return text.replace("|", "\\|")
