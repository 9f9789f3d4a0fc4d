"""Read a YAML case file (never evaluating its text) into a validated, immutable Case."""

import re
import types
import typing
from pathlib import Path
from typing import Any

import yaml
from pydantic import BaseModel, ValidationError

from seacable import files, meshes
from seacable.case import moordyn, reference
from seacable.case.base import (
    BOOLEAN_ERROR,
    MAGNITUDE_ERROR,
    HullMesh,
    HydroDatabase,
    Table,
    instances,
)
from seacable.case.schema import Case
from seacable.case.system import SystemCase
from seacable.errors import CaseError

_TAGS = ("type", "kind", "model")


class _CaseYAML(yaml.SafeLoader):
    """PyYAML's safe loader reading numbers as engineers write them: YAML 1.1 wants a dot and
    a signed exponent for a float, so ``1e6`` and ``1.0e6`` would be text; here they are
    floats (as YAML 1.2 reads them), whatever field they fill."""


_CaseYAML.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:[0-9][0-9_]*)?(?:\.[0-9_]*)?[eE][-+]?[0-9]+$"),
    list("-+0123456789."),
)


def _no_duplicates(loader: Any, node: Any) -> dict:
    """A mapping whose keys are each given once: YAML lets the last of two equal keys win
    silently, which hides a typo or a pasted block."""
    seen: dict = {}
    for key_node, _ in node.value:
        if key_node.tag == "tag:yaml.org,2002:merge":
            continue  # "<<": its keys may be given again, to override them
        key = loader.construct_object(key_node, deep=True)
        if not isinstance(key, typing.Hashable):
            continue  # a list or mapping as a key: PyYAML's own error says so below
        if key in seen:
            raise CaseError(
                f"case file: key '{key}' is given twice in one mapping (lines "
                f"{seen[key] + 1} and {key_node.start_mark.line + 1}); keep one of them"
            )
        seen[key] = key_node.start_mark.line
    return yaml.SafeLoader.construct_mapping(loader, node)


_CaseYAML.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _no_duplicates)

LARGEST_CASE = 10_000_000  # bytes: a case file (tables and meshes go in their own files)
MOST_VALUES = 1_000_000  # values in a case once its YAML aliases are expanded
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


def parse_yaml(text: str):
    """The YAML text's data (a SafeLoader: never constructs objects), or one CaseError line:
    not YAML, a key given twice, nested too deep, or expanding (through aliases) to more
    values than any case holds."""
    try:
        data = yaml.load(text, Loader=_CaseYAML)
    except yaml.YAMLError as exc:
        raise CaseError(f"case file is not valid YAML: {_shortened(str(exc), 300)}") from None
    except RecursionError:
        raise CaseError("case file: its lists or mappings are nested too deeply") from None
    except (ValueError, OverflowError, KeyError, TypeError) as exc:  # a tag's value, a number
        raise CaseError(
            f"case file is not valid YAML: a value cannot be read ({type(exc).__name__}: "
            f"{_shortened(str(exc), 200)}); correct it, or remove its tag (!!float, !!int, "
            "!!bool, !!timestamp)"
        ) from None
    _count(data, [0])
    return data


def _count(value, seen: list[int]) -> None:
    """Refuse data whose values, counted as a reader walks them (a YAML alias as often as it
    is used), exceed MOST_VALUES: the "billion laughs" of nested aliases."""
    seen[0] += 1
    if seen[0] > MOST_VALUES:
        raise CaseError(
            f"case file: more than {MOST_VALUES:,} values once its aliases (*name) are expanded; "
            "no case holds that many: check the anchors (&name) and aliases"
        )
    if isinstance(value, dict):
        for item in value.values():
            _count(item, seen)
    elif isinstance(value, list):
        for item in value:
            _count(item, seen)


def _text(path: Path) -> str:
    """A case file's text, or one CaseError line: a directory, too large, a results file, not
    UTF-8 text."""
    raw = files.read_bytes(path, "case file", LARGEST_CASE, CaseError,
                           give="give the path of a .yaml file")  # fmt: skip
    if raw.startswith(HDF5_SIGNATURE):
        raise CaseError(
            f"case file '{path}' is a results file (NetCDF/HDF5), not a case; give the .yaml "
            "case file (a results file's case is in its 'case' attribute)"
        )
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise CaseError(
            f"case file '{path}' is not UTF-8 text (byte {raw[exc.start]:#04x} at position "
            f"{exc.start}); save it as UTF-8"
        ) from None


