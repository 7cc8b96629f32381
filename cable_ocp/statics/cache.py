"""On-disk cache of the CasADi functions a statics solver builds.

Building the collocated residual, its Jacobian and the Newton step (and IPOPT, when a
solve falls back to it) costs more than a solve on coarse meshes. The functions depend
only on the scene's *structure* (which terms, cable properties, which end components are
fixed, the current profile), on the scales chosen for it and on the mesh, not on the end
values, the length, the tension or the current scale (those are parameters). So a second
process solving a scene of the same structure loads them (``casadi.Function.deserialize``)
instead of building them.

Where: ``$CABLE_OCP_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/cable_ocp``, else
``~/.cache/cable_ocp``. ``CABLE_OCP_CACHE=0`` switches the cache off (no reads, no
writes).

Safety: an entry is one file named by the SHA-256 of its key: a JSON header line (the
key, the names, the payload's length and SHA-256), then the functions serialised
together (``casadi.StringSerializer``, shared sub-functions once). The key holds the
cache format, the versions of cable_ocp and CasADi, a hash of the source files that
define the equations (so an edited formulation never meets functions built by the old
one), the structure, the scales and the mesh; it is stored in full in the file and
compared on load. The payload's length and checksum are checked *before* anything is
deserialised. A file that is missing, unreadable, truncated,
altered or written for another key is a miss: the functions are rebuilt and the entry is
rewritten. Writes go to a temporary file in the same folder, then ``os.replace`` (atomic),
so a reader never sees half a file; a folder that cannot be written is skipped silently.
At most :data:`MAX_ENTRIES` entries and :data:`MAX_BYTES` bytes are kept (least recently
used removed first: entries of older versions, never read again, go first), and an entry
larger than :data:`MAX_ENTRY_BYTES` (IPOPT on a very fine mesh) is not stored.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import json
import os
from pathlib import Path

import casadi as ca

from cable_ocp.numerics.atomic import replace_atomically
from cable_ocp.version import __version__

#: bump when the layout of an entry or the meaning of the stored functions changes
FORMAT = 1
MAGIC = "cable_ocp statics function cache"
MAX_ENTRIES = 256
#: most bytes of all entries together (the interval functions take 0.1-0.5 MB per scene
#: structure and mesh, IPOPT's whole-mesh graph 3-50 MB)
MAX_BYTES = 256 * 2**20
#: largest entry stored
MAX_ENTRY_BYTES = 64 * 2**20
SUFFIX = ".casadi"
ENV_SWITCH = "CABLE_OCP_CACHE"
ENV_DIR = "CABLE_OCP_CACHE_DIR"

#: the modules whose code defines the cached functions (their hash is part of the key)
_SOURCES = ("statics/formulation.py", "statics/collocation.py", "statics/mesh.py",
            "statics/shooting.py", "statics/newton.py", "statics/ipopt.py", "statics/cache.py",
            "physics")


def cache_dir() -> Path | None:
    """The cache folder, or None when ``CABLE_OCP_CACHE`` switches the cache off."""
    if os.environ.get(ENV_SWITCH, "1").strip().lower() in ("0", "false", "no", "off"):
        return None
    where = os.environ.get(ENV_DIR)
    if where:
        return Path(where).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg).expanduser() if xdg else Path.home() / ".cache") / "cable_ocp"


@functools.lru_cache(maxsize=1)
def code_version() -> str:
    """cable_ocp and CasADi versions and a hash of the equation-defining sources."""
    root = Path(__file__).resolve().parents[1]
    h = hashlib.sha256()
    for rel in _SOURCES:
        path = root / rel
        files = sorted(path.glob("*.py")) if path.is_dir() else [path]
        for f in files:
            h.update(f.relative_to(root).as_posix().encode())
            with contextlib.suppress(OSError):
                h.update(f.read_bytes())
    return f"cable_ocp {__version__}; casadi {ca.__version__}; sources {h.hexdigest()[:20]}"


def entry_key(structure: str, role: str) -> str:
    """The full key of an entry: format, versions, role and the caller's structure text.

    Parameters
    ----------
    structure : str
        The caller's text of everything the functions depend on (the scene's structure,
        scales, transcription and mesh; e.g. a ``repr`` of a tuple), stored verbatim.
    role : str
        What the functions are for (e.g. ``"blocks"``, ``"ipopt"``); it also names the
        entry's file, so that one structure can hold several entries.
    """
    return f"format {FORMAT}\n{code_version()}\nrole {role}\n{structure}"


def _path(folder: Path, key: str, role: str) -> Path:
    return folder / f"{hashlib.sha256(key.encode()).hexdigest()[:40]}-{role}{SUFFIX}"


def load(structure: str, role: str) -> dict[str, ca.Function] | None:
    """The functions stored for (structure, role), or None (miss, cache off, or an entry
    that fails any check: it is never deserialised then).

    Parameters
    ----------
    structure : str
        The structure text the entry was saved under (see :func:`entry_key`).
    role : str
        The role the entry was saved under (e.g. ``"blocks"``, ``"ipopt"``).
    """
    folder = cache_dir()
    if folder is None:
        return None
    key = entry_key(structure, role)
    path = _path(folder, key, role)
    try:
        raw = path.read_bytes()
        head, sep, payload = raw.partition(b"\n")
        if not sep:
            return None
        header = json.loads(head.decode("utf-8"))
        if not (isinstance(header, dict) and header.get("magic") == MAGIC
                and header.get("format") == FORMAT and header.get("key") == key
                and isinstance(header.get("names"), list)
                and header.get("bytes") == len(payload)
                and header.get("sha256") == hashlib.sha256(payload).hexdigest()):
            return None
        names = header["names"]
        fns = ca.StringDeserializer(payload.decode("ascii")).unpack()
        if not (isinstance(fns, list) and len(fns) == len(names)
                and all(isinstance(f, ca.Function) for f in fns)):
            return None
        out = dict(zip(names, fns, strict=True))
    except (OSError, ValueError, KeyError, TypeError, RuntimeError, UnicodeDecodeError):
        return None
    with contextlib.suppress(OSError):
        os.utime(path)  # most recently used
    return out


def save(structure: str, role: str, functions: dict[str, ca.Function]) -> bool:
    """Store the functions for (structure, role) as one serialised bundle (shared parts
    once); True when written.

    Parameters
    ----------
    structure : str
        The structure text to file the entry under (see :func:`entry_key`).
    role : str
        The role to file the entry under (e.g. ``"blocks"``, ``"ipopt"``).
    functions : dict of str to casadi.Function
        The functions by name; :func:`load` returns them under the same names. Nothing
        is stored (False) when they cannot be serialised, the bundle exceeds
        :data:`MAX_ENTRY_BYTES`, the cache is off or the folder cannot be written.
    """
    folder = cache_dir()
    if folder is None:
        return False
    key = entry_key(structure, role)
    names = list(functions)
    try:
        ser = ca.StringSerializer()
        ser.pack([functions[n] for n in names])
        payload = ser.encode().encode("ascii")
    except (RuntimeError, UnicodeEncodeError):  # cannot be serialised: nothing to store
        return False
    if len(payload) > MAX_ENTRY_BYTES:
        return False
    header = json.dumps({"magic": MAGIC, "format": FORMAT, "key": key, "names": names,
                         "bytes": len(payload),
                         "sha256": hashlib.sha256(payload).hexdigest()})
    path = _path(folder, key, role)
    content = header.encode("utf-8") + b"\n" + payload
    try:
        folder.mkdir(parents=True, exist_ok=True)
        # not flushed to the disk: a cut entry fails its length or checksum and is rebuilt
        replace_atomically(path, lambda tmp: Path(tmp).write_bytes(content))
    except OSError:
        return False
    _evict(folder)
    return True


def _evict(folder: Path) -> None:
    """Keep the most recently used entries, at most :data:`MAX_ENTRIES` of them and
    :data:`MAX_BYTES` together (the newest entry is always kept)."""
    entries = []
    for p in folder.glob("*" + SUFFIX):
        with contextlib.suppress(OSError):
            st = p.stat()
            entries.append((st.st_mtime, st.st_size, p))
    entries.sort(reverse=True)  # most recently used first
    count = total = 0
    for _, size, p in entries:
        count += 1
        total += size
        if count > 1 and (count > MAX_ENTRIES or total > MAX_BYTES):
            with contextlib.suppress(OSError):
                p.unlink()


def clear() -> int:
    """Remove every entry of the cache folder; the number removed."""
    folder = cache_dir()
    if folder is None or not folder.is_dir():
        return 0
    n = 0
    for p in folder.glob("*" + SUFFIX):
        with contextlib.suppress(OSError):
            p.unlink()
            n += 1
    return n
