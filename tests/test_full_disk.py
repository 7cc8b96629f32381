"""A write that fails part-way keeps the earlier file (issue 22, fault 2; CONVENTIONS "Exit
codes": an output that cannot be written, e.g. a full disk, found after the solve: exit 2,
the earlier file is kept).

The fault is real, not mocked: the command runs under a file-size limit (the soft
``RLIMIT_FSIZE`` of this process lowered to 2000 bytes for the run, ``SIGXFSZ`` ignored),
so that the kernel fails the write past 2000 bytes with ``EFBIG`` exactly as a full disk
fails it with ``ENOSPC`` (the same ``OSError`` path). Before the fix ``--json`` truncated
the earlier file in place, left 2000 bytes of JSON and exited 3 ("internal error:
OSError").
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest
from faults import file_size_limit

from cable_ocp.numerics.atomic import replace_atomically, write_text_atomically

ROOT = Path(__file__).resolve().parents[1]
PROBLEM = ROOT / "problems" / "dezoysa_sea_buggy.toml"
LIMIT = 2000  # bytes: the solve's JSON, CSV and figure are each larger


@pytest.fixture(scope="module")
def control(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The control run, in this process without the limit: ``--json`` onto an earlier file
    of mode 0640 (it also warms this process's functions, so that the limited runs below
    write only their output)."""
    from cable_ocp.cli import main

    work = tmp_path_factory.mktemp("control")
    target = work / "out.json"
    target.write_text("EARLIER\n")
    target.chmod(0o640)
    assert main(["solve", str(PROBLEM), "--json", str(target), "--quiet"]) == 0
    return target


@pytest.mark.parametrize("option,name", [("--json", "out.json"), ("--csv", "out.csv"),
                                         ("--plot", "out.png")])
def test_a_failed_write_keeps_the_earlier_file_and_exits_2(
        tmp_path: Path, control: Path, capsys: pytest.CaptureFixture[str], option: str,
        name: str) -> None:
    from cable_ocp.cli import main

    target = tmp_path / name
    target.write_text("EARLIER\n")
    capsys.readouterr()
    with file_size_limit(LIMIT):
        rc = main(["solve", str(PROBLEM), option, str(target), "--quiet"])
    lines = capsys.readouterr().err.strip().splitlines()
    assert rc == 2, lines
    assert lines == [f"cable-ocp: error: {option} {target}: could not be written (File too "
                     "large); the earlier file is kept"]
    assert target.read_text() == "EARLIER\n"
    assert [p.name for p in tmp_path.iterdir()] == [name]


def test_the_same_write_succeeds_without_the_limit(control: Path) -> None:
    """The control: the same command without the limit replaced the earlier file whole
    (valid JSON, larger than the limit), kept its permissions and left no other file."""
    import json

    assert json.loads(control.read_text())["status"] == "solved"
    assert control.stat().st_size > LIMIT
    assert stat.S_IMODE(control.stat().st_mode) == 0o640
    assert [p.name for p in control.parent.iterdir()] == ["out.json"]


def test_replace_atomically_on_failure_and_interruption(tmp_path: Path) -> None:
    """A writer that fails after writing part of the content, or is interrupted, leaves
    the earlier file and no temporary file; a new file gets the umask's permissions."""
    target = tmp_path / "f.txt"
    target.write_text("EARLIER")

    def half(tmp: str) -> None:
        Path(tmp).write_text("HALF")
        raise OSError(28, "No space left on device")

    def interrupted(tmp: str) -> None:
        Path(tmp).write_text("HALF")
        raise KeyboardInterrupt

    with pytest.raises(OSError, match="No space left"):
        replace_atomically(target, half)
    with pytest.raises(KeyboardInterrupt):
        replace_atomically(target, interrupted)
    assert target.read_text() == "EARLIER"
    assert [p.name for p in tmp_path.iterdir()] == ["f.txt"]
    new = tmp_path / "new.txt"
    umask = os.umask(0o022)
    try:
        write_text_atomically(new, "x\n")
    finally:
        os.umask(umask)
    assert new.read_text() == "x\n" and stat.S_IMODE(new.stat().st_mode) == 0o644
