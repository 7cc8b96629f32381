"""A write that fails part-way keeps the earlier file (issue 22, fault 2; CONVENTIONS "Exit
codes": an output that cannot be written, e.g. a full disk, found after the solve: exit 2,
the earlier file is kept).

The fault is real, not mocked: the command runs in a subprocess under a file-size limit
(``RLIMIT_FSIZE`` of 2000 bytes, ``SIGXFSZ`` ignored), so that the kernel fails the write
past 2000 bytes with ``EFBIG`` exactly as a full disk fails it with ``ENOSPC`` (the same
``OSError`` path). Before the fix ``--json`` truncated the earlier file in place, left 2000
bytes of JSON and exited 3 ("internal error: OSError").
"""

from __future__ import annotations

import os
import resource
import signal
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from cable_ocp.numerics.atomic import replace_atomically, write_text_atomically

ROOT = Path(__file__).resolve().parents[1]
PROBLEM = ROOT / "problems" / "dezoysa_sea_buggy.toml"
LIMIT = 2000  # bytes: the solve's JSON, CSV and figure are each larger


def _limited() -> None:
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (LIMIT, LIMIT))


@pytest.fixture(scope="module")
def warm_cache(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """A cache the problem's functions are already in, so that the limited runs write only
    their output: made by the control run of :func:`test_the_same_write_succeeds_without_the_limit`
    (without the limit, ``--json`` onto an earlier file of mode 0640)."""
    cache = tmp_path_factory.mktemp("cache")
    work = tmp_path_factory.mktemp("control")
    target = work / "out.json"
    target.write_text("EARLIER\n")
    target.chmod(0o640)
    env = {**os.environ, "CABLE_OCP_CACHE_DIR": str(cache)}
    r = subprocess.run([sys.executable, "-m", "cable_ocp", "solve", str(PROBLEM), "--json",
                        "out.json", "--quiet"], env=env, capture_output=True, text=True, cwd=work)
    assert r.returncode == 0, r.stderr
    return cache, target


@pytest.mark.parametrize("option,name", [("--json", "out.json"), ("--csv", "out.csv"),
                                         ("--plot", "out.png")])
def test_a_failed_write_keeps_the_earlier_file_and_exits_2(
        tmp_path: Path, warm_cache: tuple[Path, Path], option: str, name: str) -> None:
    target = tmp_path / name
    target.write_text("EARLIER\n")
    env = {**os.environ, "CABLE_OCP_CACHE_DIR": str(warm_cache[0]), "MPLBACKEND": "Agg"}
    r = subprocess.run([sys.executable, "-m", "cable_ocp", "solve", str(PROBLEM), option,
                        name, "--quiet"], env=env, capture_output=True, text=True,
                       cwd=tmp_path, preexec_fn=_limited)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert lines == [f"cable-ocp: error: {option} {name}: could not be written (File too "
                     "large); the earlier file is kept"]
    assert target.read_text() == "EARLIER\n"
    assert [p.name for p in tmp_path.iterdir()] == [name]


def test_the_same_write_succeeds_without_the_limit(warm_cache: tuple[Path, Path]) -> None:
    """The control: the same command without the limit replaced the earlier file whole
    (valid JSON, larger than the limit), kept its permissions and left no other file."""
    import json

    target = warm_cache[1]
    assert json.loads(target.read_text())["status"] == "solved"
    assert target.stat().st_size > LIMIT
    assert stat.S_IMODE(target.stat().st_mode) == 0o640
    assert [p.name for p in target.parent.iterdir()] == ["out.json"]


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
