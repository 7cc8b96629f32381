"""Ctrl-C as one interruption, wherever it lands.

A Ctrl-C (SIGINT) reaches Python as :class:`KeyboardInterrupt`, except where native code
takes it first:

* Inside an IPOPT solve the Ctrl-C is caught by CasADi's check in a callback (a
  ``KeyboardInterruptException`` warning on stderr, return status
  ``NonIpopt_Exception_Thrown``) or by IPOPT's own handler (``User_Requested_Stop``); no
  ``KeyboardInterrupt`` is raised, and a caller that retries a failed solve would go on.
  :func:`call_solver` runs the solve and turns either back into one, without the warning.
* CasADi's own loops (``rootfinder``, ``mapaccum`` of a Newton step) poll Python's signals
  and turn the ``KeyboardInterrupt`` into a ``RuntimeError`` whose message ends in
  ``KeyboardInterrupt``. :func:`is_interruption` recognises it.

Retry loops and fallbacks ("this solve failed, try another start", "compiling failed, use
the interpreted function") therefore solve through :func:`call_solver` and call
:func:`reraise_interruption` in their ``except Exception`` blocks: an interruption is never
retried. :func:`requested` says whether one has happened in this process; the command line
installs :func:`install` (SIGINT and SIGTERM record the request, then raise
``KeyboardInterrupt``) so that it also knows after native code swallowed the exception.

During ``python -m cable_ocp`` / ``cable-ocp`` start-up (the imports, before the command
line's own handler is in place) :func:`defer_during_launch` records a Ctrl-C without raising
it, so that no import traceback is printed; the command line checks it (:func:`check`) as
soon as it starts.
"""

from __future__ import annotations

import contextlib
import io
import os
import signal
import sys
import threading
from collections.abc import Iterator
from types import FrameType
from typing import Any

__all__ = ["IPOPT_STOP", "call_solver", "check", "clear", "defer_during_launch", "install",
           "deferred", "is_interruption", "reraise_interruption", "requested", "signals_blocked"]

#: IPOPT's return status after a Ctrl-C during its solve
IPOPT_STOP = "User_Requested_Stop"
#: what CasADi prints when a callback saw a Ctrl-C (the solve then fails, silently)
_CASADI_CAUGHT = "KeyboardInterruptException"

#: the signals that interrupt a command: Ctrl-C and a polite kill
SIGNALS = (signal.SIGINT, signal.SIGTERM)

_requested = False
_deferred = 0  # depth of deferred() contexts: the handler records instead of raising


def requested() -> bool:
    """Whether an interruption has been requested in this process (a signal caught by
    :func:`install`'s handler, or seen by :func:`check_ipopt` / :func:`is_interruption`)."""
    return _requested


def _request() -> None:
    global _requested
    _requested = True


def clear() -> None:
    """Forget an interruption (for a process that goes on, e.g. an interactive session)."""
    global _requested
    _requested = False


def check() -> None:
    """Raise :class:`KeyboardInterrupt` if an interruption has been requested (not inside
    :func:`deferred`, which raises it at its end)."""
    if _requested and not _deferred:
        raise KeyboardInterrupt