def load_case(source: str | Path | dict) -> SystemCase:
    """Load and validate a case (a system of bodies and lines) from a YAML file path, a YAML
    string or a dict. The single-cable form (``cables:``) is refused with the command that
    rewrites it (``seacable upgrade``, which reads it with :func:`load_single_cable`).

    Raises
    ------
    CaseError
        With one line per problem: the path in the file (``lines[0].sections``), the value, what
        is allowed and, for unknown keys, the valid keys.
    """
    data, text, file = _read(source)
    if "cables" in data:
        name = str(source) if file is not None else "FILE"
        raise CaseError(
            "cables: the single-cable form (cables: with top and bottom) is not read any more; "
            f"write the case as a system of bodies and lines: seacable upgrade {name} "
            "-o system.yaml"
        )
    case = _validated(SystemCase, data, text, file)
    assert isinstance(case, SystemCase)
    return case


def load_single_cable(source: str | Path | dict) -> Case:
    """Load and validate a case in the single-cable form (``cables:`` with ``top`` and
    ``bottom``), which only ``seacable upgrade`` reads (``case.legacy.upgrade``): a path, a YAML
    string or a dict, as :func:`load_case`.

    Raises
    ------
    CaseError
        As :func:`load_case`; for a system of bodies and lines, that it is one already.
    """
    data, text, file = _read(source)
    if "lines" in data:
        raise CaseError("the case is already a system of bodies and lines (lines:)")
    case = _validated(Case, data, text, file)
    assert isinstance(case, Case)
    return case


def _read(source: str | Path | dict) -> tuple[dict, str | None, Path | None]:
    """The mapping of a case source, its YAML text (None for a dict; a MoorDyn deck's case
    written as YAML, case.moordyn) and its file (None for a dict or a YAML string)."""
    file = None
    text = None
    if isinstance(source, dict):
        data = source
    else:
        path = Path(source) if not (isinstance(source, str) and "\n" in source) else None
        if path is not None and path.suffix.lower() in (".yaml", ".yml") and not path.exists():
            raise CaseError(f"case file '{path}' does not exist")
        if path is not None and path.exists():
            text = _text(path)
            file = path.resolve()
        else:
            text = str(source)
        if moordyn.looks_like_deck(text):  # a MoorDyn input file: its case, and as YAML
            data, text = moordyn.convert(
                text,
                str(path) if file is not None else None,
                file.parent if file is not None else None,
            )
            return data, text, file
        data = parse_yaml(text)
    if not isinstance(data, dict):
        raise CaseError(f"a case must be a mapping of keys to values; got {type(data).__name__}")
    return data, text, file


def _validated(root, data: dict, text: str | None, file: Path | None) -> Case | SystemCase:
    try:
        case = root.model_validate(data)
    except ValidationError as exc:
        raise CaseError(format_errors(exc, root)) from None
    case._source_dump = case.model_dump(mode="json")
    case._source_text = text if text is not None else _dumped(case)
    case._base_dir = None if file is None else str(file.parent)
    case._source_file = None if file is None else str(file)
    return case


def derive_case(case: Case | SystemCase, changes: dict) -> Case | SystemCase:
    """A new case from ``case``: the mapping it was read from with ``changes`` merged in,
    validated as a case file is (the same checks and messages), its relative file names still
    referring to ``case``'s folder.

    ``changes`` is a nested mapping like the case's own (``{"simulation": {"duration": 1.0}}``):
    a mapping merges into the mapping at the same key, a value of None removes the key, any
    other value (numbers, strings, lists) replaces it.

    Raises
    ------
    CaseError
        When the derived case is invalid, as for a file.
    """
    data = parse_yaml(case_text(case))
    merged = _merged(data, changes)
    derived = load_case(merged) if isinstance(case, SystemCase) else load_single_cable(merged)
    derived._base_dir, derived._source_file = case._base_dir, case._source_file
    return derived


