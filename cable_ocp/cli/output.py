"""The output contract that every ``cable-ocp`` command shares.

Exit codes (the same for every subcommand)
------------------------------------------
0    success
1    computed, but not a success: the JSON ``status`` says which and ``message`` why
2    the user's input is wrong (file, key, value, option, output path); one line names it
     and says what would be valid; found before any solve
3    an internal error: one line, plus "rerun with --debug for the traceback"
130  interrupted (Ctrl-C or SIGTERM), after writing the rows and results already finished;
     a result that an interruption cut short is never written as if it were whole

Outputs
-------
* ``--json PATH`` writes strict JSON (no NaN or Infinity: ``null`` where a number does not
  exist) whose top level always has ``status``, ``message``, ``warnings`` and the package
  ``version``; ``--json -`` prints the JSON alone on stdout (no table, no progress there).
* ``--csv PATH`` writes a table with the unit of every column in its header; ``-`` is stdout.
* ``--plot PATH`` saves a figure in the format of its suffix (png, pdf, svg, ...).
* Output paths and plot formats are checked before any computation; every file written is
  confirmed on stderr (``wrote PATH``).
* Anything that runs longer than about two seconds shows a progress bar on stderr when
  stderr is a terminal; ``--quiet`` turns the bar and the confirmations off.
* A run whose estimated cost is above 10 min of CPU or 4 GB of memory
  (:mod:`cable_ocp.cli.cost`) is refused with exit 2 and the estimate, unless ``--force``.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import io
import json
import math
import os
import sys
import threading
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.numerics.atomic import replace_atomically, write_text_file
from cable_ocp.numerics.jsonable import json_safe
from cable_ocp.status import Status

EXIT_OK = 0
EXIT_NOT_SUCCESS = 1
EXIT_INPUT = 2
EXIT_INTERNAL = 3
EXIT_INTERRUPTED = 130

STDOUT = "-"


def version() -> str:
    """The package version (also ``cable-ocp --version``)."""
    from cable_ocp import __version__

    return __version__


# --------------------------------------------------------------------------------------
# Options shared by the subcommands
# --------------------------------------------------------------------------------------

def common_parent() -> argparse.ArgumentParser:
    """Options every subcommand takes (``--quiet``, ``--debug``)."""
    p = argparse.ArgumentParser(add_help=False)
    g = p.add_argument_group("common options")
    g.add_argument("--quiet", action="store_true",
                   help="no progress bar and no 'wrote PATH' confirmations on stderr")
    g.add_argument("--debug", action="store_true",
                   help="print the full traceback of an internal error")
    return p


def add_set_option(p: argparse.ArgumentParser) -> None:
    """``--set KEY=VALUE`` (repeatable), the dotted-key overrides of a problem file."""
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a key of the problem file with a dotted name and a TOML "
                        "value, e.g. --set end_b.position=[0,229,183] (repeatable)")


def add_json_option(p: argparse.ArgumentParser, what: str) -> None:
    """``--json PATH`` ('-' = stdout).

    Parameters
    ----------
    p : argparse.ArgumentParser
        The (sub)command's parser the option is added to.
    what : str
        What the JSON holds, for the help text (``"write {what} as JSON"``).
    """
    p.add_argument("--json", metavar="PATH",
                   help=f"write {what} as JSON; '-' prints the JSON alone on stdout")


def add_csv_option(p: argparse.ArgumentParser, what: str) -> None:
    """``--csv PATH`` ('-' = stdout).

    Parameters
    ----------
    p : argparse.ArgumentParser
        The (sub)command's parser the option is added to.
    what : str
        What the table holds, for the help text (``"write {what} as CSV"``).
    """
    p.add_argument("--csv", metavar="PATH",
                   help=f"write {what} as CSV (units in the header); '-' = stdout")


def add_plot_option(p: argparse.ArgumentParser, what: str) -> None:
    """``--plot PATH`` (format from the suffix).

    Parameters
    ----------
    p : argparse.ArgumentParser
        The (sub)command's parser the option is added to.
    what : str
        What the figure shows, for the help text (``"save {what}"``).
    """
    p.add_argument("--plot", metavar="PATH",
                   help=f"save {what}; the format follows the suffix (png, pdf, svg, ...)")


def add_force_option(p: argparse.ArgumentParser) -> None:
    """``--force``: run even when the estimated cost is above the limits."""
    p.add_argument("--force", action="store_true",
                   help="run even when the estimated cost is above the limits (10 min of "
                        "CPU, 4 GB of memory; see docs/cli.md)")


def check_cost(args: argparse.Namespace, cost: Any) -> None:
    """Exit 2 before any work when ``cost`` (:class:`cable_ocp.cli.cost.Cost`) is above
    the limits, unless ``--force``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line; its ``force`` attribute (``--force``, False when absent)
        lets a costly run go ahead.
    cost : Cost
        The run's estimated CPU time and memory (:mod:`cable_ocp.cli.cost`).
    """
    from cable_ocp.cli.cost import check_cost as check

    check(cost, force=getattr(args, "force", False))


def overrides(args: argparse.Namespace) -> dict[str, Any]:
    """The ``--set`` overrides as a dict (parsed like TOML values)."""
    from cable_ocp.scene import parse_override

    return dict(parse_override(s) for s in getattr(args, "overrides", None) or [])


# --------------------------------------------------------------------------------------
# Output paths, checked before any computation
# --------------------------------------------------------------------------------------

def plot_formats() -> list[str]:
    """File suffixes matplotlib can save (png, pdf, svg, ...)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    return sorted(FigureCanvasAgg(Figure()).get_supported_filetypes())


