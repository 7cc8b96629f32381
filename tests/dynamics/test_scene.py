"""Dynamic scene validation: every bad key is named, statics and dynamics files are told
apart, and the statics part of a dynamic scene is the problem of the static start."""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.dynamics import dynamic_scene_from_dict, load_dynamic_scene
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.motion import length_numeric, motion_function

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"

BASE = {
    "environment": {"water_depth": 1000.0, "water_density": 1025.0},
    "cable": {"length": 100.0, "diameter": 0.03, "weight_in_water": 30.0,
              "axial_stiffness": 5.0e7, "mass_per_length": 4.0, "tangential_drag": 0.01},
    "unit": {"mass": 1000.0, "added_mass": 500.0, "weight_in_water": 8000.0,
             "drag_area": 1.0, "drag_coefficient": 1.0},
    "end_b": {"position": [0.0, 0.0, 1000.0]},
    "top_motion": {"heave_amplitude": 1.0, "heave_frequency": 0.8},
    "simulation": {"model": "axial", "duration": 10.0, "time_step": 0.01},
}


def with_(path: str, value) -> dict:
    """BASE with one dotted key set (value None deletes it)."""
    d = copy.deepcopy(BASE)
    parts = path.split(".")
    node = d
    for p in parts[:-1]:
        node = node.setdefault(p, {})
    if value is None:
        node.pop(parts[-1], None)
    else:
        node[parts[-1]] = value
    return d


def test_base_scene_parses_with_defaults() -> None:
    s = dynamic_scene_from_dict(BASE)
    assert s.length == 100.0
    assert s.cable[0].added_mass_coefficient == 1.0  # normal C_a default (cylinder)
    assert s.cable[0].tangential_added_mass_coefficient == 0.0
    assert s.unit.added_mass == (500.0, 500.0, 500.0)
    assert s.simulation.segments == 20 and s.simulation.start == "static"
    assert s.simulation.scheme == "midpoint" and s.simulation.steps == 1000
    # the static start: end_a free, loaded by the unit's weight in water
    assert s.statics.end_a.position == (None, None, None)
    assert s.statics.end_a.force == (0.0, 0.0, -8000.0)
    assert s.statics.end_b.position == (0.0, 0.0, 1000.0)


@pytest.mark.parametrize("path,value,needle", [
    ("cable.mass_per_length", None, "cable.mass_per_length is missing"),
    ("cable.mass_per_length", -1.0, "cable.mass_per_length"),
    ("cable.mass_per_length", 1.0, "cable.mass_per_length"),  # lighter than its weight in water
    ("cable.added_mass_coefficient", -0.5, "cable.added_mass_coefficient"),
    ("cable.axial_damping", float("nan"), "cable.axial_damping"),
    ("cable.bogus", 1.0, "cable.bogus"),
    ("unit.mass", None, "unit.mass is missing"),
    ("unit.added_mass", [1.0, 2.0], "unit.added_mass"),
    ("unit.weight_in_water", 1e6, "unit.weight_in_water"),
    ("unit.drag_area", 0.0, "drag_coefficient"),
    ("unit.colour", "red", "unit.colour"),
    ("top_motion.heave_frequency", None, "top_motion.heave_frequency is missing"),
    ("top_motion.heave_frequency", 0.0, "top_motion.heave_frequency"),
    ("top_motion.payout_law", "cubic", "top_motion.payout_law"),
    ("top_motion.payout_amplitude", 1.0, "top_motion.payout_amplitude"),
    ("top_motion.payout_speed", -20.0, "top_motion.payout_speed"),  # length < 0 in 10 s
    ("top_motion.tow", {"speed": 2.0, "straight_length": 10.0}, "top_motion.tow.turn_diameter"),
    ("top_motion.tow", {"speed": 2.0, "sped": 1.0}, "top_motion.tow.sped"),
    ("top_motion.ramp_time", -1.0, "top_motion.ramp_time"),
    ("top_motion.series", [[0.0, 0, 0, 0], [0.0, 0, 0, 1]], "top_motion.series"),
    ("simulation.model", "spectral", "simulation.model"),
    ("simulation.model", None, "simulation.model is missing"),
    ("simulation.time_step", 0.003, "simulation.duration"),  # not a whole number of steps
    ("simulation.time_step", 20.0, "simulation.time_step"),
    ("simulation.output_step", 0.015, "simulation.output_step"),
    ("simulation.segments", 0, "simulation.segments"),
    ("simulation.segments", 2.5, "simulation.segments"),
    ("simulation.scheme", "rk4", "simulation.scheme"),
    ("simulation.start", "moving", "simulation.start"),
    ("simulation.on_slack", "ignore", "simulation.on_slack"),
    ("simulation.colour", 1, "simulation.colour"),
    ("modes.wave_band", [1.0, 0.5], "modes.wave_band"),
    ("modes.count", 0, "modes.count"),
    ("end_b.force", [0.0, 0.0, 1.0], "end_b"),
    ("cable.length", "free", "cable.length"),
])
def test_bad_keys_are_named(path: str, value, needle: str) -> None:
    with pytest.raises(CableOCPError, match=needle.replace(".", r"\.").replace("(", r"\(")):
        dynamic_scene_from_dict(with_(path, value))