def with_settings(case: SystemCase, settings: list[str] | tuple[str, ...]) -> SystemCase:
    """``case`` with each ``PATH=VALUE`` of ``settings`` set, validated as a case file is (the
    command line's ``--set``). PATH is written as the file nests its keys: ``simulation.duration``,
    ``environment.waves[0].significant_height``, ``bodies.buoy.mass`` (a list's item by its
    index or by its ``name``); a key the file leaves out may be given. VALUE is read as YAML
    (``10``, ``rk4``, ``[0, 0, -80]``, ``null`` to remove the key).

    Raises
    ------
    CaseError
        A setting not written PATH=VALUE, a path that leads nowhere, or the case it gives
        refused (one line per problem, as for a file).
    """
    if not settings:
        return case
    data = case_data(case)
    for setting in settings:
        path, sep, value = setting.partition("=")
        if not sep or not path.strip():
            raise CaseError(
                f"--set {setting!r}: write PATH=VALUE, e.g. --set simulation.duration=10"
            )
        try:
            parsed = parse_yaml(value) if value.strip() else None
        except CaseError as exc:
            detail = " ".join(str(exc).partition(": ")[2].split())
            raise CaseError(
                f"--set {setting!r}: the value is not YAML ({detail}); write a number, a word, "
                "or a list or mapping in brackets ([0, 0, -80], {kind: sine, ...})"
            ) from None
        set_key(data, path.strip(), parsed, f"--set {setting!r}")
    derived = load_case(data)
    derived._base_dir, derived._source_file = case._base_dir, case._source_file
    return derived


_STEP = re.compile(r"([^.\[\]]+)|\[(\d+)\]")


def case_data(case: Case | SystemCase) -> dict:
    """The mapping ``case`` was read from (a new copy): what ``set_key`` changes and
    ``load_case`` validates again."""
    return parse_yaml(case_text(case))


def set_key(data: dict, path: str, value: Any, label: str) -> None:
    """Set the key at ``path`` (written as ``with_settings`` writes it) of a case's mapping
    ``data`` to ``value`` (None removes it), in place; a CaseError starting with ``label``
    (what the user wrote: ``--set 'a.b=1'``) when the path leads nowhere."""
    steps = [(name.strip(), index) for name, index in _STEP.findall(path)]
    here: Any = data
    done = ""
    for k, (name, index) in enumerate(steps):
        last = k == len(steps) - 1
        if isinstance(here, list):
            names = [item.get("name") for item in here if isinstance(item, dict)]
            index = index or (name if name.isdigit() else "")  # ``forces.2`` as ``forces[2]``
            at = int(index) if index else (names.index(name) if name in names else None)
            if at is None or not 0 <= at < len(here):
                raise CaseError(
                    f"{label}: {done or 'the case'} has no item "
                    f"{index or repr(name)}; its items: 0 to {len(here) - 1}"
                    + (f" or by name: {', '.join(map(str, names))}" if any(names) else "")
                )
            key: Any = at
        elif isinstance(here, dict) and not index:
            if name not in here and not last:
                raise CaseError(
                    f"{label}: {done or 'the case'} has no key '{name}'; its keys: "
                    f"{', '.join(map(str, here))}"
                )
            key = name
        else:
            raise CaseError(f"{label}: {done or 'the case'} is not a list or mapping")
        if last:
            if value is None and isinstance(here, dict):
                here.pop(key, None)
            else:
                here[key] = value
        else:
            here = here[key]
        done += f"[{key}]" if isinstance(key, int) else (f".{key}" if done else key)


def _merged(data: dict, changes: dict) -> dict:
    out = dict(data)
    for key, value in changes.items():
        if value is None:
            out.pop(key, None)
        elif isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = _merged(out[key], value)
        else:
            out[key] = value
    return out


def case_text(case: Case | SystemCase) -> str:
    """The YAML text a case was loaded from, or a dump of the case when it was built in Python
    or changed since (``model_copy(update=...)``): the text of the case that runs."""
    if case._source_text is None or case._source_dump != case.model_dump(mode="json"):
        return _dumped(case)
    return case._source_text


def _dumped(case: Case | SystemCase) -> str:
    """A case as YAML, in its file's keys (a dict given in Python may hold NumPy numbers, which
    YAML cannot write: the validated case holds plain ones)."""
    return _yaml(case.model_dump(mode="json", by_alias=True, exclude_unset=True))