def check_output_path(path: str | None, option: str, *, allow_stdout: bool = True,
                      formats: Sequence[str] | None = None) -> None:
    """Raise :class:`CableOCPError` unless ``path`` can be written.

    ``-`` (stdout) is accepted where ``allow_stdout``; otherwise the parent directory must
    exist and be writable, the path must not be a directory nor another file that is not a
    regular one (a device such as /dev/full, a pipe: the whole-or-nothing write renames a
    temporary file over the path, which would replace it), and, with ``formats``, the
    suffix must be one of them.

    Parameters
    ----------
    path : str or None
        The output path as given; None (option not given) passes, ``"-"`` is stdout.
    option : str
        The option's name for the message, e.g. ``"--json"``.
    allow_stdout : bool
        Accept ``"-"`` (default True); False for outputs that must be files (figures).
    formats : sequence of str, optional
        Valid file suffixes, lower case without the dot (e.g. :func:`plot_formats`); None
        (default): any suffix.
    """
    if path is None:
        return
    if path == STDOUT:
        if not allow_stdout:
            raise CableOCPError(f"{option} -: this output cannot go to stdout; give a file name")
        return
    p = Path(path)
    if not path or p.is_dir() or path.endswith(("/", os.sep)):
        raise CableOCPError(f"{option} {path}: is a directory; give a file name")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise CableOCPError(f"{option} {path}: the directory {str(parent)!r} does not exist")
    if p.exists() and not p.is_file():
        # a device or a pipe: the atomic rename would replace it by a regular file
        raise CableOCPError(f"{option} {path}: is not a regular file; give a file name, or - "
                            "for stdout" if allow_stdout else
                            f"{option} {path}: is not a regular file; give a file name")
    if not os.access(parent, os.W_OK) or (p.exists() and not os.access(p, os.W_OK)):
        raise CableOCPError(f"{option} {path}: not writable")
    if formats is not None:
        suffix = p.suffix.lower().lstrip(".")
        if suffix not in formats:
            raise CableOCPError(
                f"{option} {path}: format {suffix or '(none)'!r} is not supported; give a "
                f"file name ending in one of: {', '.join('.' + f for f in formats)}")


