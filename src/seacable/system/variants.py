"""The evaluation compiled for the kinds of component a system holds (``system.evaluation``).

``features(p)`` names what a system holds: its kinds of line (lumped-mass, 3D rigid segments,
planar rigid links, natural strings), ties, compensators, force models with states, and the
force models that have a flag of their own. For each set, ``variant`` writes a copy of the
template ``system/evaluation.py`` with those flags, under a name made of a digest of the
template, the flags and the package's compiled sources (so that an edited kernel gives a new
copy, never a stale cache), in the seacable cache folder (``cache_folder``), imports it and
compiles its entries (``kernel.ENTRIES``) for the system's types; numba caches them on disk
beside the copy, shared by every process. ``bind(p)`` gives the parameters the entries'
addresses (``SystemParams.entries``), through which every caller reaches them
(``system.kernel``'s trampolines, ``kernels.indirect``).
"""

import hashlib
import importlib.util
import os
import sys
import tempfile
import threading
from pathlib import Path
from types import ModuleType
from typing import Any, NamedTuple

import numba
import numpy as np
from numba import types

from seacable.forces import kinds
from seacable.kernels import helper, jit, records, stamp
from seacable.system import evaluation, kernel, outputs

PACKAGE = Path(__file__).resolve().parents[1]
TEMPLATE = Path(evaluation.__file__)
FLAGS_START, FLAGS_END = "# FLAGS:", "# END FLAGS"
LINE_FLAGS = ("LUMPED", "SEGMENTS", "PLANAR", "GROUPS", "TIP_JOINTS", "NATURAL", "TIES",
              "COMPENSATORS", "STATES", "WAVES", "FAILURES")  # fmt: skip
# each force model's flag; None: compiled into every copy (gravity and buoyancy: a fraction of a
# second; each of the others costs 0.5 to 1.4 s of compiling, and a new combination of them
# compiles only the copy's own functions, the models' kernels being cached apart)
FORCE_FLAG: dict[int, str | None] = {
    kinds.GRAVITY: None,
    kinds.BUOYANCY: None,
    kinds.DRAG: "F_DRAG",
    kinds.FLUID_INERTIA: "F_FLUID_INERTIA",
    kinds.ROD: "F_ROD",
    kinds.APPLIED: "F_APPLIED",
    kinds.LINEAR_STIFFNESS: "F_STIFFNESS",
    kinds.LINEAR_DAMPING: "F_DAMPING",
    kinds.QUADRATIC_DAMPING: "F_DAMPING",
    kinds.SERVO: "F_SERVO",
    kinds.NON_LINEAR_HYDROSTATIC: "F_MESH",
    kinds.NON_LINEAR_FROUDE_KRYLOV: "F_MESH",
    kinds.RADIATION_DAMPING: "F_RADIATION_DAMPING",
    kinds.DIFFRACTION: "F_DIFFRACTION",
    kinds.WAVE_DRIFT: "F_WAVE_DRIFT",
    kinds.THRUSTER: "F_THRUSTER",
    kinds.RUDDER: "F_RUDDER",
    kinds.PROPELLER: "F_PROPELLER",
    kinds.FIN: "F_FIN",
    kinds.WIND: "F_COEFFICIENTS",
    kinds.CURRENT: "F_COEFFICIENTS",
    kinds.SHORT_WING: "F_HULL_CURRENT",
    kinds.CROSS_FLOW: "F_HULL_CURRENT",
    kinds.COMPENSATOR: None,  # the compensators: COMPENSATORS
}
FORCE_FLAGS = tuple(dict.fromkeys(flag for flag in FORCE_FLAG.values() if flag is not None))


class Variant(NamedTuple):
    """A compiled copy of the evaluation: its module and its entries' addresses
    (``kernel.ENTRIES``)."""

    module: ModuleType
    entries: np.ndarray


_variants: dict[tuple[str, ...], Variant] = {}
_lock = threading.Lock()
_fallback: list[Path] = []  # the cache folder when no user folder can be written


