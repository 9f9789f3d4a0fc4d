"""Where batches run (an operability map's chunks, a sweep's load cases): a Dask cluster, a
local one by default or any scheduler given its address. Nothing of scheduling or transport is
seacable's own: Dask's ``distributed`` does it, from the ``dask`` extra."""

import os
import re
from collections.abc import Iterator
from contextlib import contextmanager

from seacable.errors import CaseError

LOCAL = "local"  # a cluster of this machine's cores, started and stopped with the batch


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