def call_solver(solver: Any, **kwargs: Any) -> tuple[dict[str, Any], dict[str, Any]]:
    """Call a CasADi solver (``nlpsol``, ``conic``) and return its result and ``stats()``;
    raise :class:`KeyboardInterrupt` instead if a Ctrl-C stopped it.

    A Ctrl-C during the solve reaches either IPOPT's own handler (return status
    ``User_Requested_Stop``) or CasADi's check inside a callback, which prints a
    ``KeyboardInterruptException`` warning on ``sys.stderr`` and ends the solve with
    ``NonIpopt_Exception_Thrown``; neither raises. The solver's ``sys.stderr`` is captured
    for the call (in the main thread, the only one that signals reach): that warning is
    recognised and not shown, any other text is passed on.

    Parameters
    ----------
    solver : casadi.Function
        The solver.
    **kwargs
        Its arguments (``x0``, ``p``, ``lbx``, ...).

    Returns
    -------
    tuple of dict
        The solver's outputs and its ``stats()``.
    """
    if threading.current_thread() is not threading.main_thread():
        # signals reach the main thread only; sys.stderr is global: never swap it here
        res = solver(**kwargs)
        stats = solver.stats()
        if str(stats.get("return_status")) == IPOPT_STOP:
            _request()
        check()
        return res, stats
    buf = io.StringIO()
    try:
        with contextlib.redirect_stderr(buf):
            res = solver(**kwargs)
    finally:
        text = buf.getvalue()
        caught = _CASADI_CAUGHT in text
        if text and not caught:
            sys.stderr.write(text)
    stats = solver.stats()
    if caught or str(stats.get("return_status")) == IPOPT_STOP:
        _request()
    check()
    return res, stats


def is_interruption(exc: BaseException) -> bool:
    """Whether ``exc`` is, or stands for, a Ctrl-C: a :class:`KeyboardInterrupt`, CasADi's
    ``RuntimeError`` wrapping one, or any exception raised after an interruption was
    requested (an aborted computation fails in arbitrary ways)."""
    if isinstance(exc, KeyboardInterrupt):
        return True
    if isinstance(exc, RuntimeError) and str(exc).rstrip().endswith("KeyboardInterrupt"):
        _request()
        return True
    return _requested


def reraise_interruption(exc: BaseException) -> None:
    """In an ``except Exception`` block that would retry or fall back: raise
    :class:`KeyboardInterrupt` instead if ``exc`` stands for a Ctrl-C.

    Parameters
    ----------
    exc : BaseException
        The exception caught.
    """
    if is_interruption(exc):
        raise KeyboardInterrupt from None


def _handler(signum: int, frame: FrameType | None) -> None:
    _request()
    if not _deferred:
        raise KeyboardInterrupt


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Around writing a finished result: a SIGINT or SIGTERM (delivered to any thread) is
    recorded, not raised, until the block ends; then :class:`KeyboardInterrupt` is raised
    if one came (the command line writes what finished, then exits 130)."""
    global _deferred
    _deferred += 1
    try:
        yield
    finally:
        _deferred -= 1
    if not _deferred and _requested:
        raise KeyboardInterrupt


def install() -> None:
    """SIGINT and SIGTERM record an interruption and raise :class:`KeyboardInterrupt` (the
    command line's handler; main thread only)."""
    for sig in SIGNALS:
        signal.signal(sig, _handler)


def _record(signum: int, frame: FrameType | None) -> None:
    _request()


def _launched_as_cli() -> bool:
    """``python [options] -m cable_ocp ...`` or the ``cable-ocp`` script."""
    if os.path.basename(sys.argv[0] if sys.argv else "").startswith("cable-ocp"):
        return True
    args = list(getattr(sys, "orig_argv", []))[1:]
    for i, a in enumerate(args):
        if a == "-m":
            return args[i + 1:i + 2] == ["cable_ocp"]
        if not a.startswith("-"):
            return False
    return False


def defer_during_launch() -> None:
    """When the process is the command line starting up, record SIGINT and SIGTERM without
    raising until :func:`install` takes over (no import traceback); otherwise nothing."""
    if _launched_as_cli() and threading.current_thread() is threading.main_thread():
        for sig in SIGNALS:
            signal.signal(sig, _record)


@contextlib.contextmanager
def signals_blocked() -> Iterator[None]:
    """Block SIGINT and SIGTERM in this thread for the duration (e.g. around starting a
    worker process, which inherits the mask and sets its own handlers before unblocking);
    pending signals are delivered on exit."""
    if not hasattr(signal, "pthread_sigmask"):  # pragma: no cover - Windows
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)
