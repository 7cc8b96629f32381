"""The text face every command shares: progress in a pipe or on an odd terminal
(cli.output.progress, the one progress helper) and the one table formatter
(numerics.text_table.table): 100 columns, a failed row keeping its columns."""

from __future__ import annotations

import argparse
import io
import os
import time

import pytest

from cable_ocp.cli import output as out
from cable_ocp.numerics.text_table import WIDTH, table


class Clock:
    """A clock the test moves by hand (no real time is measured)."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_progress_in_a_pipe_writes_a_line_every_10_s_or_10_percent() -> None:
    """A stream that is not a terminal gets short lines: when 10 s have passed since the
    last, or 10 % more is done (but not within 1 s of the last), and a last line."""
    stream, clock = io.StringIO(), Clock()
    args = argparse.Namespace(quiet=False)
    # (seconds since the start, steps done of 100) and whether a line is due
    steps = [(0.5, 5, False),    # 5 %, 0.5 s
             (1.2, 12, True),    # 12 % since the start, 1.2 s >= 1 s
             (2.0, 15, False),   # 3 % more, 0.8 s
             (12.5, 16, True),   # 11.3 s since the last line
             (13.0, 30, False),  # 14 % more, but 0.5 s after the last line
             (14.0, 31, True),   # 15 % more, 1.5 s after
             (20.0, 35, False)]  # 4 % more, 6 s after
    with out.progress(args, 100, "heave simulation", "sample", stream=stream,
                      clock=clock) as bar:
        for t, done, due in steps:
            before = stream.getvalue().count("\n")
            clock.now = 100.0 + t
            bar(done, 100)
            assert stream.getvalue().count("\n") == before + due, (t, done)
        clock.now = 100.0 + 25.0
        bar(100)
    lines = stream.getvalue().splitlines()
    assert len(lines) == 5  # three due lines, the 10 % at 100 and the last one
    assert lines[0] == "cable-ocp: heave simulation: 12/100 sample (12 %), 1 s, ~9 s left"
    assert lines[1].startswith("cable-ocp: heave simulation: 16/100 sample (16 %), 12 s")
    assert lines[-1] == "cable-ocp: heave simulation: 100/100 sample (100 %), 25 s (done)"


def test_progress_in_a_pipe_says_preparing_through_a_silent_start() -> None:
    """A command that prepares for a while before its first step (the deployment's nine
    identifications: 37 s of silence in a pipe) gets a `preparing` line from the timer's
    tick after 10 s without one, and again 10 s later; a tick sooner writes nothing."""
    stream, clock = io.StringIO(), Clock()
    lines = out.ProgressLines(stream, 1, "heave simulation", "sample", clock)
    for t, due in ((4.0, 0), (10.5, 1), (15.0, 1), (20.6, 2)):
        clock.now = 100.0 + t
        lines.tick()
        assert stream.getvalue().count("\n") == due, t
    assert stream.getvalue().splitlines() == ["cable-ocp: heave simulation: preparing, 10 s",
                                              "cable-ocp: heave simulation: preparing, 21 s"]
    clock.now = 100.0 + 21.0
    lines(500, 4000)  # the first step: 0.4 s after the last line, 12 % done: not yet due
    clock.now = 100.0 + 31.0
    lines.tick()
    assert stream.getvalue().splitlines()[-1].startswith(
        "cable-ocp: heave simulation: 500/4000 sample (12 %), 31 s")


def test_progress_short_run_and_quiet_write_nothing() -> None:
    """A run that finishes before any line is due writes none (no final line either);
    ``--quiet`` writes nothing at all."""
    for quiet, t in ((False, 0.5), (True, 50.0)):
        stream, clock = io.StringIO(), Clock()
        with out.progress(argparse.Namespace(quiet=quiet), 10, "job", stream=stream,
                          clock=clock) as bar:
            clock.now += t
            bar(10)
        assert stream.getvalue() == ""


def test_progress_bar_draws_on_a_terminal_that_reports_0_columns() -> None:
    """A new pseudo-terminal reports 0 x 0; tqdm with dynamic_ncols draws nothing there, the
    bar falls back to 80 columns and draws."""
    master, slave = os.openpty()
    try:
        assert os.get_terminal_size(slave).columns == 0
        os.set_blocking(master, False)
        with open(slave, "w", closefd=False) as tty:
            assert out.bar_columns(tty) == out.FALLBACK_COLUMNS
            with out.progress(argparse.Namespace(quiet=False), 100, "job", "step",
                              stream=tty) as bar:
                bar(50, 100)
                tty.flush()
                text = b""
                for _ in range(50):  # the pty passes the bytes on shortly
                    try:
                        text += os.read(master, 4096)
                    except BlockingIOError:
                        if b"50/100" in text:
                            break
                        time.sleep(0.01)
        drawn = text.decode(errors="replace").split("\r")
        bar_line = next(s for s in drawn if "50/100" in s)
        assert "50%|" in bar_line and len(bar_line) > 60
    finally:
        os.close(master)
        os.close(slave)


def test_table_fits_100_columns_and_a_failed_row_keeps_its_columns() -> None:
    headers = [f"column {k}" for k in range(14)]
    good = [f"{1000.0 * k:.3f}" for k in range(14)]
    failed = ["lqg", "failed"] + [None] * 12
    text = table(headers, [good, failed], ["[m]"] * 14)
    lines = text.splitlines()
    assert max(len(s) for s in lines) <= WIDTH
    # split into blocks, each repeating the first column; the failed row in each block has
    # as many cells, right-aligned under the same headings
    blocks = text.split("\n\n")
    assert len(blocks) >= 2
    for b in blocks:
        rows = b.splitlines()
        assert len(rows) == 5  # headings, units, dashes, two rows
        assert len(rows[3].split()) == len(rows[4].split()) == len(rows[2].split())
        assert len(rows[3]) == len(rows[4]) == len(rows[2])
    assert "lqg" in blocks[1] and "-" in blocks[1].splitlines()[4]
    with pytest.raises(ValueError, match="cells for 14 headings"):
        table(headers, [good[:-1]])


def test_table_block_without_units_has_no_units_line() -> None:
    """A block of columns none of which has a unit prints no empty units line between its
    headings and its dashes (bench deploy's second and third blocks); a first column with
    a unit keeps the line in every block."""
    headers = ["method", "time", "binding", "note"]
    units = ["", "[s]", "", ""]
    row = ["ocp", 541.9, "x" * 40, "y" * 60]  # the note does not fit beside the binding
    blocks = table(headers, [row], units).split("\n\n")
    assert len(blocks) == 2
    first, *rest = (b.splitlines() for b in blocks)
    assert len(first) == 4 and first[1].split() == ["[s]"]  # headings, units, dashes, row
    for b in rest:
        assert len(b) == 3 and set(b[1]) == {"-", " "}  # headings, dashes, row
    timed = table(headers, [row], ["[s]", "", "", ""]).split("\n\n")
    assert len(timed) == 2
    for b in timed:
        assert b.splitlines()[1].split() == ["[s]"]


def test_bench_tables_fit_100_columns() -> None:
    """The benchmarks' tables (bench-heave, bench dynamics, bench sweep's headings and
    labels) at their widest rows, through the one formatter: <= 100 columns; a failed or
    missing row (NaN times, no amplitude) keeps its cells."""
    from cable_ocp.bench import dynamics as bd
    from cable_ocp.bench import heave_mpc as bh
    from cable_ocp.bench import statics_sweep

    nan = float("nan")
    heave = bh.format_table([
        bh.BenchRow("qpoases (condensed)", 100, 6.9e-4, 2.1e-3, 300, 0,
                    "condensed dense QP, warm-started", 6.8e-4, 2.0e-3),
        bh.BenchRow("do-mpc", 100, nan, nan, 0, 0, "not installed (pip install do-mpc)")])
    dyn = bd.format_table([
        bd.BenchRow("cable_ocp lumped (compiled)", 80, 0.0125, 2.345e-3, 426.0, 12.345,
                    1.55e-2, -0.0021, 0.0013, "solved"),
        bd.BenchRow("moordyn", 80, 2.5e-4, nan, nan, nan, nan, nan, None, "not installed")])
    import inspect
    src = inspect.getsource(statics_sweep)
    labels = [s for s in ("collocation, 1st process (build)", "compiled, 1st process (C compile)")
              if s in src]
    assert len(labels) == 2
    sweep = table(["method", "points", "total [ms]", "CPU [ms]", "first [ms]", "next [ms]",
                   "next CPU [ms]", "next p90 [ms]", "iters mean", "iters median",
                   "factor. mean", "solved"],
                  [[labels[1], 19, 1613.2, 93.1, 3.5, 0.47, 0.47, 0.61, 5.8, 6.0, 1.4, 19],
                   [labels[0], 19, nan, nan, nan, nan, nan, nan, nan, nan, nan, 0]])
    for text in (heave, dyn, sweep):
        assert max(len(line) for line in text.splitlines()) <= WIDTH, text
    rows = [line for line in dyn.splitlines()[3:]]
    assert len(rows[0]) == len(rows[1])