def record(case: Case | SystemCase) -> dict:
    """What a results file keeps of its case, besides its text, to repeat the run: every
    setting with its default resolved (``case_resolved``), and the text of every file the case
    reads (``input_files``: a YAML mapping of each file's name, as the case gives it, to its
    text)."""
    files = {table.file: table.text(case._base_dir) for _, table in instances(case, Table)}
    files |= {mesh.file: _mesh_text(mesh, case._base_dir) for _, mesh in instances(case, HullMesh)}
    out = {"case_resolved": _yaml(case.model_dump(mode="json", by_alias=True))}
    if files:
        out["input_files"] = _yaml(files)
    return out


_DUMPER = getattr(yaml, "CSafeDumper", yaml.SafeDumper)  # libyaml's: ten times faster


def _yaml(data) -> str:
    """Plain data as YAML text (safe: no Python objects), keys in their order."""
    return yaml.dump(data, Dumper=_DUMPER, sort_keys=False, allow_unicode=True)


def _mesh_text(mesh: HullMesh, base_dir) -> str:
    """A mesh file's text: an STL file (binary or not) as ASCII STL of the same triangles, to
    17 digits; another format as it is."""
    path = mesh.path(base_dir)
    if (mesh.format or path.suffix.lstrip(".")).lower() == "stl":
        return meshes.stl_text(meshes.read(path, "stl"))
    return path.read_text(encoding="utf-8")


def files_read(case: Case | SystemCase) -> list[Path]:
    """Every file a run of ``case`` reads, resolved: its case file, its table files, its mesh
    files and its hydrodynamic databases (WAMIT's .3, .3sc, .3fk and .hst beside a .1), which
    a results file must replace none of."""
    files = [Path(case._source_file)] if case._source_file else []
    return files + [path for paths in files_named(case).values() for path in paths]


def files_named(case: Case | SystemCase) -> dict[str, list[Path]]:
    """Each file name the case gives (its ``file:`` keys: tables, meshes, databases) -> the
    files it reads by that name, resolved (a WAMIT database's .1 and the .3, .3sc, .3fk and
    .hst beside it, which may not exist)."""
    named: dict[str, list[Path]] = {}
    for kind in (Table, HullMesh, HydroDatabase):
        for _, part in instances(case, kind):
            path = part.path(case._base_dir).resolve()
            beside = WAMIT_SIDE_FILES if path.suffix.lower() == ".1" else ()
            named[part.file] = [path, *(path.with_suffix(s) for s in beside)]
    return named


WAMIT_SIDE_FILES = (".3", ".3sc", ".3fk", ".hst")  # what a WAMIT database reads beside its .1


def case_base_dir(case: Case | SystemCase):
    """Directory that relative file names in the case refer to (None: current directory)."""
    return case._base_dir


# pydantic's labels of the members of a union in an error's location: ``literal['a','b']``,
# ``function-after[_check(), Model]``; never a field name
_MEMBER = re.compile(r"^[a-z][a-z-]*\[.*\]$")


def _relevant(errors: list) -> list:
    """The errors without those of a union's word (a ``Literal``) where a mapping was given:
    the mapping's own errors say what is wrong with it."""
    kept = [
        e for e in errors if not (e["type"] == "literal_error" and isinstance(e.get("input"), dict))
    ]
    return kept or errors


def format_errors(exc: ValidationError, root: Any = Case) -> str:
    """A case's problems: one line for one ("field: what is wrong ..."), else a line saying
    how many, then one line each."""
    errors = _relevant(exc.errors())
    if len(errors) == 1:
        return (_error_line(errors[0], root) + _reference(errors[0], root)).removeprefix("- ")
    lines = [f"invalid case ({len(errors)} problems):"]
    for error in errors:
        lines.append(_error_line(error, root) + _reference(error, root))
    return "\n".join(lines)


def _reference(error: dict, root: Any) -> str:
    """Where the reference documents the key an error names (the system schema's keys)."""
    if root is not SystemCase:
        return ""
    loc = tuple(error["loc"])
    if error["type"] in (BOOLEAN_ERROR, MAGNITUDE_ERROR):
        loc = (*loc, error["ctx"]["key"])
    while error["type"].startswith("union_tag") and loc and isinstance(loc[-1], int):
        loc = loc[:-1]  # a part of unknown kind: the key that lists the parts
    _, parent = _walk(loc[:-1], root) if loc else ("", None)
    key = loc[-1] if loc else None
    if parent is not None and error["type"] != "extra_forbidden":
        names = {field.alias or name: name for name, field in parent.model_fields.items()}
        if key in names:
            return f" (reference: {reference.link(parent, str(key))})"
    _, model = _walk(loc if error["type"] != "extra_forbidden" else loc[:-1], root)
    return f" (reference: {reference.link(model)})" if model is not None else ""


