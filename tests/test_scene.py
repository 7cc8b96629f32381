"""Problem-file validation: every user error is one CableOCPError naming the key."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.scene import load_scene, parse_override, scene_from_dict

PROBLEMS = Path(__file__).resolve().parents[1] / "problems"


@pytest.fixture()
def base(problems) -> dict:
    with (problems / "dezoysa_sea_buggy.toml").open("rb") as fh:
        return tomllib.load(fh)


def set_key(d: dict, key: str, value) -> dict:
    node = d
    parts = key.split(".")
    for p in parts[:-1]:
        node = node.setdefault(p, {})
    if value is None:
        del node[parts[-1]]
    else:
        node[parts[-1]] = value
    return d


@pytest.mark.parametrize(("key", "value", "words"), [
    ("cable.length", -5.0, ["cable.length", "> 0"]),
    ("cable.length", 200.0, ["cable.length", "chord"]),
    ("cable.lenght", 305.0, ["cable.lenght", "valid keys"]),
    ("cable.weight_in_water", None, ["cable.weight_in_water", "missing"]),
    ("environment.water_density", None, ["environment.water_density", "missing"]),
    ("cable.diameter", math.nan, ["cable.diameter", "finite"]),
    ("cable.diameter", "thick", ["cable.diameter", "number"]),
    ("cable.drag_law", "morison", ["cable.drag_law", "vector"]),
    ("cable.axial_stiffness", -1.0, ["cable.axial_stiffness", "> 0"]),
    ("end_b.position", [1.0, 2.0], ["end_b.position", "3 entries"]),
    ("end_b.force", [1.0, 2.0, 3.0], ["end_b", "exactly one"]),
    ("solver.degree", 0, ["solver.degree", "1..9"]),
    ("solver.scheme", "chebyshev", ["solver.scheme", "legendre"]),
    ("environment.current.speed", math.inf, ["environment.current.speed", "finite"]),
    ("environment.current.knots", 1, ["environment.current.knots", "valid"]),
    ("widget", {}, ["widget", "top-level"]),
])
def test_bad_input_names_the_key(base, key, value, words):
    with pytest.raises(CableOCPError) as err:
        scene_from_dict(set_key(base, key, value))
    for w in words:
        assert w in str(err.value), str(err.value)


def test_free_length_needs_a_tension(base):
    set_key(base, "cable.length", "free")
    with pytest.raises(CableOCPError, match="end_a.tension or end_b.tension"):
        scene_from_dict(base)


def test_tension_needs_free_length(base):
    set_key(base, "end_b.tension", 5000.0)
    with pytest.raises(CableOCPError, match='cable.length = "free"'):
        scene_from_dict(base)


def test_free_everywhere_rejected(base):
    del base["layout"]
    set_key(base, "end_a.position", ["free", 0.0, 0.0])
    set_key(base, "end_a.force", [100.0, "free", "free"])
    set_key(base, "end_b.position", ["free", 0.0, 183.0])
    set_key(base, "end_b.force", [100.0, "free", "free"])
    with pytest.raises(CableOCPError, match="the x position is free at both ends"):
        scene_from_dict(base)


def test_elastic_cable_may_be_shorter_than_chord(base):
    set_key(base, "cable.length", 250.0)
    set_key(base, "cable.axial_stiffness", 1.0e6)
    assert scene_from_dict(base).cable.length == 250.0


def test_no_current_means_no_drag_fields_needed(base):
    del base["environment"]["current"]
    for k in ("diameter", "normal_drag", "tangential_drag"):
        del base["cable"][k]
    assert scene_from_dict(base).environment.current is None


def test_psi0_rotates_end_b(base):
    sc = scene_from_dict(base)  # psi0 = 90 in the file
    assert sc.end_b.position == pytest.approx((0.0, 229.0, 183.0), abs=1e-12)


def test_overrides(problems):
    assert parse_override("end_b.position=[0,229,183]") == ("end_b.position", [0, 229, 183])
    assert parse_override("cable.length=free") == ("cable.length", "free")
    assert parse_override("solver.degree=4") == ("solver.degree", 4)
    sc = load_scene(problems / "dezoysa_sea_buggy.toml",
                    dict([parse_override("layout.psi0_deg=0"),
                          parse_override("cable.drag_law=vector")]))
    assert sc.end_b.position == pytest.approx((229.0, 0.0, 183.0))
    assert sc.cable.drag_law == "vector"
    with pytest.raises(CableOCPError, match="key=value"):
        parse_override("cable.length")


def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(CableOCPError, match="not found"):
        load_scene(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[cable\nlength = 3")
    with pytest.raises(CableOCPError, match="not valid TOML"):
        load_scene(bad)


def test_shipped_problems_load(problems):
    for f in sorted(problems.glob("*.toml")):
        sc = load_scene(f)
        assert sc.meta.get("source"), f"{f.name} must cite its source in [meta]"


@pytest.mark.parametrize("name,loader", [
    ("dezoysa_sea_buggy.toml", "cable_ocp.scene.statics:load_scene"),
    ("dynamics/huang_5_7.toml", "cable_ocp.scene.dynamics:load_dynamic_scene"),
    ("heave/ex_6_3_6_cable.toml", "cable_ocp.scene.heave:load_scene"),
])
def test_one_loader_reads_every_kind(name: str, loader: str) -> None:
    """``cable_ocp.load`` (one loader for every problem file) returns the scene the kind's
    own loader returns, with the same overrides; the kind's loader refuses the others."""
    import importlib

    import cable_ocp

    mod, fn = loader.split(":")
    own = getattr(importlib.import_module(mod), fn)
    path = PROBLEMS / name
    over = {"meta.title": "renamed"}
    assert cable_ocp.load(path, over) == own(path, over)
    assert cable_ocp.load(path) == own(path)
    others = {"statics": PROBLEMS / "dezoysa_sea_buggy.toml",
              "dynamics": PROBLEMS / "dynamics" / "huang_5_7.toml",
              "heave": PROBLEMS / "heave" / "ex_6_3_6.toml"}
    kind = {"cable_ocp.scene.statics": "statics", "cable_ocp.scene.dynamics": "dynamics",
            "cable_ocp.scene.heave": "heave"}[mod]
    for other, p in others.items():
        if other != kind:
            with pytest.raises(CableOCPError, match=f"a {other} scene"):
                own(p)
