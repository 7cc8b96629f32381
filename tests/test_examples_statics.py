"""The statics example scripts run and reproduce their figure's numbers."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _load(name: str):  # noqa: ANN202
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_wang_fig3(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    mod = _load("wang_fig3")
    data = mod.compute(step=30.0)
    i90 = list(data["psi0"]).index(90.0)
    # Wang, Cheong & Chucheepsakul (1993), Fig. 3 text: Tx ~ 1.580 kN at psi0 = 90 deg
    assert data["componentwise"][i90, 0] == pytest.approx(1580.0, rel=5e-3)
    # flagged exactly where the componentwise cable dips below the seabed (> 147.9 deg)
    np.testing.assert_array_equal(data["componentwise_below_seabed"], data["psi0"] > 147.9)
    out = mod.plot(data, tmp_path / "fig3.png")
    assert out.stat().st_size > 20_000
    assert mod.main(["--out", str(tmp_path / "m.png"), "--step", "45"]) == 0
    cap = capsys.readouterr()
    assert "psi0 = 90 deg" in cap.out
    assert f"wrote {tmp_path / 'm.png'}" in cap.err  # the file written, on stderr
    assert (tmp_path / "m.png").stat().st_size > 20_000