def _error_line(error: dict, root: Any) -> str:
    """One problem of a case as one line."""
    path, _ = _walk(error["loc"], root)
    where = path or "(top level)"
    if error["type"] == "extra_forbidden":
        key = error["loc"][-1]
        parent_path, parent = _walk(error["loc"][:-1], root)
        valid = ", ".join(_keys(parent)) if parent is not None else "?"
        return (
            f"- {parent_path or '(top level)'}: unknown key '{key}'. Valid keys: {valid}. "
            "Check the spelling or remove it"
        )
    message = error["msg"].removeprefix("Value error, ")
    if error["type"] == "missing":
        return f"- {where}: required key is missing"
    value = error.get("input")
    if error["type"] in (BOOLEAN_ERROR, MAGNITUDE_ERROR):  # by the model holding the key
        where = f"{path}.{error['ctx']['key']}" if path else str(error["ctx"]["key"])
        value = error["ctx"]["value"]
    shown = _shortened(repr(value)) if not isinstance(value, dict) else "{...}"
    if error["type"] in ("union_tag_invalid", "union_tag_not_found"):
        ctx = error.get("ctx", {})
        key = ctx.get("discriminator", "'type'").strip("'")
        allowed = ctx.get("expected_tags") or ", ".join(
            repr(t) for t in _tag_values(_annotation_at(error["loc"], root))
        )
        if "tag" in ctx:
            return f"- {where}.{key}: value {ctx['tag']!r} is not allowed; allowed: {allowed}"
        return f"- {where}.{key}: required key is missing; allowed: {allowed}"
    if isinstance(value, dict):  # a check of a whole mapping: its message names the keys
        return f"- {message}" if where == "(top level)" else f"- {where}: {message}"
    return f"- {where}: {message} (got {shown})"


def _shortened(text: str, size: int = 80) -> str:
    """An offending value as an error quotes it: never the whole input."""
    return text if len(text) <= size else f"{text[: size - 25]} ... ({len(text)} characters)"


def _walk(loc, root: Any = Case) -> tuple[str, type[BaseModel] | None]:
    """Readable path for a pydantic location and the model found at its end (tags dropped)."""
    text = ""
    annotation: Any = root
    for item in loc:
        if isinstance(item, str) and _MEMBER.match(item):
            continue  # pydantic's label of a union member (``function-after[...]``)
        model = _as_model(annotation, item)
        if model is not None and item in _tag_values(annotation):
            annotation = model
            continue
        if isinstance(item, int):
            text += f"[{item}]"
            annotation = _item_type(annotation)
            continue
        text += ("." if text else "") + str(item)
        model = _as_model(annotation)
        field = _keys(model).get(item) if model is not None else None
        annotation = field.annotation if field is not None else None
    return text, _as_model(annotation)


def _annotation_at(loc, root: Any = Case):
    """Annotation of the field at ``loc`` (for listing the allowed tags of a union)."""
    parent_path, parent = _walk(loc[:-1], root)
    field = _keys(parent).get(loc[-1]) if parent is not None else None
    return None if field is None else field.annotation


def _keys(model: type[BaseModel]) -> dict:
    """A model's fields by the key the file writes (``external forces``, ``from``)."""
    return {field.alias or name: field for name, field in model.model_fields.items()}


def _members(annotation) -> list:
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        return _members(typing.get_args(annotation)[0])
    if origin in (typing.Union, types.UnionType):
        out = []
        for arg in typing.get_args(annotation):
            out.extend(_members(arg))
        return out
    return [annotation]


def _tag_values(annotation) -> dict:
    tags = {}
    for member in _members(annotation):
        if isinstance(member, type) and issubclass(member, BaseModel):
            for tag in _TAGS:
                field = member.model_fields.get(tag)
                if field is not None:
                    for value in typing.get_args(field.annotation):
                        tags[value] = member
    return tags


def _as_model(annotation, tag=None):
    if tag is not None:
        return _tag_values(annotation).get(tag)
    for member in _members(annotation):
        if isinstance(member, type) and issubclass(member, BaseModel):
            return member
    return None


def _item_type(annotation):
    for member in _members(annotation):
        if typing.get_origin(member) is list:
            return typing.get_args(member)[0]
    return None
