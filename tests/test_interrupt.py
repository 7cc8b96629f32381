"""Ctrl-C and kills, in real processes: every command stops with exit 130, one line on
stderr and the finished part written whole (docs/cli.md, "Exit codes"); a batch's workers
never outlive their parent.

All the processes run at once (one launch, one wait: the whole module costs about as much
wall time as its slowest process). Each is signalled at its own moment, chosen by what it
has done rather than by the clock, so that the moment holds on a loaded machine: 0.05 s
after the start (the imports), after an amount of its own CPU time (the imports take about
1 s of CPU: later is inside the build or the solve), or after a batch has stored its first
rows. Functions are not compiled in these processes (CABLE_OCP_CACHE=0): no C compiler
runs, and the CPU times mean the same on every run.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from cable_ocp.numerics import interrupt

ROOT = Path(__file__).resolve().parents[1]
P = ROOT / "problems"
LINE = ["--quiet"]
ONE_LINE = ["cable-ocp: interrupted"]


@dataclass
class Run:
    """One process: its arguments, when and how it is signalled, what it wrote."""

    name: str
    argv: list[str]
    when: tuple[str, float]          # ("wall", s) | ("cpu", s) | ("rows", n)
    how: str = "sigint_group"        # "sigint_group" (a terminal's Ctrl-C), "sigterm", "sigkill"
    outputs: tuple[str, ...] = ()    # file names written in its folder
    proc: Any = None
    folder: Path | None = None
    signalled: float | None = None   # when (time.monotonic())
    workers: list[int] = field(default_factory=list)
    gone_after: float | None = None  # s from the signal until every worker had exited
    rc: int | None = None
    stderr: list[str] = field(default_factory=list)


def _cpu_s(pid: int) -> float:
    """User + system CPU time of a process, s (/proc; its children not counted)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _alive(pid: int) -> bool:
    """True while the process exists and is not a zombie (pid 1 of a container may never
    reap an orphan)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def _children(pid: int) -> list[int]:
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                if int((d / "stat").read_text().rsplit(")", 1)[1].split()[1]) == pid:
                    out.append(int(d.name))
            except (OSError, IndexError, ValueError):
                pass
    return out


def _rows(run: Run) -> int:
    path = run.folder / "b.jsonl"
    return len(path.read_text().splitlines()) if path.exists() else 0


def _batch(kind_args: list[str]) -> list[str]:
    return ["batch", str(P / "dezoysa_sea_buggy.toml"), "--range",
            "layout.psi0_deg=0:140:60", "--out", "b", "--workers", "2", "--chunk-size", "1",
            *kind_args, *LINE]


RUNS = [
    # the imports (numpy, scipy, casadi: about 1 s of CPU): nothing written, no traceback
    Run("solve, at start-up", ["solve", str(P / "berteaux_mooring.toml"), "--json", "s.json",
                               *LINE], ("cpu", 0.3)),
    # Berteaux's buoy with 1 kN top tension has no equilibrium: Newton fails, then IPOPT
    # runs twice (with 160 intervals from about 1.3 to 3.8 s of CPU); a Ctrl-C there
    # printed CasADi's KeyboardInterruptException warning before the line
    Run("solve, in IPOPT", ["solve", str(P / "berteaux_mooring.toml"), "--set",
                            "end_b.tension=1000", "--set", "solver.intervals=160", "--json",
                            "s.json", *LINE], ("cpu", 1.9)),
    # 36 directions take about 6 s of CPU: the Ctrl-C lands in one of them; it was
    # retried from a fresh start and the run ended "solved", exit 0
    Run("footprint", ["footprint", str(P / "footprint_tethered_unit.toml"), "--directions",
                      "36", "--json", "f.json", "--csv", "f.csv", *LINE], ("cpu", 2.5),
        outputs=("f.json", "f.csv")),
    # the time steps of 600 s of the lumped line run from about 2 to 10-14 s of CPU (the
    # build before them took up to 2.0 s, so a moment at 1.9 s sometimes came before the
    # first step: nothing finished, nothing written; 120 s ended at ~2.4 s on a faster
    # machine: the Ctrl-C then came after the run); a Ctrl-C there gave exit 3 (CasADi's
    # RuntimeError) or was lost (exit 0)
    # (records every 0.5 s: the finished part's 22 500 records of 0.01 s took 2.5 s of CPU
    # to write after the signal, 460 take 0.3 s)
    Run("simulate", ["simulate", str(P / "dynamics" / "line_6_3_6_lumped3d.toml"), "--set",
                     "simulation.duration=600", "--set", "simulation.output_step=0.5",
                     "--json", "m.json", "--csv", "m.csv", *LINE],
        ("cpu", 3.5), outputs=("m.json", "m.csv")),
    Run("heave", ["heave", str(P / "heave" / "ex_6_3_6.toml"), "--duration", "60",
                  "--json", "h.json", *LINE], ("cpu", 1.5), outputs=("h.json",)),
    # a terminal's Ctrl-C reaches the workers too: they printed ~60 lines of tracebacks
    Run("batch, Ctrl-C", _batch([]), ("rows", 2), outputs=("b.csv", "b.jsonl", "b.meta.json")),
    # the parent alone: SIGTERM ends it as a Ctrl-C does; SIGKILL leaves the workers
    # orphaned, and they used to block for ever on their pipes
    Run("batch, SIGTERM", _batch(["--json", "b.json"]), ("rows", 2), how="sigterm",
        outputs=("b.csv", "b.jsonl", "b.meta.json", "b.json")),
    Run("batch, SIGKILL", _batch([]), ("rows", 2), how="sigkill",
        outputs=("b.csv", "b.jsonl", "b.meta.json")),
]


def _due(run: Run, t: float) -> bool:
    kind, value = run.when
    if kind == "wall":
        return t >= value
    if kind == "cpu":
        return _cpu_s(run.proc.pid) >= value
    return _rows(run) >= value


def _signal(run: Run) -> None:
    if run.name.startswith("batch"):
        run.workers = _children(run.proc.pid)
    if run.how == "sigint_group":
        os.killpg(run.proc.pid, signal.SIGINT)
    else:
        os.kill(run.proc.pid, signal.SIGTERM if run.how == "sigterm" else signal.SIGKILL)
    run.signalled = time.monotonic()


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Run]:
    env = {**os.environ, "CABLE_OCP_CACHE": "0",
           "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    base = tmp_path_factory.mktemp("interrupt")
    todo = [Run(r.name, list(r.argv), r.when, r.how, r.outputs) for r in RUNS]
    for k, run in enumerate(todo):
        run.folder = base / str(k)
        run.folder.mkdir()
        # stderr to a file, not a pipe: a leaked worker would hold a pipe open for ever
        with open(base / f"{k}.err", "w") as err:
            run.proc = subprocess.Popen([sys.executable, "-m", "cable_ocp", *run.argv],
                                        cwd=run.folder, env=env, stdout=subprocess.DEVNULL,
                                        stderr=err, start_new_session=True)
    t0 = time.monotonic()
    pending = list(todo)
    while pending and time.monotonic() - t0 < 120:
        for run in list(pending):
            if run.proc.poll() is not None:  # finished before its moment came
                pending.remove(run)
            elif _due(run, time.monotonic() - t0):
                _signal(run)
                pending.remove(run)
        time.sleep(0.01)
    for run in todo:
        if run.workers:  # gone within 10 s of the signal?
            while any(_alive(p) for p in run.workers) and time.monotonic() - run.signalled < 10:
                time.sleep(0.05)
            run.gone_after = time.monotonic() - run.signalled
            for pid in run.workers:  # never leave a leaked worker behind this test
                if _alive(pid):
                    os.kill(pid, signal.SIGKILL)
    for k, run in enumerate(todo):
        try:
            run.proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(run.proc.pid, signal.SIGKILL)
            run.proc.wait()
        run.rc = run.proc.returncode
        run.stderr = (base / f"{k}.err").read_text().splitlines()
    return {run.name: run for run in todo}


def _check(run: Run) -> None:
    if not run.signalled:
        pytest.skip(f"{run.name}: finished (exit {run.rc}) before its moment came")
    assert (run.rc, run.stderr) == (130, ONE_LINE), run.name
    # nothing but the outputs the command finished: no temporary or half file
    left = {p.name for p in run.folder.iterdir()}
    assert left <= set(run.outputs), (run.name, left)


@pytest.mark.parametrize("name", [r.name for r in RUNS if r.how != "sigkill"])
def test_interrupted_command_exits_130_with_one_line(runs: dict[str, Run], name: str) -> None:
    """Exit 130, exactly one line on stderr (no traceback, no CasADi warning), and no file
    but the finished part: for these moments, the solve has none, the heave comparison
    its JSON of the controllers finished, footprint its finished directions, simulate its
    finished samples, a batch its finished rows."""
    _check(runs[name])


def test_heave_keeps_its_finished_controllers(runs: dict[str, Run]) -> None:
    run = runs["heave"]
    _check(run)
    path = run.folder / "h.json"
    if not path.exists():  # the Ctrl-C came before the first run (building the designs)
        return
    data = json.loads(path.read_text(), parse_constant=pytest.fail)
    assert data["status"] == "interrupted"
    st = [c["status"] for c in data["controllers"].values()]
    assert "interrupted" in st and st.index("interrupted") == st.count("solved")


def test_footprint_keeps_its_finished_directions(runs: dict[str, Run]) -> None:
    run = runs["footprint"]
    _check(run)
    data = json.loads((run.folder / "f.json").read_text(), parse_constant=pytest.fail)
    assert data["status"] == "interrupted"
    n = len(data["directions"])
    assert n < 36 and data["message"] == f"interrupted after {n} of 36 directions"
    assert len((run.folder / "f.csv").read_text().splitlines()) == 1 + n


def test_simulate_keeps_its_finished_samples(runs: dict[str, Run]) -> None:
    run = runs["simulate"]
    _check(run)
    data = json.loads((run.folder / "m.json").read_text(), parse_constant=pytest.fail)
    assert data["status"] == "interrupted" and "interrupted after" in data["message"]
    t = data["t"]
    assert 0 < t[-1] < 600
    assert np.allclose(np.diff(t), 0.5, rtol=0, atol=1e-9)  # the records' grid, as asked
    assert len((run.folder / "m.csv").read_text().splitlines()) == 1 + len(t)


@pytest.mark.parametrize("name", ["batch, Ctrl-C", "batch, SIGTERM", "batch, SIGKILL"])
def test_batch_workers_end_with_their_parent(runs: dict[str, Run], name: str) -> None:
    """Two workers were running when the parent was signalled; within 10 s of its end
    (SIGKILL: of the kill) none is left. The rows stored are whole JSON lines, one per
    case, and (when the parent could finish) the CSV has the same rows."""
    run = runs[name]
    if not run.signalled:
        pytest.skip(f"{name}: finished before its first rows")
    assert len(run.workers) == 2, run.workers
    assert run.gone_after is not None and run.gone_after < 10, "workers left running"
    if run.how == "sigkill":
        assert run.rc == -signal.SIGKILL
    rows = [json.loads(line) for line in (run.folder / "b.jsonl").read_text().splitlines()]
    assert 2 <= len(rows) < 60 and len({r["case"] for r in rows}) == len(rows)
    if run.how != "sigkill":
        _check(run)
        assert len((run.folder / "b.csv").read_text().splitlines()) == 1 + len(rows)
    if "--json" in run.argv:  # the summary of what was stored, status interrupted
        data = json.loads((run.folder / "b.json").read_text(), parse_constant=pytest.fail)
        assert data["status"] == "interrupted" and data["cases_stored"] == len(rows)
        assert sum(data["statuses"].values()) == len(rows)


def test_ipopt_stop_and_casadi_wrapping_are_interruptions() -> None:
    """The two forms in which native code hands back a Ctrl-C: IPOPT's return status and
    CasADi's RuntimeError ending in KeyboardInterrupt; other failures are not."""
    class Solver:
        def __init__(self, status: str, warn: str = "") -> None:
            self.status, self.warn = status, warn

        def __call__(self, **kw: Any) -> dict[str, Any]:
            sys.stderr.write(self.warn)
            return {"x": kw["x0"]}

        def stats(self) -> dict[str, Any]:
            return {"return_status": self.status, "success": False}

    try:
        assert interrupt.call_solver(Solver("Infeasible_Problem_Detected"), x0=1)[0] == {"x": 1}
        with pytest.raises(KeyboardInterrupt):
            interrupt.call_solver(Solver(interrupt.IPOPT_STOP), x0=1)
        interrupt.clear()
        with pytest.raises(KeyboardInterrupt):
            interrupt.call_solver(Solver("NonIpopt_Exception_Thrown",
                                         'CasADi - WARNING("KeyboardInterruptException")\n'),
                                  x0=1)
        interrupt.clear()
        assert not interrupt.is_interruption(RuntimeError("Error in Function::call: singular"))
        assert interrupt.is_interruption(RuntimeError("Error in Function::call for 'chunk' "
                                                      "[MXFunction]:\nKeyboardInterrupt"))
        assert interrupt.requested()
    finally:
        interrupt.clear()
