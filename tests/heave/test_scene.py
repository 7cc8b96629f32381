"""Heave scene schema: problem files load; unknown keys and bad values are rejected."""

from __future__ import annotations

from pathlib import Path

import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.heave import load_scene, scene_from_dict

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("name", ["compare_6_2_6.toml", "ex_6_3_6.toml"])
def test_problem_files_load(name: str) -> None:
    sc = load_scene(ROOT / "problems" / "heave" / name)
    assert sc.meta["source"] and sc.title


@pytest.mark.parametrize("doc,match", [
    ({"sea": {"modal_frequency": 0.7, "colour": "blue"}}, "unknown key sea.colour"),
    ({"bogus": {}}, "unknown top-level table \\[bogus\\]"),
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


@pytest.mark.parametrize("table,key,val", [
    ("winch", "stroke_max", -1.0),        # reached qpOASES as a RuntimeError before
    ("winch", "speed_max", 0.0),          # ZeroDivisionError in the metrics before
    ("winch", "command_rate_max", -0.1),
    ("winch", "delay", -0.2),
    ("controller", "q", -1.0),            # LinAlgError in the Riccati solver before
    ("controller", "preview_time", -1.0),  # IndexError in the simulation before
    ("controller", "r", 0.0),             # accepted silently before
    ("controller", "measurement_noise", 0.0),
    ("sea", "peak_enhancement", 0.0),     # accepted silently before
    ("sea", "peak_enhancement", -1.0),
    ("unit", "a", 0.0),
    ("simulation", "seed", -1),
])
def test_bad_values_raise_naming_the_key(table: str, key: str, val: float) -> None:
    doc: dict = {"sea": {"modal_frequency": 0.7}}
    doc.setdefault(table, {})[key] = val
    with pytest.raises(CableOCPError, match=f"^{table}\\.{key} = "):
        scene_from_dict(doc)


def test_problem_file_with_bad_value_raises_before_simulating(tmp_path: Path) -> None:
    # The CLI path: a problem file with a bad limit fails at load time with the key named.
    src = (ROOT / "problems" / "heave" / "ex_6_3_6.toml").read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text(src.replace("stroke_max = 2.0", "stroke_max = -1.0"))
    with pytest.raises(CableOCPError, match=r"^winch\.stroke_max = -1\.0: must be > 0 \(m\)$"):
        load_scene(bad)


@pytest.mark.parametrize("key,val", [("stroke_max", -1.0), ("speed_max", 0.0), ("q", -1.0),
                                     ("r", 0.0), ("preview_time", -1.0)])
def test_mpc_settings_checked_in_the_python_api(plant_636, key: str, val: float) -> None:  # noqa: ANN001
    from cable_ocp.heave import mpc

    with pytest.raises(CableOCPError, match=f"{key} = "):
        mpc.LinearMPC(plant_636, 0.0, mpc.MPCSettings(horizon=5, **{key: val}))


def test_missing_file_raises() -> None:
    with pytest.raises(CableOCPError, match="not found"):
        load_scene("/nonexistent/heave.toml")


def _valid_doc() -> dict:
    import tomllib

    return tomllib.loads((ROOT / "problems" / "heave" / "ex_6_3_6.toml").read_text())


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -1e300, 1e300, "x", True])
def test_every_number_is_finite_and_in_its_range(bad: object) -> None:
    """Every numeric key of RULES rejects non-finite, huge and non-numbers, naming itself
    in the statics style (``table.key = value: ...``)."""
    from cable_ocp.scene.heave import RULES

    for table, key in RULES:
        doc = _valid_doc()
        doc.setdefault(table, {})[key] = bad
        if key in ("zero_crossing_period", "peak_period"):
            del doc["sea"]["modal_frequency"]
        with pytest.raises(CableOCPError, match=f"^{table}\\.{key} = "):
            scene_from_dict(doc)


def test_range_message_gives_the_bounds_and_the_reason() -> None:
    doc = _valid_doc()
    doc["vessel"]["damping_ratio"] = 6e5
    with pytest.raises(CableOCPError) as err:
        scene_from_dict(doc)
    assert str(err.value).startswith("vessel.damping_ratio = 600000.0: must be in [0.01, 10] (-);")


def test_rk4_step_checked_against_the_fastest_mode() -> None:
    """K = 300 1/s with h_sim = 0.01 s: |lambda| h = 3 (RK4 unstable beyond 2.79); the
    message names simulation.substeps and the least value with |lambda| h <= 1 (15)."""
    doc = _valid_doc()
    doc["winch"]["gain"] = 300.0
    with pytest.raises(CableOCPError, match=r"^simulation\.substeps = 5: .*winch\.gain.* >= 15$"):
        scene_from_dict(doc)
    doc["simulation"]["substeps"] = 15
    scene_from_dict(doc)


def test_scenes_built_in_python_are_checked() -> None:
    import dataclasses

    from cable_ocp.scene.heave import check

    sc = load_scene(ROOT / "problems" / "heave" / "ex_6_3_6.toml")
    bad = dataclasses.replace(sc, winch=dataclasses.replace(sc.winch, delay=-1.0))
    with pytest.raises(CableOCPError, match=r"^winch\.delay = -1\.0: must be >= 0 \(s\)$"):
        check(bad)