def features(p: kernel.SystemParams) -> tuple[str, ...]:
    """The flags of ``system.evaluation`` a system needs: those of the kinds it holds."""
    lumped, planar, segments, natural, _ = kernel.present(p)  # one place for these kinds
    held = {
        "LUMPED": lumped is not None,
        "SEGMENTS": segments is not None,
        "PLANAR": planar is not None,
        "GROUPS": len(p.group_member) > 0,
        "TIP_JOINTS": len(p.rs_tip_joint) > 0,
        "NATURAL": natural is not None,
        "TIES": len(p.tie_from) > 0,
        "COMPENSATORS": len(p.compensator) > 0,
        "STATES": int(p.n_s) > 0,
        "WAVES": p.wave.shape[1] > 0,
        "FAILURES": len(p.fail_line) > 0,
    }
    present = {FORCE_FLAG[int(k)] for k in np.asarray(p.force_kind)}
    on = [name for name in LINE_FLAGS if held[name]]
    return tuple(on + [name for name in FORCE_FLAGS if name in present])


def describe(flags: tuple[str, ...]) -> str:
    """The kinds a copy compiles, for a person ("lumped-mass lines; ties; forces: ...")."""
    words = {"LUMPED": "lumped-mass lines", "SEGMENTS": "3D rigid-segment lines",
             "PLANAR": "planar rigid-link lines", "GROUPS": "groups of bodies",
             "TIP_JOINTS": "joints at lines' ends", "NATURAL": "natural strings",
             "TIES": "ties", "COMPENSATORS": "compensators",
             "STATES": "force models' states", "WAVES": "waves on the lines",
             "FAILURES": "line failures"}  # fmt: skip
    parts = [words[f] for f in flags if f in words]
    forces = [f[2:].lower().replace("_", " ") for f in flags if f.startswith("F_")]
    parts.append("forces: " + ", ".join(["the common ones", *forces]))
    return "; ".join(parts)


def cache_folder() -> Path:
    """Where the copies are written: ``SEACABLE_CACHE_DIR``, else ``NUMBA_CACHE_DIR``'s
    ``seacable`` folder, else the user's cache folder (``XDG_CACHE_HOME`` or ``~/.cache``)
    ``/seacable``; a temporary folder when none can be written."""
    given = os.environ.get("SEACABLE_CACHE_DIR")
    if given:
        candidates = [Path(given)]
    else:
        candidates = []
        if os.environ.get("NUMBA_CACHE_DIR"):
            candidates.append(Path(os.environ["NUMBA_CACHE_DIR"]) / "seacable")
        home = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
        candidates.append(Path(home) / "seacable")
    for folder in candidates:
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError:
            continue
        if os.access(folder, os.W_OK):
            return folder
    if not _fallback:  # one temporary folder a process, not one a call
        _fallback.append(Path(tempfile.mkdtemp(prefix="seacable-cache-")))
    return _fallback[0]


def source(flags: tuple[str, ...]) -> str:
    """The template's text with its flags set: True for ``flags``, False for the others."""
    text = TEMPLATE.read_text()
    start = text.index(FLAGS_START)
    start = text.index("\n", start) + 1
    end = text.index(FLAGS_END)
    lines = [f"{name} = {name in flags}\n" for name in LINE_FLAGS + FORCE_FLAGS]
    return text[:start] + "".join(lines) + text[end:]


def _module(flags: tuple[str, ...]) -> ModuleType:
    """The copy of the evaluation for ``flags``, written once (never rewritten: numba keys its
    cache by the file's time stamp) and imported."""
    text = source(flags)
    digest = hashlib.sha256((stamp.sources_digest() + text).encode()).hexdigest()[:20]
    name = f"seacable_evaluation_{digest}"
    if name in sys.modules:
        return sys.modules[name]
    path = cache_folder() / f"{name}.py"
    if not path.exists():
        partial = path.with_name(f".{name}.{os.getpid()}.tmp")
        partial.write_text(text)
        os.replace(partial, path)  # whole or absent, whoever writes it at the same time
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def _address(dispatcher: Any, signature: tuple) -> int:
    """The native entry of ``dispatcher`` compiled (or loaded from the cache) for
    ``signature``."""
    dispatcher.compile(signature)
    result = dispatcher.overloads[signature]
    if types.unliteral(result.signature.return_type) != types.int64:
        raise TypeError(f"{dispatcher.py_func.__qualname__} must return an int64 status")
    return int(result.library.get_pointer_to_function(result.fndesc.llvm_func_name))


