"""Heave scene schema: problem files load; unknown keys and bad values are rejected."""

from __future__ import annotations

from pathlib import Path

import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.scene import load_scene, scene_from_dict

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("name", ["ex_6_2_6.toml", "ex_6_3_6.toml"])
def test_problem_files_load(name: str) -> None:
    sc = load_scene(ROOT / "problems" / "heave" / name)
    assert sc.source.startswith("004")


@pytest.mark.parametrize("doc,match", [
    ({"sea": {"modal_frequency": 0.7, "colour": "blue"}}, "unknown key \\[sea\\] 'colour'"),
    ({"bogus": {}}, "unknown top-level key 'bogus'"),
    ({"sea": {"modal_frequency": 0.7, "spectrum": "foo"}}, "spectrum = 'foo'"),
    ({"sea": {}}, "exactly one of modal_frequency"),
    ({"sea": {"modal_frequency": 0.7}, "winch": {"delay": 0.12}}, "integer multiple"),
    ({"sea": {"modal_frequency": 0.7}, "winch": {"accel_max": 1.0}}, "command_rate_max"),
    ({"sea": {"modal_frequency": 0.7}, "unit": {"cable_scene": "x.toml"}}, "cable_scene"),
    ({"sea": {"modal_frequency": 0.7}, "controller": {"horizon": 2.5}}, "integer"),
    ({"sea": {"modal_frequency": 0.7}, "controller": {"controllers": ["pid"]}}, "controllers"),
])
def test_bad_scenes_raise(doc: dict, match: str) -> None:
    with pytest.raises(CableOCPError, match=match):
        scene_from_dict(doc)


def test_missing_file_raises() -> None:
    with pytest.raises(CableOCPError, match="not found"):
        load_scene("/nonexistent/heave.toml")