def check_outputs(args: argparse.Namespace,
                  extra: Sequence[tuple[str, str | os.PathLike[str]]] = (),
                  inputs: Sequence[tuple[str, str | os.PathLike[str] | None]] = ()) -> None:
    """Check every output option the command has (``json``, ``csv``, ``plot``, ``netcdf``)
    and that no two outputs, and no output and an input (the problem file ``file``, and
    ``inputs``), are one file.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line.
    extra : sequence of (str, path)
        More outputs of the command, ``(option, path)`` (e.g. the batch store's files),
        for the collision check.
    inputs : sequence of (str, path or None)
        More files the command reads, ``(what, path)`` (e.g. ``("[unit] cable_scene",
        path)``); None paths are skipped.
    """
    check_output_path(getattr(args, "json", None), "--json")
    check_output_path(getattr(args, "csv", None), "--csv")
    if getattr(args, "plot", None) is not None:
        check_output_path(args.plot, "--plot", allow_stdout=False, formats=plot_formats())
    if getattr(args, "json", None) == STDOUT and getattr(args, "csv", None) == STDOUT:
        raise CableOCPError("--json - and --csv -: only one output can go to stdout")
    outputs = [(opt, getattr(args, opt.lstrip("-"), None))
               for opt in ("--json", "--csv", "--plot", "--netcdf")] + list(extra)
    seen: dict[str, str] = {}
    problem = getattr(args, "file", None)
    if isinstance(problem, str) and problem:
        seen[os.path.realpath(problem)] = "the problem file"
    for what, path in inputs:
        if path is not None:
            seen.setdefault(os.path.realpath(path), f"the input {what} {path}")
    for opt, path in outputs:
        if path is None or str(path) == STDOUT:
            continue
        key = os.path.realpath(path)
        if key in seen:
            raise CableOCPError(f"{opt} {path}: the same file as {seen[key]}; give each "
                                "output its own file")
        seen[key] = f"{opt} {path}"


def stdout_free(args: argparse.Namespace) -> bool:
    """True when stdout may carry text (no ``--json -`` / ``--csv -``)."""
    return STDOUT not in (getattr(args, "json", None), getattr(args, "csv", None))


# --------------------------------------------------------------------------------------
# Writing
# --------------------------------------------------------------------------------------

def envelope(status: str, message: str, data: dict[str, Any] | None = None,
             warnings: Sequence[str] = ()) -> dict[str, Any]:
    """The top level of every JSON output: status, message, warnings, version, then
    ``data`` (whose own ``status``/``message``/``warnings`` keys, if any, are replaced).

    Parameters
    ----------
    status : str
        The run's status, e.g. ``"solved"`` or ``"ok"`` for a success, ``"interrupted"``,
        or the command's failure status: a member of :class:`cable_ocp.status.Status`
        (anything else is a bug and raises ``ValueError``).
    message : str
        One line saying what happened or why it failed.
    data : dict, optional
        The command's results, appended after the envelope's keys; its ``status``,
        ``message``, ``warnings`` and ``version`` keys are dropped. None (default): none.
    warnings : sequence of str
        Warnings of the run, as a list in the JSON (default none).
    """
    out: dict[str, Any] = {"status": Status(status), "message": message,
                           "warnings": list(warnings), "version": version()}
    for key, value in (data or {}).items():
        if key not in out:
            out[key] = value
    return out


def json_text(obj: Any) -> str:
    """Strict JSON text (``allow_nan=False`` after
    :func:`cable_ocp.numerics.jsonable.json_safe`)."""
    return json.dumps(json_safe(obj), indent=2, allow_nan=False)


def confirm(args: argparse.Namespace, path: str, what: str = "") -> None:
    """``wrote PATH`` on stderr (not with ``--quiet``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line; its ``quiet`` attribute (False when absent) silences the line.
    path : str
        The file written.
    what : str
        What the file is (``"JSON"``, ``"CSV"``, ``"figure"``), shown in parentheses; empty
        (default): nothing shown.
    """
    if not getattr(args, "quiet", False):
        print(f"wrote {path}" + (f" ({what})" if what else ""), file=sys.stderr)


def write_output(option: str, path: str, write: Callable[[str], Any]) -> None:
    """Write the output file ``path`` whole or not at all: ``write(tmp)`` on a temporary
    file beside it, then a rename (:func:`cable_ocp.numerics.atomic.replace_atomically`).

    Parameters
    ----------
    option : str
        The option that named the file, for the message (e.g. ``"--json"``).
    path : str
        The file.
    write : callable
        ``write(tmp_path)`` writes the whole content to ``tmp_path``.

    Raises
    ------
    CableOCPError
        When the file cannot be written (a full disk, a file-size limit, a vanished
        directory: CONVENTIONS "Exit codes", exit 2): naming the path and the reason; the
        earlier file is kept and no partial file is left.
    """
    with output_errors(option, path):
        replace_atomically(path, write)


