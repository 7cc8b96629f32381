"""Every example script is a command with --help: argparse, a description, an --out option
for its figure with a default file name; --help prints and writes nothing."""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

import pytest

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.py"))


@pytest.mark.parametrize("script", EXAMPLES, ids=lambda p: p.stem)
def test_example_help(script: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                      capsys: pytest.CaptureFixture[str]) -> None:
    spec = importlib.util.spec_from_file_location(script.stem, script)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as exc:
        mod.main(["--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    assert out.startswith("usage:") and "--out PATH" in out and "(default" in out
    assert len(out.split("\n\n")[1]) > 40  # a description paragraph after the usage
    assert os.listdir(tmp_path) == []      # nothing written (no "--help.png")
    with pytest.raises(SystemExit) as exc:
        mod.main(["--no-such-option"])
    assert exc.value.code == 2