def _signatures(p: kernel.SystemParams) -> tuple[kernel.SystemParams, kernel.SystemWork, dict]:
    """The parameters ``p`` unbound, a workspace of theirs, and the signatures of the copy's
    entries (``kernel.ENTRIES``) and parts (``kernel.PARTS``: the evaluate entry's)."""
    bound = p._replace(entries=np.zeros(len(kernel.ENTRIES) + len(kernel.PARTS), dtype=np.int64))
    w = kernel.make_work(bound)
    vector = numba.typeof(np.zeros(1))
    pt, wt = numba.typeof(bound), numba.typeof(w)  # their types; their records not built
    table = numba.typeof(w.pos)
    return (
        bound,
        w,
        {
            "evaluate": (types.float64, vector, pt, wt, vector),
            "body_forces": (types.float64, vector, pt, wt, table, table, vector, table),
            "project": (vector, pt),
            "after_step": (types.float64, vector, pt, wt),
            "start_memory": (types.float64, vector, pt, wt),
        },
    )


# the evaluation's parts in the order of the jobs: the longest to compile at the two ends, the
# shortest where the two processes meet, so that neither waits long for the other's last one
JOB_ORDER = ("_motions", "_models", "_masses", "_lines", "_solve", "_backward")
assert sorted(JOB_ORDER) == sorted(kernel.PARTS)


def jobs(p: kernel.SystemParams) -> list[helper.Job]:
    """What a first run of ``p`` compiles before its evaluation's entries, as it needs them:
    the compiled constructors of its two records, the parts of the evaluation, the outputs.
    Each is compiled apart and cached on disk, so that two processes can share them
    (``kernels.helper``); the entries then link them."""
    return _jobs(_module(features(p)), *_signatures(p))


def _jobs(module: ModuleType, bound, w, signatures: dict) -> list[helper.Job]:
    evaluate = signatures["evaluate"]
    return [
        (records._pack, records.pack_signature(bound)),
        (records._pack, records.pack_signature(w)),
        *((getattr(module, name), evaluate) for name in JOB_ORDER if module.USED[name]),
        (outputs.outputs_chunk, outputs.signature(bound, w)),
    ]


def variant(p: kernel.SystemParams) -> Variant:
    """The compiled copy of the evaluation for the kinds ``p`` holds (compiled once a process,
    loaded from numba's cache when another process compiled it; compiled on two cores when
    nothing of it is cached: ``jobs``, ``kernels.helper``)."""
    flags = features(p)
    found = _variants.get(flags)
    if found is not None:
        return found
    with _lock:
        if flags in _variants:
            return _variants[flags]
        module = _module(flags)
        bound, w, signatures = _signatures(p)
        with jit.announced(f"the evaluation of {describe(flags)}", "about 10 to 30 s"):
            wanted = not helper.cached((module.evaluate, signatures["evaluate"]))
            todo = _jobs(module, bound, w, signatures)  # the helper's: jobs(bound)
            helper.compile_all(todo, (__name__, "jobs", (bound,)), wanted)
            parts = [_address(getattr(module, name), signatures["evaluate"])
                     if module.USED[name] else 0 for name in kernel.PARTS]  # fmt: skip
            entries = [_address(getattr(module, name), signatures[name])
                       for name in kernel.ENTRIES]  # fmt: skip
        _variants[flags] = Variant(module, np.array(entries + parts, dtype=np.int64))
        return _variants[flags]


def bind(p: kernel.SystemParams) -> kernel.SystemParams:
    """``p`` with the addresses of the evaluation compiled for its kinds."""
    return p._replace(entries=variant(p).entries.copy())
