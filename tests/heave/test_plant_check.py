"""A cable scene that its model cannot run as the heave plant is refused by the model-side
check (:func:`cable_ocp.heave.cable_models.check_plant_scene`), before any work: the heave
scene itself (``cable_ocp.scene.heave``) imports no model, so this check runs after it is
built, when the comparison starts, and the command exits 2 with one line naming the key."""

from __future__ import annotations

from pathlib import Path

import pytest
from heave_files import heave_with_line

from cable_ocp.cli import main
from cable_ocp.errors import CableOCPError
from cable_ocp.heave.cable_compare import compare
from cable_ocp.scene.heave import load_scene

LINE = Path(__file__).resolve().parents[2] / "problems" / "dynamics" / "line_6_3_6.toml"
CURRENT = "[environment.current]\nspeed = 0.5\nheading_deg = 0.0\n\n[cable]\nnormal_drag = 1.2"


def _axial_line_in_a_current(tmp_path: Path) -> Path:
    text = LINE.read_text()
    assert text.count("\n[cable]") == 1
    return heave_with_line(tmp_path, "ex_6_3_6_cable.toml", text.replace("[cable]", CURRENT, 1))


def test_the_scene_builds_and_the_model_refuses_it(tmp_path: Path) -> None:
    """The heave scene validates (its keys are right); the axial model refuses a current,
    and the message names ``unit.cable_scene`` and what to change."""
    sc = load_scene(_axial_line_in_a_current(tmp_path))
    with pytest.raises(CableOCPError, match=r"unit.cable_scene = .*line.toml.*remove "
                                            r"\[environment.current\]"):
        compare(sc)


def test_the_command_exits_2_with_one_line(tmp_path: Path, capsys: pytest.CaptureFixture
                                           ) -> None:
    code = main(["heave", str(_axial_line_in_a_current(tmp_path)), "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert len(err) == 1 and "environment.current" in err[0], err
