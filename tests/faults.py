"""Faults the tests impose on this process (helpers shared by the fault tests)."""

from __future__ import annotations

import contextlib
import resource
import signal
from collections.abc import Iterator


@contextlib.contextmanager
def file_size_limit(limit: int) -> Iterator[None]:
    """This process's writes fail past ``limit`` bytes inside the block (EFBIG, as a full
    disk fails them with ENOSPC; SIGXFSZ ignored): the soft limit only, restored after.

    Parameters
    ----------
    limit : int
        Largest file size a write may reach, bytes.
    """
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    old = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (limit, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, (soft, hard))
        signal.signal(signal.SIGXFSZ, old)
