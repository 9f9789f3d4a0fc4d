"""Where batches run (an operability map's chunks, a sweep's load cases): a Dask cluster, a
local one by default or any scheduler given its address. Nothing of scheduling or transport is
seacable's own: Dask's ``distributed`` does it, from the ``dask`` extra."""

import os
import re
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from seacable import files
from seacable.case import loader
from seacable.case.system import SystemCase
from seacable.errors import CaseError

LOCAL = "local"  # a cluster of this machine's cores, started and stopped with the batch
LARGEST_INPUT = 2_000_000_000  # bytes of one file a case reads, sent to the workers


def pack(case: SystemCase) -> dict:
    """What a worker needs to build ``case``, as plain data: the case's settings, and the bytes
    of each file it reads (tables, meshes, databases with WAMIT's files beside a .1) under a
    name of the batch's own (``input_<k>/<file name>``), to which the case points. Nothing of
    this machine's folders is in it: a worker that does not share this disk builds the case
    alike (``unpack``)."""
    data = case.model_dump(by_alias=True, exclude_none=True)
    renamed: dict[str, str] = {}
    contents: dict[str, bytes] = {}
    for k, (name, paths) in enumerate(loader.files_named(case).items()):
        renamed[name] = f"input_{k}/{Path(name).name}"
        for path in paths:
            if path.is_file() or path == paths[0]:  # WAMIT's side files are optional
                contents[f"input_{k}/{path.name}"] = files.read_bytes(
                    path, "input file", LARGEST_INPUT, CaseError
                )
    return {"case": _renamed(data, renamed), "files": contents}


def _renamed(data, renamed: dict[str, str]):
    """``data`` with each ``file:`` value that ``renamed`` maps replaced."""
    if isinstance(data, dict):
        return {key: renamed.get(value, value) if key == "file" and isinstance(value, str)
                else _renamed(value, renamed) for key, value in data.items()}  # fmt: skip
    if isinstance(data, list):
        return [_renamed(value, renamed) for value in data]
    return data


def unpack(packed: dict, folder) -> SystemCase:
    """The case ``pack`` made, its files written into ``folder`` (a worker's private temporary
    folder) and read from there."""
    for name, raw in packed["files"].items():
        if not re.fullmatch(r"input_\d+/[^/\\]+", name) or name.endswith(("/.", "/..")):
            raise CaseError(f"input file '{name}': not a name pack gives")
        target = Path(folder) / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(raw)
    case = loader.load_case(packed["case"])
    assert isinstance(case, SystemCase)
    case._base_dir = str(folder)
    return case


def check(scheduler: str | None) -> None:
    """Refuse a ``--dask`` value that is not 'local', None ('none') or a scheduler's address."""
    if scheduler not in (None, LOCAL) and not re.match(
        r"^(tcp|tls|inproc|ucx|ws|wss)://\S+$", scheduler
    ):
        raise CaseError(f"--dask '{scheduler}': give 'local', 'none' or a Dask scheduler's "
                        "address (tcp://host:8786, or tls:// for an encrypted one)")  # fmt: skip


@contextmanager
def client(scheduler: str, what: str) -> Iterator:
    """A ``distributed.Client`` of a local cluster (``scheduler`` 'local': one worker process
    a core, one thread each) or of the scheduler at the address ``scheduler``
    (``tcp://host:8786``), closed (and the local cluster stopped) on leaving. ``what``: the
    batch, named in the refusal when Dask is not installed."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise CaseError(
            f"{what} on Dask needs dask.distributed: pip install 'seacable[dask]' (or run it in "
            "this process: --dask none)"
        ) from None
    check(scheduler)
    cluster = None
    if scheduler == LOCAL:
        cluster = LocalCluster(n_workers=os.cpu_count() or 1, threads_per_worker=1,
                               processes=True, dashboard_address=None)  # fmt: skip
        connected = Client(cluster)
    else:
        try:
            connected = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise CaseError(
                f"--dask '{scheduler}': no Dask scheduler answers there ({exc}); give a "
                "scheduler's address (tcp://host:8786), 'local' or 'none'"
            ) from None
    try:
        yield connected
    finally:
        connected.close()
        if cluster is not None:
            cluster.close()
