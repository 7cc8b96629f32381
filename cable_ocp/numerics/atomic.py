"""Write a file whole or not at all: through a temporary file beside it, then a rename.

A write that fails part-way (a full disk, a file-size limit, Ctrl-C) leaves the earlier
file as it was and no temporary file behind (CONVENTIONS "Exit codes": an output that
cannot be written is found after the solve and the earlier file is kept). The rename is
atomic on one file system, which is why the temporary file is made in the target's own
directory. The new file gets the earlier file's permissions, or the umask's for a new one.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

__all__ = ["replace_atomically", "write_text_atomically", "write_text_file"]


def _mode_for(target: Path) -> int:
    """The permission bits the written file should get."""
    try:
        return target.stat().st_mode & 0o7777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def replace_atomically(path: str | os.PathLike[str], write: Callable[[str], Any]) -> Path:
    """Call ``write(tmp)`` on a temporary file beside ``path``, then rename it onto ``path``.

    Parameters
    ----------
    path : str or path-like
        The file to write (its directory must exist). Its suffix is kept on the temporary
        file, so that writers that pick the format from it (matplotlib, netCDF) still do.
    write : callable
        ``write(tmp_path)`` writes the whole content to the file ``tmp_path`` (str).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    OSError
        What ``write`` or the rename raised (e.g. ``ENOSPC``): ``path`` is then unchanged and
        the temporary file removed. Any other exception of ``write`` (and a
        KeyboardInterrupt) leaves ``path`` unchanged too.
    """
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=f".part{target.suffix}",
                               dir=directory)
    os.close(fd)
    try:
        write(tmp)
        os.chmod(tmp, _mode_for(target))
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    return target


def write_text_file(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` (UTF-8, newlines as given) to ``path`` and flush it to the disk (the
    writer of :func:`write_text_atomically`; on its own it is not atomic).

    Parameters
    ----------
    path : str or path-like
        The file, usually a temporary one.
    text : str
        Its whole content.
    """
    with open(path, "w", encoding="utf-8", newline="") as fh:
        fh.write(text)
        fh.flush()
        os.fsync(fh.fileno())


def write_text_atomically(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` whole or not at all (:func:`replace_atomically`).

    Parameters
    ----------
    path : str or path-like
        The file to write.
    text : str
        Its whole content.
    """
    return replace_atomically(path, lambda tmp: write_text_file(tmp, text))