@contextlib.contextmanager
def output_errors(option: str, path: str) -> Iterator[None]:
    """Around a library writer that writes ``path`` whole or not at all (e.g.
    :func:`cable_ocp.numerics.export.write_netcdf`): its ``OSError`` becomes the
    :class:`CableOCPError` of :func:`write_output` (exit 2, the path and the reason).

    Parameters
    ----------
    option : str
        The option that named the file, for the message.
    path : str
        The file.
    """
    existed = Path(path).exists()
    try:
        yield
    except OSError as exc:
        why = exc.strerror or str(exc) or type(exc).__name__
        kept = "the earlier file is kept" if existed else "no file was written"
        raise CableOCPError(f"{option} {path}: could not be written ({why}); {kept}") from exc


def _write(args: argparse.Namespace, path: str, text: str, what: str, option: str) -> None:
    """``text`` to stdout (``path`` ``"-"``, no confirmation) or to the file ``path``
    (whole or not at all: :func:`write_output`), confirmed (:func:`confirm`) as ``what``."""
    if path == STDOUT:
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_output(option, path, lambda tmp: write_text_file(tmp, text))
        confirm(args, path, what)


def emit_json(args: argparse.Namespace, obj: dict[str, Any], path: str | None = None) -> None:
    """Write ``obj`` as strict JSON to ``path`` (default ``args.json``); '-' = stdout.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line: ``json`` is the default path, ``quiet`` silences the
        confirmation.
    obj : dict
        The output, usually an :func:`envelope`; NaN and infinities become null
        (:func:`cable_ocp.numerics.jsonable.json_safe`).
    path : str, optional
        Where to write (``"-"``: stdout, without a confirmation); None (default):
        ``args.json``, and nothing is written when that is not set either.
    """
    if obj.get("status") != Status.INTERRUPTED:
        interrupt.check()  # a Ctrl-C that CasADi swallowed: the result is not written
    path = path or args.json
    if path:
        _write(args, path, json_text(obj) + "\n", "JSON", "--json")


def csv_text(header: Sequence[str], rows: Sequence[Sequence[Any]]) -> str:
    """CSV text; non-finite numbers are written as empty cells.

    Parameters
    ----------
    header : sequence of str
        Column names, each with its unit (e.g. ``"t [s]"``).
    rows : sequence of sequence
        The rows; a finite float is written with ``repr`` (full precision), None and a
        non-finite float as an empty cell, anything else as ``csv`` writes it.
    """
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for row in rows:
        w.writerow(["" if v is None else (repr(float(v)) if isinstance(v, (float, np.floating))
                                           and math.isfinite(v) else
                                           "" if isinstance(v, (float, np.floating)) else v)
                    for v in row])
    return buf.getvalue()


def emit_csv(args: argparse.Namespace, header: Sequence[str], rows: Sequence[Sequence[Any]],
             path: str | None = None, partial: bool = False) -> None:
    """Write a CSV table to ``path`` (default ``args.csv``); '-' = stdout.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line: ``csv`` is the default path, ``quiet`` silences the
        confirmation.
    header : sequence of str
        Column names, each with its unit.
    rows : sequence of sequence
        The rows, as :func:`csv_text` writes them.
    path : str, optional
        Where to write (``"-"``: stdout, without a confirmation); None (default):
        ``args.csv``, and nothing is written when that is not set either.
    partial : bool
        The rows finished before an interruption (written although one is pending);
        default False: an interruption pending is raised instead (nothing written).
    """
    if not partial:
        interrupt.check()
    path = path or args.csv
    if path:
        _write(args, path, csv_text(header, rows), "CSV", "--csv")


def emit_plot(args: argparse.Namespace, draw: Callable[[str], Any],
              path: str | None = None) -> None:
    """Call ``draw(path)`` (which saves the figure) and confirm it.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line: ``plot`` is the default path, ``quiet`` silences the
        confirmation.
    draw : callable
        ``draw(path)`` draws and saves the figure at ``path`` (format from the suffix).
    path : str, optional
        Where to save; None (default): ``args.plot``, and nothing is drawn when that is not
        set either.
    """
    interrupt.check()
    path = path or args.plot
    if not path:
        return
    write_output("--plot", path, draw)
    confirm(args, path, "figure")


