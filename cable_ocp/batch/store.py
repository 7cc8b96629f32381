"""Batch results on disk, written as they arrive: ``OUT.jsonl`` (one JSON object per case,
appended per row), ``OUT.csv`` (the same rows as a table, units in the header),
``OUT.meta.json`` (the batch's inputs and the units of every column) and, while a batch
runs, ``OUT.lock``.

Rows are keyed by case index: cases with identical parameters (``--grid k=40,40,40``) are
separate cases, each with its own seed and row; a row's ``duplicate_of`` names the first
case with the same parameters. Every file is strict JSON (no NaN or Infinity: a value that
is not a finite number is ``null``).

Only one batch writes to an ``OUT`` at a time: it holds an exclusive lock on ``OUT.lock``
(``fcntl.flock``, released by the kernel when the process ends, however it ends) and a
second one is refused. An interrupted batch resumes from the JSON lines, after its inputs
(problem file digest, ``--set``, grids, ranges, random keys, samples, seed, options,
cable_ocp version) are checked against the meta file: rows already there are kept and
their cases skipped; a line cut short by the interruption is dropped with every line after
it; a line that is JSON but not a row of this batch, a second row for a case, and a
``worker_lost`` row are dropped (their cases run again), each counted in :attr:`Store.notes`.
At the end the CSV is rewritten in case order from the rows, one row per case.

A write that fails (a full disk, a file-size limit) raises :class:`CableOCPError` naming
the file and the reason (CLI exit 2): the lines already written stay intact (a row half
appended is cut off again) and the batch can continue with ``--resume``.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import hashlib
import io
import json
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.atomic import write_text_atomically
from cable_ocp.numerics.jsonable import json_safe

FIXED = ["case", "status", "message"]
TAIL = ["wall_time [s]", "case_id", "duplicate_of"]
#: statuses whose cases run again on ``--resume``
RETRIED = ("worker_lost",)
#: the meta file's layout (``format``); a meta file of another layout cannot be resumed
FORMAT = 2
#: the inputs a resume must share with the batch it continues, in the order checked
INPUTS = ("version", "problem", "files", "kind", "command", "set", "grid", "range", "random",
          "samples", "seed", "options", "cases")


def paths(out: str | Path) -> tuple[Path, Path, Path]:
    """(CSV, JSON lines, meta) for ``out`` (a ``.csv`` or ``.jsonl`` suffix is optional)."""
    base = _base(out)
    return (base.with_name(base.name + ".csv"), base.with_name(base.name + ".jsonl"),
            base.with_name(base.name + ".meta.json"))


def lock_path(out: str | Path) -> Path:
    """``OUT.lock``, the file a running batch holds locked."""
    base = _base(out)
    return base.with_name(base.name + ".lock")


def _base(out: str | Path) -> Path:
    out = Path(out)
    return out.with_suffix("") if out.suffix.lower() in (".csv", ".jsonl") else out


def default_out(problem: str | Path) -> Path:
    """The default ``--out``: the problem file's stem and ``_batch``, in the current
    directory (``problems/x.toml`` -> ``x_batch.csv``, ``.jsonl``, ``.meta.json``)."""
    return Path(Path(problem).stem + "_batch")


def strict_json(value: Any, indent: int | None = None) -> str:
    """``value`` as strict JSON text (:func:`cable_ocp.numerics.jsonable.json_safe`: a
    number that is not finite becomes ``null``; ``allow_nan=False``).

    Parameters
    ----------
    value : Any
        A row, the meta record, ...
    indent : int, optional
        As :func:`json.dumps`; None (default): one line.
    """
    return json.dumps(json_safe(value), indent=indent, allow_nan=False, default=str)


def sha256_file(path: str | Path) -> str:
    """The SHA-256 digest (hex) of a file's bytes."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def sha256_data(data: Any) -> str:
    """The SHA-256 digest (hex) of a value's canonical strict JSON (sorted keys)."""
    text = json.dumps(json_safe(data), sort_keys=True, separators=(",", ":"),
                      allow_nan=False, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


# --------------------------------------------------------------------------------------
# What differs between two batches' inputs
# --------------------------------------------------------------------------------------

def _v(value: Any) -> str:
    return json.dumps(value) if isinstance(value, (str, list, dict)) else str(value)


def _sweep(option: str, entries: Any) -> str:
    if not entries:
        return "none"
    parts = []
    for e in entries:
        if option == "range":
            parts.append(f"{e[0]}={_v(e[1][0])}:{_v(e[1][-1])}:{len(e[1])}" if e[1]
                         else f"{e[0]}=")
        elif option == "random":
            parts.append(f"{e[0]}={e[1]}({_v(e[2][0])},{_v(e[2][1])})")
        else:
            parts.append(f"{e[0]}=" + ",".join(_v(x) for x in e[1]))
    return " ".join(parts)


def differences(old: dict[str, Any], new: dict[str, Any]) -> list[str]:
    """What differs between the inputs recorded in two meta records (:data:`INPUTS`), one
    phrase each, e.g. ``"problem file digest differs"`` or ``"--set x=1 vs x=2"``.

    Parameters
    ----------
    old : dict
        The meta record of the stored batch (as read from ``OUT.meta.json``).
    new : dict
        The meta record of the batch that would continue it.
    """
    old, new = json_safe(old), json.loads(strict_json(new))
    out: list[str] = []
    for key in INPUTS:
        a, b = old.get(key), new.get(key)
        if a == b:
            continue
        if key == "problem":
            a, b = a or {}, b or {}
            if a.get("sha256") != b.get("sha256"):
                out.append(f"problem file digest differs (sha256 {str(a.get('sha256'))[:12]} of "
                           f"{a.get('path')} then, {str(b.get('sha256'))[:12]} of {b.get('path')}"
                           " now)")
        elif key == "files":  # other files the problem reads ([unit] cable_scene)
            a, b = a or {}, b or {}
            for k in sorted(set(a) | set(b)):
                fa, fb = a.get(k) or {}, b.get(k) or {}
                if fa.get("sha256") != fb.get("sha256"):
                    out.append(f"{k} digest differs (sha256 {str(fa.get('sha256'))[:12]} of "
                               f"{fa.get('path')} then, {str(fb.get('sha256'))[:12]} of "
                               f"{fb.get('path')} now)")
        elif key == "set":
            a, b = a or {}, b or {}
            for k in sorted(set(a) | set(b)):
                if k not in b:
                    out.append(f"--set {k}={_v(a[k])} then, not now")
                elif k not in a:
                    out.append(f"--set {k}={_v(b[k])} now, not then")
                elif a[k] != b[k]:
                    out.append(f"--set {k}={_v(a[k])} vs {k}={_v(b[k])}")
        elif key in ("grid", "range", "random"):
            out.append(f"--{key} {_sweep(key, a)} vs {_sweep(key, b)}")
        elif key == "version":
            out.append(f"cable_ocp version {a} vs {b}")
        elif key == "cases":
            if not out:  # the cases follow from the inputs above: named only when alone
                out.append("the cases differ")
        else:
            out.append(f"{'--' if key in ('samples', 'seed', 'command') else ''}{key} "
                       f"{_v(a)} vs {_v(b)}")
    return out


# --------------------------------------------------------------------------------------
# The lock
# --------------------------------------------------------------------------------------

def _take_lock(path: Path, base: Path) -> int | None:
    """An exclusive, non-blocking ``flock`` on ``path`` (created if need be); the file
    descriptor, or None where ``fcntl`` is missing (Windows: no lock)."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not on POSIX
        return None
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_CLOEXEC", 0), 0o666)
        except OSError as exc:
            raise _write_error(path, exc, "") from exc
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            if exc.errno not in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK):
                os.close(fd)
                raise
            holder = ""
            with contextlib.suppress(OSError, ValueError):
                holder = os.read(fd, 64).decode().strip()
            os.close(fd)
            who = f" (process {holder})" if holder.isdigit() else ""
            raise CableOCPError(
                f"--out {base}: another batch is writing there{who}, holding {path}; wait "
                "for it to end (then --resume continues it), or give another --out"
            ) from None
        # a batch that just ended removes its lock file: lock the file that is on disk
        try:
            same = os.stat(path).st_ino == os.fstat(fd).st_ino
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)
    with contextlib.suppress(OSError):
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n".encode())
    return fd


def _write_error(path: Path, exc: OSError, kept: str) -> CableOCPError:
    why = exc.strerror or str(exc) or type(exc).__name__
    return CableOCPError(f"--out {path}: could not be written ({why}){kept}")


# --------------------------------------------------------------------------------------
# The store
# --------------------------------------------------------------------------------------

class Store:
    """Append-as-you-go storage of one batch (see the module docstring).

    Parameters
    ----------
    out : str or Path
        Base path of the results: ``OUT.csv``, ``OUT.jsonl``, ``OUT.meta.json`` and, while
        the batch runs, ``OUT.lock`` are written next to it (a ``.csv`` or ``.jsonl``
        suffix is dropped first).
    meta : dict
        The batch record, written to ``OUT.meta.json``: ``columns`` (the CSV header, in
        order) and ``cases`` (the overrides of each case, in order) are required; with
        ``resume``, its :data:`INPUTS` must equal those of the stored batch.
    resume : bool
        Continue the batch already at ``out``: keep its rows (:attr:`done`, by case index;
        see the module docstring for what is dropped). Default False.
    overwrite : bool
        Replace results already at ``out``; without it or ``resume`` (default False), such
        results are an error.
    case_ids : sequence of str, optional
        Each case's :attr:`cable_ocp.batch.cases.Case.case_id`, in order: a stored row must
        carry its case's identifier to be kept. None (default): derived from ``cases``.

    Raises
    ------
    CableOCPError
        Another batch holds ``OUT.lock``; results there without ``resume``/``overwrite``;
        a resume whose meta file is damaged or whose inputs differ (the message says what
        differs); a file that cannot be written.
    """

    def __init__(self, out: str | Path, meta: dict[str, Any], resume: bool = False,
                 overwrite: bool = False, case_ids: Sequence[str] | None = None) -> None:
        self.csv_path, self.jsonl_path, self.meta_path = paths(out)
        self.lock_path = lock_path(out)
        self.meta = meta
        self.columns = list(meta["columns"])
        self.done: dict[int, dict[str, Any]] = {}
        self.notes: list[str] = []
        self._fds: dict[Path, int] = {}
        self._lock = _take_lock(self.lock_path, _base(out))
        try:
            self._open(resume, overwrite, case_ids)
        except BaseException:
            self.close()
            raise

    def _open(self, resume: bool, overwrite: bool, case_ids: Sequence[str] | None) -> None:
        exists = self.jsonl_path.exists() or self.csv_path.exists()
        if resume and self.jsonl_path.exists():
            if case_ids is None:
                case_ids = [json.dumps(c, sort_keys=True, separators=(",", ":"))
                            for c in self.meta["cases"]]
            self._check_meta()
            self._load(list(case_ids))
        elif exists and not (resume or overwrite):
            raise CableOCPError(
                f"--out {self.csv_path}: results of a batch are already there; give --resume "
                "to continue that batch, --overwrite to replace it, or another --out")
        else:
            self._replace(self.jsonl_path, "")
        self._replace(self.meta_path, strict_json(self.meta, indent=2) + "\n")
        self._replace(self.csv_path, self._csv_text(self._sorted()))
        for path in (self.jsonl_path, self.csv_path):
            try:
                self._fds[path] = os.open(path, os.O_WRONLY | os.O_APPEND
                                          | getattr(os, "O_CLOEXEC", 0))
            except OSError as exc:
                raise _write_error(path, exc, "") from exc

    def _check_meta(self) -> None:
        """Refuse a resume whose meta file is damaged or records other inputs."""
        advice = ("start afresh with --overwrite (the rows there are replaced) or give "
                  "another --out")
        try:
            text = self.meta_path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise CableOCPError(f"--resume: {self.meta_path} is missing, so the rows in "
                                f"{self.jsonl_path} cannot be checked against this batch's "
                                f"inputs; {advice}") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise CableOCPError(f"--resume: {self.meta_path} cannot be read ({exc}); "
                                f"{advice}") from None
        try:
            old = json.loads(text)
            why = "" if isinstance(old, dict) else f"holds {type(old).__name__}, not a record"
        except json.JSONDecodeError as exc:
            why = "empty" if not text.strip() else f"not JSON: {exc.msg} at line {exc.lineno}"
        if not why and old.get("format") != FORMAT:
            why = ("written by another cable_ocp version, without the record of its inputs"
                   if "format" not in old else f"format {old.get('format')!r}, not {FORMAT}")
        if not why and not all(k in old for k in INPUTS):
            why = "the record of the inputs is incomplete"
        if why:
            raise CableOCPError(f"--resume: {self.meta_path} is damaged ({why}); {advice}")
        diff = differences(old, self.meta)
        if diff:
            raise CableOCPError(
                f"--resume: {self.jsonl_path} holds a batch run with other inputs: "
                + "; ".join(diff) + "; give the same inputs to continue it, or --overwrite "
                "or another --out to start afresh")

    def _load(self, case_ids: list[str]) -> None:
        """Keep the stored rows of this batch's cases (see the module docstring)."""
        good: list[str] = []
        bad: list[int] = []
        twice: list[int] = []
        retried: list[int] = []
        cut = 0
        with self.jsonl_path.open(encoding="utf-8", errors="replace") as fh:
            lines = fh.readlines()
        for number, line in enumerate(lines, 1):
            if not line.strip():
                continue
            try:
                row = json.loads(line)
            except json.JSONDecodeError:
                # a line cut short by the interruption: drop it and what follows
                cut = len(lines) - number + 1
                break
            index = row.get("case") if isinstance(row, dict) else None
            if not (isinstance(index, int) and not isinstance(index, bool)
                    and 0 <= index < len(case_ids) and row.get("case_id") == case_ids[index]
                    and isinstance(row.get("status"), str)):
                bad.append(number)
            elif index in self.done:
                twice.append(index)
            elif row["status"] in RETRIED:
                retried.append(index)
            else:
                good.append(line if line.endswith("\n") else line + "\n")
                self.done[index] = row
        name = self.jsonl_path
        if cut:
            self.notes.append(f"{name}: a line cut short dropped (line {len(lines) - cut + 1})"
                              + (f" with the {cut - 1} after it" if cut > 1 else "")
                              + "; their cases run again")
        if bad:
            self.notes.append(f"{name}: {len(bad)} line(s) that are not rows of this batch "
                              f"dropped (line {', '.join(map(str, bad[:5]))}"
                              + (", ..." if len(bad) > 5 else "") + ")")
        if twice:
            self.notes.append(f"{name}: {len(twice)} second row(s) of a case dropped (case "
                              f"{', '.join(map(str, twice[:5]))}" + (", ..." if len(twice) > 5
                                                                     else "") + ")")
        if retried:
            self.notes.append(f"{len(retried)} {RETRIED[0]} case(s) run again (case "
                              f"{', '.join(map(str, retried[:5]))}"
                              + (", ..." if len(retried) > 5 else "") + ")")
        if "".join(good) != "".join(lines):  # a line dropped, or the last one ended
            self._replace(self.jsonl_path, "".join(good))

    def _replace(self, path: Path, text: str) -> None:
        try:
            write_text_atomically(path, text)
        except OSError as exc:
            kept = "; the earlier file is kept" if path.exists() else ""
            raise _write_error(path, exc, kept) from exc

    def _sorted(self) -> list[dict[str, Any]]:
        return [self.done[k] for k in sorted(self.done)]

    def _cells(self, row: dict[str, Any]) -> list[Any]:
        return ["" if row.get(self._key(c)) is None else row.get(self._key(c))
                for c in self.columns]

    def _csv_text(self, rows: Sequence[dict[str, Any]], header: bool = True) -> str:
        buf = io.StringIO()
        w = csv.writer(buf)
        if header:
            w.writerow(self.columns)
        for row in rows:
            w.writerow(self._cells(row))
        return buf.getvalue()

    @staticmethod
    def _key(column: str) -> str:
        return "wall_time_s" if column == "wall_time [s]" else column

    def _append(self, path: Path, text: str) -> None:
        """Append ``text`` whole, or cut the file back to where it was and raise."""
        fd = self._fds[path]
        data = memoryview(text.encode("utf-8"))
        start = os.lseek(fd, 0, os.SEEK_END)
        try:
            while data:
                data = data[os.write(fd, data):]
        except OSError as exc:
            with contextlib.suppress(OSError):
                os.ftruncate(fd, start)
            raise _write_error(path, exc, (
                f"; the {len(self.done)} finished rows are kept in {self.jsonl_path}: make "
                "room, then continue with --resume")) from exc

    def add(self, row: dict[str, Any]) -> None:
        """Append one row (keyed by its ``case`` index) to both files.

        Raises
        ------
        CableOCPError
            A file cannot be written (a full disk): the earlier lines are intact.
        """
        row = json.loads(strict_json(row))
        self._append(self.jsonl_path, strict_json(row) + "\n")
        self.done[row["case"]] = row
        self._append(self.csv_path, self._csv_text([row], header=False))

    def finish(self) -> list[dict[str, Any]]:
        """Close the files, rewrite the CSV in case order and release the lock; returns the
        rows, in case order."""
        rows = self._sorted()
        try:
            self._close_files()
            # whole or not at all: a full disk keeps the CSV the rows were appended to
            self._replace(self.csv_path, self._csv_text(rows))
        finally:
            self.close()
        return rows

    def abort(self) -> None:
        """:meth:`finish` as far as it goes (after an interruption or an error): never
        raises for a file that cannot be written."""
        try:
            self.finish()
        except CableOCPError:
            self.close()

    def _close_files(self) -> None:
        for fd in self._fds.values():
            with contextlib.suppress(OSError):
                os.close(fd)
        self._fds.clear()

    def close(self) -> None:
        """Close the files and release the lock (rows already written stay)."""
        self._close_files()
        if self._lock is not None:
            with contextlib.suppress(OSError):
                os.unlink(self.lock_path)
            with contextlib.suppress(OSError):
                os.close(self._lock)
            self._lock = None