def test_unknown_key_lists_the_valid_ones() -> None:
    with pytest.raises(CableOCPError) as exc:
        dynamic_scene_from_dict(with_("simulation.colour", 1))
    assert "time_step" in str(exc.value) and "segments" in str(exc.value)


def test_unknown_table_lists_the_dynamic_scene_tables() -> None:
    """An unknown top-level table names the tables a dynamic scene takes (the dynamic ones
    included, not the statics list)."""
    with pytest.raises(CableOCPError) as exc:
        dynamic_scene_from_dict(with_("nonsense.key", 1))
    msg = str(exc.value)
    assert "[nonsense]" in msg
    assert all(t in msg for t in ("simulation", "top_motion", "unit", "cable"))
    assert "footprint" not in msg and "layout" not in msg


def test_added_mass_needs_a_diameter_and_zero_is_valid() -> None:
    d = with_("cable.diameter", None)
    d["cable"].pop("tangential_drag")
    with pytest.raises(CableOCPError, match=r"cable\.diameter is missing.*added_mass"):
        dynamic_scene_from_dict(d)
    d["cable"]["added_mass_coefficient"] = 0.0
    s = dynamic_scene_from_dict(d)  # in air: no added mass, no drag, no diameter
    assert s.cable[0].added_mass_coefficient == 0.0


def test_unit_and_end_a_are_exclusive_and_anchor_is_accepted() -> None:
    d = with_("end_a", {"position": [0.0, 0.0, 0.0]})
    with pytest.raises(CableOCPError, match=r"\[end_a\] and \[unit\]"):
        dynamic_scene_from_dict(d)
    d.pop("unit")
    d["cable"]["length"] = 1000.5
    s = dynamic_scene_from_dict(d)
    assert s.anchored and s.statics.end_a.position == (0.0, 0.0, 0.0)
    d["end_a"] = {"force": [0.0, 0.0, -1.0]}
    with pytest.raises(CableOCPError, match="end_a"):
        dynamic_scene_from_dict(d)


def test_unit_volume_gives_weight_and_inconsistent_pair_is_rejected() -> None:
    d = with_("unit.weight_in_water", None)
    d["unit"]["volume"] = 0.354
    s = dynamic_scene_from_dict(d)
    assert s.unit.weight_in_water == pytest.approx((1000.0 - 1025.0 * 0.354) * 9.81, rel=1e-12)
    d["unit"]["weight_in_water"] = 8000.0
    with pytest.raises(CableOCPError, match="unit.weight_in_water .* disagrees with unit.volume"):
        dynamic_scene_from_dict(d)


def test_statics_and_dynamics_files_are_told_apart(tmp_path: Path) -> None:
    with pytest.raises(CableOCPError, match="statics scene.*cable-ocp solve"):
        load_dynamic_scene(PROBLEMS / "berteaux_mooring.toml")
    d = copy.deepcopy(BASE)
    d.pop("simulation")
    with pytest.raises(CableOCPError, match=r"\[simulation\] is missing"):
        dynamic_scene_from_dict(d)


def test_unit_drag_in_a_current_joins_the_static_load() -> None:
    """At rest in a current U the unit's drag is 1/2 rho C_D S |U| U (vector law)."""
    d = with_("environment.current", {"speed": 0.5, "heading_deg": 90.0})
    d["cable"]["normal_drag"] = 1.2
    s = dynamic_scene_from_dict(d)
    fx, fy, fz = s.statics.end_a.force
    assert fx == pytest.approx(0.0, abs=1e-9)
    assert fy == pytest.approx(0.5 * 1025.0 * 1.0 * 1.0 * 0.25, rel=1e-12)
    assert fz == -8000.0


def test_overrides_and_problem_files(tmp_path: Path) -> None:
    for f in sorted((PROBLEMS / "dynamics").glob("*.toml")):
        s = load_dynamic_scene(f)
        assert s.simulation.duration > 0
    s = load_dynamic_scene(PROBLEMS / "dynamics" / "huang_3_3_5.toml",
                           {"top_motion.payout_speed": 2.0, "simulation.segments": 8})
    assert s.top_motion.payout_speed == 2.0 and s.simulation.segments == 8
    assert s.with_overrides({"simulation.segments": 4}).simulation.segments == 4