def say(args: argparse.Namespace, text: str) -> None:
    """Human-readable text on stdout, unless stdout carries JSON or CSV.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line (``--json -`` or ``--csv -`` keep stdout for themselves).
    text : str
        The text, printed with a newline.
    """
    if stdout_free(args):
        print(text)


def warn(text: str) -> None:
    """One warning line on stderr, ``warning: TEXT`` (also with ``--quiet``: a warning is
    not a progress report or a confirmation)."""
    print(f"warning: {' '.join(text.split())}", file=sys.stderr)


def note(args: argparse.Namespace, text: str) -> None:
    """A remark on stderr (not with ``--quiet``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line; its ``quiet`` attribute (False when absent) silences the remark.
    text : str
        The remark, printed with a newline.
    """
    if not getattr(args, "quiet", False):
        print(text, file=sys.stderr)


# --------------------------------------------------------------------------------------
# Progress
# --------------------------------------------------------------------------------------

#: a progress line in a pipe or a log at least every this many seconds ...
PROGRESS_EVERY_S = 10.0
#: ... or when this fraction more of the work is done, but never more than one a second
PROGRESS_EVERY_FRACTION = 0.1
PROGRESS_MIN_S = 1.0
#: the bar's width on a terminal that reports no width (0 columns)
FALLBACK_COLUMNS = 80


def _clock_text(seconds: float) -> str:
    return f"{seconds:.0f} s" if seconds < 600 else f"{seconds / 60:.0f} min"


class ProgressLines:
    """Progress as short lines on a stream that is not a terminal (a pipe, a log): one line
    when :data:`PROGRESS_EVERY_S` have passed since the last, or when
    :data:`PROGRESS_EVERY_FRACTION` more of the total is done (at most one line per
    :data:`PROGRESS_MIN_S`), and a last line at :meth:`close` if any was written. A command
    that prepares for a while before its first step (identifications, designs) calls
    :meth:`tick` from a timer: a ``preparing`` line every :data:`PROGRESS_EVERY_S` of silence.

    Parameters
    ----------
    stream : file-like
        Where the lines go (``sys.stderr``).
    total : int
        Number of steps expected (a call may change it).
    desc, unit : str
        What runs and the name of one step.
    clock : callable
        Seconds, monotonic (default :func:`time.monotonic`; a test injects its own).
    """

    def __init__(self, stream: Any, total: int, desc: str, unit: str,
                 clock: Callable[[], float] | None = None) -> None:
        import time

        self.stream, self.total, self.desc, self.unit = stream, max(int(total), 0), desc, unit
        self.clock = clock or time.monotonic
        self.start = self.last_t = self.clock()
        self.last_done = 0
        self.done = 0
        self.postfix: str | None = None
        self.lines = 0
        self.first: tuple[float, int] | None = None
        self._lock = threading.Lock()  # the timer's tick and the steps write one at a time

    def _write(self, now: float, last: bool = False) -> None:
        with self._lock:
            self._write_line(now, last)

    def _write_line(self, now: float, last: bool) -> None:
        total = max(self.total, 1)
        elapsed = now - self.start
        text = (f"cable-ocp: {self.desc}: {self.done}/{self.total} {self.unit} "
                f"({100.0 * self.done / total:.0f} %), {_clock_text(elapsed)}")
        if self.first is None and not last:  # no step reported yet: the total is not known
            text = f"cable-ocp: {self.desc}: preparing, {_clock_text(elapsed)}"
        elif last:
            text += " (done)" if self.done >= self.total else " (stopped)"
        elif self.first is not None and self.first[1] < self.done < self.total:
            # the rate since the first report (not since the start: a command may prepare
            # for a while before its first step)
            rate = (self.done - self.first[1]) / max(now - self.first[0], 1e-9)
            text += f", ~{_clock_text((self.total - self.done) / rate)} left"
        if self.postfix:
            text += f", {self.postfix}"
        print(text, file=self.stream, flush=True)
        self.lines += 1
        self.last_t, self.last_done = now, self.done

    def __call__(self, done: int, total: int | None = None, postfix: str | None = None
                 ) -> None:
        """Record ``done`` steps (and a new ``total``, a ``postfix``); write a line when due.

        Parameters
        ----------
        done : int
            Steps finished.
        total : int, optional
            A new total.
        postfix : str, optional
            A short text after the line (e.g. failures).
        """
        if total is not None:
            self.total = max(int(total), 0)
        if postfix is not None:
            self.postfix = postfix
        self.done = int(done)
        now = self.clock()
        if self.first is None:
            self.first = (now, self.done)
        since = now - self.last_t
        frac = (self.done - self.last_done) / max(self.total, 1)
        if since >= PROGRESS_EVERY_S or (frac >= PROGRESS_EVERY_FRACTION
                                         and since >= PROGRESS_MIN_S):
            self._write(now)

    def tick(self) -> None:
        """A line when :data:`PROGRESS_EVERY_S` have passed since the last (or the start)
        without one: the heartbeat of a command that is still preparing or in a long step."""
        now = self.clock()
        if now - self.last_t >= PROGRESS_EVERY_S:
            self._write(now)

    def close(self) -> None:
        """The last line, if any line was written (a short run writes none)."""
        if self.lines:
            self._write(self.clock(), last=True)


