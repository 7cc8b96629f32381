"""The batch store (issue 22, fault 5, and the batch part of fault 2): rows keyed by case
index (identical cases stay separate), strict JSON, one batch at a time per --out, a resume
that checks its inputs and survives damaged lines and meta files, worker_lost cases run
again, and an append on a full disk is an environment error with the earlier lines kept.

Most checks run the store through ``run_batch`` with a runner that solves nothing (its
outputs are functions of the case, so every number is known); the CLI checks solve De
Zoysa's cable, one warm solve per case.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import pytest
from faults import file_size_limit

from cable_ocp.batch import build_cases, parse_grid, parse_range, run_batch
from cable_ocp.batch.cases import Case
from cable_ocp.batch.executors import RunnerSpec
from cable_ocp.batch.store import Store, lock_path
from cable_ocp.cli import main
from cable_ocp.errors import CableOCPError
from cable_ocp.scene import read_problem

ROOT = Path(__file__).resolve().parents[1]
DEZOYSA = ROOT / "problems" / "dezoysa_sea_buggy.toml"
SPEED = "environment.current.speed"


class _Fake:
    """A runner that solves nothing: y = the case's seed, z = NaN, w = +inf; every case it
    runs is recorded in ``FakeSpec.ran``."""

    def __init__(self, message: str) -> None:
        self.message = message

    def columns(self) -> list[str]:
        return ["y [-]", "z [-]", "w [-]"]

    def run(self, case: Case) -> dict[str, Any]:
        FakeSpec.ran.append(case.index)
        return {"case": case.index, "case_id": case.case_id, "status": "solved",
                "message": self.message, "wall_time_s": 0.0, **case.overrides,
                "y [-]": float(case.seed), "z [-]": math.nan, "w [-]": math.inf}


@dataclass
class FakeSpec(RunnerSpec):
    message: str = ""
    ran: ClassVar[list[int]] = []

    def make(self) -> Any:
        return _Fake(self.message)


def _fake(message: str = "") -> FakeSpec:
    FakeSpec.ran = []
    return FakeSpec("statics", read_problem(DEZOYSA), {}, message)


def _strict(text: str) -> Any:
    """``json.loads`` that refuses NaN, Infinity and -Infinity."""
    def refuse(name: str) -> Any:
        raise ValueError(f"not strict JSON: {name}")

    return json.loads(text, parse_constant=refuse)


def _lines(path: Path) -> list[str]:
    return path.read_text(encoding="utf-8").splitlines(keepends=True)


def test_identical_cases_are_separate_rows_marked_as_duplicates(tmp_path: Path) -> None:
    """`--grid speed=1,1,1 --seed 1`: three cases with their own seeds give three rows (in
    memory, in the JSON lines and in the CSV), keyed by index; cases 1 and 2 are marked
    duplicates of case 0 (they collapsed into one row before)."""
    grid = [parse_grid(f"{SPEED}=1.0,1.0,1.0")]
    res = run_batch(DEZOYSA, grid, seed=1, workers=0, out=tmp_path / "d", spec=_fake())
    seeds = [c.seed for c in build_cases(grid, seed=1)]
    assert len(set(seeds)) == 3
    assert [r["case"] for r in res.rows] == [0, 1, 2]
    assert [r["y [-]"] for r in res.rows] == [float(s) for s in seeds]
    assert [r["duplicate_of"] for r in res.rows] == [None, 0, 0]
    assert res.duplicates() == [[0, 1, 2]]
    stored = [_strict(line) for line in _lines(tmp_path / "d.jsonl")]
    assert [r["case"] for r in stored] == [0, 1, 2]
    csv_lines = (tmp_path / "d.csv").read_text().splitlines()
    assert len(csv_lines) == 4 and csv_lines[0].endswith("case_id,duplicate_of")
    assert [line.rsplit(",", 1)[1] for line in csv_lines[1:]] == ["", "0", "0"]
    again = run_batch(DEZOYSA, grid, seed=1, workers=0, out=tmp_path / "d", resume=True,
                      spec=_fake())
    assert FakeSpec.ran == [] and len(again.rows) == 3 and again.skipped == 3


def test_every_store_file_is_strict_json(tmp_path: Path) -> None:
    """Outputs that are NaN or infinite, an infinite grid value and a list value holding
    NaN end as null: the JSON lines and the meta file parse with a parser that refuses
    NaN and Infinity (both held bare NaN/Infinity before)."""
    grid = [(SPEED, [1.0, math.inf]), ("layout.note", [[1.0, math.nan]])]
    run_batch(DEZOYSA, grid, workers=0, out=tmp_path / "s", spec=_fake())
    rows = [_strict(line) for line in _lines(tmp_path / "s.jsonl")]
    assert [r["z [-]"] for r in rows] == [None, None]
    assert [r["w [-]"] for r in rows] == [None, None]
    assert [r[SPEED] for r in rows] == [1.0, None]
    assert rows[0]["layout.note"] == [1.0, None]
    meta = _strict((tmp_path / "s.meta.json").read_text())
    assert meta["grid"][0] == [SPEED, [1.0, None]]
    assert meta["cases"][1] == {SPEED: None, "layout.note": [1.0, None]}


def test_a_second_batch_on_the_same_out_is_refused(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    """While one batch holds OUT.lock, a second on the same --out exits 2 with one line
    naming the lock and what to do, and writes nothing (two runs at once duplicated 145 of
    148 rows before); once the first ends, the lock file is gone and a run goes through. The
    API refuses alike."""
    out = tmp_path / "c"
    cmd = ["batch", str(DEZOYSA), "--grid", f"{SPEED}=1.0", "--workers", "0", "--quiet",
           "--out", str(out)]
    first = Store(out, {"columns": ["case"], "cases": [{}]})
    try:
        capsys.readouterr()
        assert main(cmd) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "another batch is writing there" in err[0], err
        assert str(lock_path(out)) in err[0] and "another --out" in err[0]
        assert (tmp_path / "c.jsonl").read_text() == ""  # the first's, untouched
        with pytest.raises(CableOCPError, match="another batch is writing there"):
            run_batch(DEZOYSA, [(SPEED, [1.0])], workers=0, out=out, overwrite=True,
                      spec=_fake())
    finally:
        first.close()
    assert not lock_path(out).exists()
    assert main([*cmd, "--overwrite"]) == 0
    assert not lock_path(out).exists()
    assert len(_lines(tmp_path / "c.jsonl")) == 1


def test_resume_drops_lines_that_are_not_rows_and_counts_them(tmp_path: Path) -> None:
    """Lines that are JSON but not rows (`{}`, `null`, a list, a row of a case the batch
    does not have) and a second row of a case are dropped with a counted note, the rows are
    kept, nothing runs again (this exited 3 before)."""
    out = tmp_path / "r"
    run_batch(DEZOYSA, ranges=[parse_range("layout.psi0_deg=0:30:4")], workers=0, out=out,
              spec=_fake())
    jsonl = tmp_path / "r.jsonl"
    rows = _lines(jsonl)
    stray = json.dumps({**json.loads(rows[0]), "case": 7}) + "\n"
    jsonl.write_text(rows[0] + "{}\n" + rows[1] + "null\n[1, 2]\n" + stray + rows[0]
                     + "".join(rows[2:]), encoding="utf-8")
    res = run_batch(DEZOYSA, ranges=[parse_range("layout.psi0_deg=0:30:4")], workers=0,
                    out=out, resume=True, spec=_fake())
    assert FakeSpec.ran == []
    assert _lines(jsonl) == rows
    assert [r["case"] for r in res.rows] == [0, 1, 2, 3]
    assert any("4 line(s) that are not rows of this batch dropped (line 2, 4, 5, 6)" in n
               for n in res.notes), res.notes
    assert any("1 second row(s) of a case dropped (case 0)" in n for n in res.notes)


@pytest.mark.parametrize("damage,why", [("truncated", "not JSON"), ("empty", "empty"),
                                        ("null", "holds NoneType"), ("missing", "missing"),
                                        ("old", "without the record of its inputs")])
def test_resume_with_a_damaged_meta_file_is_refused(tmp_path: Path, damage: str,
                                                    why: str) -> None:
    """A meta file cut short, empty, not a record, missing, or of the older layout that
    recorded no inputs: the resume is refused (CLI exit 2) saying the meta is damaged and
    how to start afresh; the rows are not touched (a truncated one exited 3 before)."""
    out = tmp_path / "m"
    grid = [(SPEED, [1.0, 1.1])]
    run_batch(DEZOYSA, grid, workers=0, out=out, spec=_fake())
    meta, jsonl = tmp_path / "m.meta.json", tmp_path / "m.jsonl"
    rows = jsonl.read_text()
    text = meta.read_text()
    if damage == "missing":
        meta.unlink()
    else:
        meta.write_text({"truncated": text[: len(text) // 2], "empty": "", "null": "null",
                         "old": json.dumps({"problem": "<dict>", "kind": "statics"})}[damage])
    with pytest.raises(CableOCPError, match=why) as err:
        run_batch(DEZOYSA, grid, workers=0, out=out, resume=True, spec=_fake())
    assert "--overwrite" in str(err.value) and str(meta) in str(err.value)
    assert jsonl.read_text() == rows and FakeSpec.ran == []


def test_resume_with_other_inputs_is_refused_saying_what_differs(tmp_path: Path) -> None:
    """A resume whose problem file changed, whose --set, grid, seed or cable_ocp version
    differ, is refused naming the difference (a changed problem file silently mixed results
    before); the same inputs continue."""
    problem = tmp_path / "p.toml"
    problem.write_bytes(DEZOYSA.read_bytes())
    out = tmp_path / "o"
    grid = [(SPEED, [1.0, 1.1])]

    def resume(**kw: Any) -> Any:
        args = {"grids": grid, "overrides": {"layout.psi0_deg": 10.0}, "seed": 1, **kw}
        return run_batch(problem, workers=0, out=out, resume=True, spec=_fake(), **args)

    run_batch(problem, grid, seed=1, workers=0, out=out, spec=_fake(),
              overrides={"layout.psi0_deg": 10.0})
    with pytest.raises(CableOCPError, match=r"--set layout\.psi0_deg=10\.0 vs "
                                            r"layout\.psi0_deg=20\.0"):
        resume(overrides={"layout.psi0_deg": 20.0})
    with pytest.raises(CableOCPError, match=r"--seed 1 vs 2"):
        resume(seed=2)
    with pytest.raises(CableOCPError, match=r"--grid environment\.current\.speed=1\.0,1\.1 "
                                            r"vs environment\.current\.speed=1\.0,2\.0"):
        resume(grids=[(SPEED, [1.0, 2.0])])
    problem.write_text(problem.read_text().replace("speed = 1.0", "speed = 2.0"))
    with pytest.raises(CableOCPError, match="problem file digest differs"):
        resume()
    problem.write_bytes(DEZOYSA.read_bytes())
    meta = tmp_path / "o.meta.json"
    record = json.loads(meta.read_text())
    meta.write_text(json.dumps({**record, "version": "0.0.1"}))
    with pytest.raises(CableOCPError, match=r"cable_ocp version 0\.0\.1 vs "):
        resume()
    meta.write_text(json.dumps(record))
    assert len(resume().rows) == 2 and FakeSpec.ran == []


def test_cli_default_out_and_resume_with_another_set_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Without --out the store is the problem file's stem and _batch in the current
    directory (--out was required before). The CLI records its --set values (it passed an
    anonymous dictionary before): a resume with another value exits 2 with one line naming
    both."""
    monkeypatch.chdir(tmp_path)
    cmd = ["batch", str(DEZOYSA), "--grid", f"{SPEED}=1.0", "--workers", "0", "--quiet"]
    assert main([*cmd, "--set", "layout.psi0_deg=10"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        f"dezoysa_sea_buggy_batch.{x}" for x in ("csv", "jsonl", "meta.json")]
    capsys.readouterr()
    assert main([*cmd, "--set", "layout.psi0_deg=20", "--resume"]) == 2
    (err,) = capsys.readouterr().err.strip().splitlines()
    assert "--set layout.psi0_deg=10 vs layout.psi0_deg=20" in err


def test_worker_lost_cases_run_again_on_resume(tmp_path: Path) -> None:
    """A worker_lost row is not a result: on --resume that case runs again (only it), and
    the store ends with one solved row per case."""
    out = tmp_path / "w"
    grid = [(SPEED, [1.0, 1.1, 1.2, 1.3])]
    run_batch(DEZOYSA, grid, workers=0, out=out, spec=_fake())
    jsonl = tmp_path / "w.jsonl"
    rows = [json.loads(line) for line in _lines(jsonl)]
    rows[2].update(status="worker_lost", message="the worker process died 2 times")
    jsonl.write_text("".join(json.dumps(r) + "\n" for r in rows))
    res = run_batch(DEZOYSA, grid, workers=0, out=out, resume=True, spec=_fake())
    assert FakeSpec.ran == [2]
    assert any("1 worker_lost case(s) run again (case 2)" in n for n in res.notes)
    stored = [json.loads(line) for line in _lines(jsonl)]
    assert sorted(r["case"] for r in stored) == [0, 1, 2, 3]
    assert {r["status"] for r in stored} == {"solved"}
    assert len((tmp_path / "w.csv").read_text().splitlines()) == 5


def test_an_append_on_a_full_disk_exits_2_and_keeps_the_earlier_lines(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The store's appends under a 3000-byte file-size limit (a JSON row of De Zoysa's
    cable is about 800 bytes): exit 2 with one line naming the file and the reason (exit 3
    before), the rows before intact and equal to the control run's, no row cut in half;
    --resume without the limit then finishes the batch. The control run, without the
    limit, also warms this process's solvers (nothing else is written under the limit)."""
    cmd = ["batch", str(DEZOYSA), "--range", "layout.psi0_deg=0:140:8", "--workers", "0",
           "--quiet"]
    assert main([*cmd, "--out", str(tmp_path / "control")]) == 0
    control = [json.loads(line) for line in _lines(tmp_path / "control.jsonl")]
    out = tmp_path / "full"
    capsys.readouterr()
    with file_size_limit(3000):
        rc = main([*cmd, "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2, err
    assert len(err) == 1 and "could not be written (File too large)" in err[0], err
    assert f"{out}.jsonl" in err[0] and "--resume" in err[0]
    text = (tmp_path / "full.jsonl").read_text()
    assert text.endswith("\n") and len(text) <= 3000
    kept = [json.loads(line) for line in text.splitlines()]
    assert 1 <= len(kept) < 8
    for row, ref in zip(kept, control, strict=False):
        assert {k: v for k, v in row.items() if k != "wall_time_s"} == {
            k: v for k, v in ref.items() if k != "wall_time_s"}
    assert not lock_path(out).exists()
    assert main([*cmd, "--out", str(out), "--resume"]) == 0
    rows = [json.loads(line) for line in _lines(tmp_path / "full.jsonl")]
    assert [r["case"] for r in rows] == list(range(8))


def test_resume_after_the_cable_scene_changed_is_refused(tmp_path: Path) -> None:
    """The meta file records the digest of the file a heave problem's `[unit] cable_scene`
    names: a resume after that file changed is refused naming it (the problem file itself
    is the same, so its own digest cannot tell)."""
    import re

    src = ROOT / "problems" / "heave" / "ex_6_3_6_cable.toml"
    text = src.read_text()
    name = re.search(r'cable_scene\s*=\s*"([^"]+)"', text).group(1)
    scene = tmp_path / "cable.toml"
    scene.write_bytes((src.parent / name).resolve().read_bytes())
    problem = tmp_path / "h.toml"
    problem.write_text(text.replace(f'"{name}"', '"cable.toml"'))
    out = tmp_path / "o"
    grid = [("simulation.duration", [1.0, 2.0])]
    run_batch(problem, grid, workers=0, out=out, spec=_fake())
    record = json.loads((tmp_path / "o.meta.json").read_text())
    assert record["files"]["[unit] cable_scene"]["path"] == str(scene.resolve())
    scene.write_text(scene.read_text() + "\n# edited\n")
    with pytest.raises(CableOCPError, match=r"\[unit\] cable_scene digest differs"):
        run_batch(problem, grid, workers=0, out=out, resume=True, spec=_fake())
