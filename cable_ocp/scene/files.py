"""Reading problem files and applying ``--set`` overrides.

A problem file is UTF-8 TOML in SI units. :func:`read_problem` turns every way a file can
be unreadable (missing, a directory, not UTF-8, binary, not TOML) into one
:class:`~cable_ocp.errors.CableOCPError` that names the file and says what is wrong.
:func:`scene_kind` tells a statics, a heave and a dynamics scene apart, so that a command
given the wrong kind can say which command to use.
"""

from __future__ import annotations

import copy
import stat
import tomllib
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError

#: scene kind -> the command that runs it
COMMANDS = {"statics": "cable-ocp solve", "system": "cable-ocp solve", "heave": "cable-ocp heave",
            "dynamics": "cable-ocp simulate"}
_HEAVE_TABLES = {"sea", "vessel", "winch", "controller"}
_DYNAMICS_TABLES = {"top_motion", "simulation", "unit", "modes"}
_STATICS_TABLES = {"environment", "cable", "end_a", "end_b"}
#: the largest problem file read, bytes (the shipped ones are a few kB; a long top-motion
#: series of 1e5 rows is about 4 MiB)
MAX_PROBLEM_BYTES = 16 * 2**20


def read_problem(path: str | Path) -> dict[str, Any]:
    """Read a TOML problem file into a dictionary.

    Raises
    ------
    CableOCPError
        When the file is missing, a directory, not a regular file (a FIFO, a device),
        larger than :data:`MAX_PROBLEM_BYTES`, unreadable, not UTF-8 or not valid TOML.
    """
    path = Path(path)
    name = str(path)
    if not path.exists():
        raise CableOCPError(f"problem file {name!r} not found")
    if path.is_dir():
        raise CableOCPError(f"problem file {name!r} is a directory: give a .toml file in it, "
                            "e.g. problems/dezoysa_sea_buggy.toml")
    try:
        st = path.stat()
    except OSError as exc:
        raise CableOCPError(f"problem file {name!r} cannot be read: {exc.strerror}") from None
    if not stat.S_ISREG(st.st_mode):
        # a FIFO would block the open forever, a device (/dev/zero) read without end
        raise CableOCPError(f"problem file {name!r} is not a regular file (a pipe, a device "
                            "or a socket); give a .toml file")
    if st.st_size > MAX_PROBLEM_BYTES:
        raise CableOCPError(f"problem file {name!r} is {st.st_size} bytes; a problem file is at "
                            f"most {MAX_PROBLEM_BYTES // 2**20} MiB of UTF-8 TOML")
    try:
        with path.open("rb") as fh:
            raw = fh.read(MAX_PROBLEM_BYTES + 1)
    except OSError as exc:
        raise CableOCPError(f"problem file {name!r} cannot be read: {exc.strerror}") from None
    if len(raw) > MAX_PROBLEM_BYTES:  # grew while it was read
        raise CableOCPError(f"problem file {name!r} is larger than "
                            f"{MAX_PROBLEM_BYTES // 2**20} MiB; a problem file is UTF-8 TOML")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        col = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        raise CableOCPError(
            f"problem file {name!r} is not UTF-8 text: byte 0x{raw[exc.start]:02x} at line "
            f"{line}, column {col}; a problem file is UTF-8 TOML") from None
    if "\x00" in text:
        raise CableOCPError(f"problem file {name!r} is binary (it contains NUL bytes); a "
                            "problem file is UTF-8 TOML")
    if not text.strip():
        raise CableOCPError(f"problem file {name!r} is empty; a problem file is UTF-8 TOML "
                            "(see problems/ for examples)")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CableOCPError(f"problem file {name!r} is not valid TOML: {exc}") from None


def scene_kind(data: dict[str, Any]) -> str:
    """``"system"`` (a ``lines`` array), ``"heave"``, ``"dynamics"`` or ``"statics"``, from
    the tables a problem has."""
    if "lines" in data:
        return "system"
    if _HEAVE_TABLES & set(data):
        return "heave"
    if _DYNAMICS_TABLES & set(data):
        return "dynamics"
    return "statics"


def check_kind(data: dict[str, Any], expected: str, path: str | Path | None = None) -> None:
    """Raise when a problem of another kind is given to the command for ``expected``.

    Parameters
    ----------
    data : dict
        The problem as read by :func:`read_problem`. A problem with no table of any kind
        passes (its scene parser names what is missing).
    expected : str
        The kind the command runs: ``"statics"``, ``"heave"`` or ``"dynamics"``.
    path : str or Path, optional
        The problem file, named in the message; None (default): the message says "this is".
    """
    kind = scene_kind(data)
    if kind == "statics" and not _STATICS_TABLES & set(data):
        return  # no table of any kind: the scene's own parser names what is missing
    if kind != expected:
        what = f"{str(path)!r} is" if path is not None else "this is"
        raise CableOCPError(f"{what} a {kind} scene, not a {expected} scene: use "
                            f"`{COMMANDS[kind]}`")


def parse_override(text: str) -> tuple[str, Any]:
    """Parse ``key=value`` (value in TOML syntax; bare words are strings).

    Examples: ``end_b.position=[0,229,183]``, ``cable.length=free``, ``solver.degree=4``.
    """
    if "=" not in text:
        raise CableOCPError(f"--set {text!r}: expected key=value, e.g. cable.length=305")
    key, value = text.split("=", 1)
    key = key.strip()
    if not key:
        raise CableOCPError(f"--set {text!r}: empty key")
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    return key, parsed


def apply_overrides(data: dict[str, Any], overrides: dict[str, Any]) -> dict[str, Any]:
    """Return a copy of ``data`` with dotted-key overrides set (tables are created; an
    integer part indexes an array of tables, e.g. ``cable.segments.0.length``).

    Parameters
    ----------
    data : dict
        The problem as read by :func:`read_problem`; not modified (deep-copied).
    overrides : dict
        Dotted key -> value, e.g. from :func:`parse_override`; the value replaces (or adds)
        the entry as is, in the units of the problem file (SI).
    """
    out = copy.deepcopy(data)
    for key, value in overrides.items():
        parts = key.split(".")
        node = out
        for p in parts[:-1]:
            if isinstance(node, list):  # an array of tables: cable.segments.0.length
                if not p.isdigit() or int(p) >= len(node):
                    raise CableOCPError(f"--set {key}: {p} is not an index 0..{len(node) - 1}")
                nxt = node[int(p)]
            else:
                nxt = node.setdefault(p, {})
            if not isinstance(nxt, (dict, list)):
                raise CableOCPError(f"--set {key}: {p} is not a table")
            node = nxt
        if isinstance(node, list):
            raise CableOCPError(f"--set {key}: give an index and a key, e.g. "
                                "cable.segments.0.length=1000")
        node[parts[-1]] = value
    return out