def bar_columns(stream: Any) -> int:
    """The width of a progress bar on the terminal ``stream``: its columns, or
    :data:`FALLBACK_COLUMNS` where it reports none (tqdm draws nothing at 0 columns).

    Parameters
    ----------
    stream : file-like
        The terminal (``sys.stderr``).
    """
    try:
        cols = os.get_terminal_size(stream.fileno()).columns
    except (AttributeError, ValueError, OSError, io.UnsupportedOperation):
        cols = 0
    return cols if cols > 0 else FALLBACK_COLUMNS


@contextlib.contextmanager
def progress(args: argparse.Namespace, total: int, desc: str, unit: str = "it",
             stream: Any = None, clock: Callable[[], float] | None = None
             ) -> Iterator[Callable[..., None]]:
    """Progress on stderr for ``total`` steps, as a callback, for every command.

    The callback is a checkpoint of interruptions (:func:`cable_ocp.numerics.interrupt.check`,
    also with ``--quiet``: a Ctrl-C that CasADi swallowed stops there) and takes
    ``(done, total=None, postfix=None)``: the number of steps finished,
    optionally a new total, and a short text shown after the bar (e.g. failures). On a
    terminal a tqdm bar shows what runs, done/total, elapsed and remaining time (its width
    the terminal's, 80 columns where the terminal reports none); in a pipe or a log, short
    lines (:class:`ProgressLines`: every ~10 s or 10 %). Nothing with ``--quiet``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line; its ``quiet`` attribute (False when absent) turns the
        progress off.
    total : int
        Number of steps expected (the callback may change it).
    desc : str
        What runs, shown before the bar.
    unit : str
        Name of one step, shown in the rate (default ``"it"``).
    stream : file-like, optional
        Where the progress goes (default ``sys.stderr``).
    clock : callable, optional
        The clock of the lines in a pipe (default :func:`time.monotonic`).
    """
    stream = sys.stderr if stream is None else stream
    if getattr(args, "quiet", False):
        yield lambda done, total=None, postfix=None: interrupt.check()
        return
    if not (hasattr(stream, "isatty") and stream.isatty()):
        lines = ProgressLines(stream, total, desc, unit, clock)

        def step(done: int, total: int | None = None, postfix: str | None = None) -> None:
            interrupt.check()
            lines(done, total, postfix)

        stop = threading.Event()
        if clock is None:  # real time: a timer keeps the lines coming through silent phases
            def beat() -> None:
                while not stop.wait(PROGRESS_MIN_S):
                    lines.tick()

            threading.Thread(target=beat, name="cable-ocp progress", daemon=True).start()
        try:
            yield step
        finally:
            stop.set()
        lines.close()  # not after an exception: an interruption says so in one line
        return
    from tqdm import tqdm

    bar = tqdm(total=total, desc=desc, unit=unit, file=stream, leave=False,
               ncols=bar_columns(stream), smoothing=0.1)

    def update(done: int, total: int | None = None, postfix: str | None = None) -> None:
        interrupt.check()
        if total is not None and total != bar.total:
            bar.total = total
        bar.n = done
        if postfix is not None:
            bar.set_postfix_str(postfix, refresh=False)
        bar.refresh()

    try:
        yield update
    finally:
        bar.close()