def test_motion_laws_and_derivatives() -> None:
    """Pay-out laws of Huang (1992) 3.1 and the top offsets, against hand formulas."""
    d = with_("top_motion", {"heave_amplitude": 0.5, "heave_frequency": 1.3,
                             "payout_law": "quadratic", "payout_speed": 0.4,
                             "payout_acceleration": 0.02})
    s = dynamic_scene_from_dict(d)
    f = motion_function(s)
    t = 2.7
    length, dl, ddl, xb, vb, ab = (np.asarray(v).ravel() for v in f(t))
    assert length[0] == pytest.approx(100.0 + 0.4 * t + 0.01 * t**2, rel=1e-15)
    assert dl[0] == pytest.approx(0.4 + 0.02 * t, rel=1e-14)
    assert ddl[0] == pytest.approx(0.02, rel=1e-14)
    assert xb[2] == pytest.approx(1000.0 + 0.5 * math.sin(1.3 * t), rel=1e-15)
    assert vb[2] == pytest.approx(0.5 * 1.3 * math.cos(1.3 * t), rel=1e-13)
    assert ab[2] == pytest.approx(-0.5 * 1.3**2 * math.sin(1.3 * t), rel=1e-13)
    # periodic law, ramp: L = L0 + r(t) p sin(w t), r = 10x^3 - 15x^4 + 6x^5
    d = with_("top_motion", {"payout_law": "periodic", "payout_amplitude": 2.0,
                             "payout_frequency": 0.5, "ramp_time": 4.0})
    s = dynamic_scene_from_dict(d)
    ls, _ = length_numeric(s.top_motion, 100.0, [1.0, 6.0])
    x = 0.25
    assert ls[0] == pytest.approx(100.0 + x**3 * (10 - 15 * x + 6 * x**2) * 2.0 * math.sin(0.5),
                           rel=1e-15)
    assert ls[1] == pytest.approx(100.0 + 2.0 * math.sin(3.0), rel=1e-15)


def test_tow_path_loop_turn() -> None:
    """Huang (1992) 5.7.4: 800 m straight at 4 m/s, a 360 deg turn of 300 m diameter,
    straight again: after the turn the path is back on the first line, 300 pi m later."""
    d = with_("top_motion", {"tow": {"speed": 4.0, "straight_length": 800.0,
                                     "turn_diameter": 300.0}})
    s = dynamic_scene_from_dict(d)
    f = motion_function(s)
    def pos(t: float) -> np.ndarray:
        return np.asarray(f(t)[3]).ravel() - np.array([0.0, 0.0, 1000.0])
    np.testing.assert_allclose(pos(100.0), [400.0, 0.0, 0.0], atol=1e-9)
    quarter = (800.0 + 150.0 * math.pi / 2) / 4.0  # a quarter of the turn (left)
    np.testing.assert_allclose(pos(quarter), [950.0, 150.0, 0.0], atol=1e-9)
    half = (800.0 + 150.0 * math.pi) / 4.0
    np.testing.assert_allclose(pos(half), [800.0, 300.0, 0.0], atol=1e-9)
    after = (800.0 + 300.0 * math.pi + 100.0) / 4.0
    np.testing.assert_allclose(pos(after), [900.0, 0.0, 0.0], atol=1e-9)
    # speed along the path is 4 m/s everywhere
    for t in (10.0, quarter, half, after):
        assert np.linalg.norm(np.asarray(f(t)[4]).ravel()) == pytest.approx(4.0, rel=1e-12)


def test_static_start_takes_the_units_drag_at_its_solved_height() -> None:
    """In a sheared current U(z) = (z - 200) / 300 m/s (linear from 0 at z = 200 m to
    1 m/s at the surface, written here from the profile's knots) the unit's drag depends
    on where it settles: the static start must re-solve until the drag is the one at the
    unit's solved height. The unit's balance (cable pull at s = 0 plus weight and drag)
    then holds with D = 1/2 rho C_D S U(z_0)^2 along x: to 1e-6 (the statics tolerance;
    seen 1e-7). The drag taken at the height first estimated (the line hanging straight
    down, z = 290 m) is 14 % off: the unit settles at z = 297 m, 52 m downstream."""
    from cable_ocp.dynamics.static import static_state

    rho, area, weight = 1025.0, 20.0, 5000.0
    d = {"environment": {"water_depth": 500.0, "water_density": rho,
                         "current": {"profile": [[200.0, 0.0, 0.0], [500.0, 1.0, 0.0]]}},
         "cable": {"length": 200.0, "diameter": 0.03, "weight_in_water": 10.0,
                   "axial_stiffness": 1.0e8, "mass_per_length": 12.0, "normal_drag": 1.2,
                   "tangential_drag": 0.01},
         "unit": {"mass": 1000.0, "weight_in_water": weight, "drag_area": area,
                  "drag_coefficient": 1.0},
         "end_b": {"position": [0.0, 0.0, 490.0]},
         "simulation": {"model": "lumped3d", "duration": 1.0, "time_step": 0.1}}
    sol = static_state(dynamic_scene_from_dict(d))
    assert sol.success, sol.message
    assert sol.diagnostics["unit_current_updates"] >= 2
    z0 = float(sol.position[0, 2])
    u0 = (z0 - 200.0) / 300.0
    drag = 0.5 * rho * 1.0 * area * u0 * abs(u0)
    assert drag > 1000.0  # a real load: the unit swings downstream
    # the cable's pull on the unit (its tension along the line towards end_b) balances the
    # weight and the drag: T(0) = (-D, 0, W)
    np.testing.assert_allclose(sol.tension_vector[0], [-drag, 0.0, weight], rtol=1e-6,
                               atol=1e-6 * weight)
