"""Heave scene files: TOML -> frozen dataclasses (unknown keys are rejected).

Schema (SI units; see ``problems/heave/*.toml`` for commented examples)::

    [meta]                   # optional, free-form text as in every scene kind
    title = "..."
    source = "..."           # citation

    [sea]
    spectrum = "bretschneider" | "pierson_moskowitz" | "jonswap"
    significant_wave_height = 3.048      # m
    modal_frequency = 0.785              # rad/s  (or zero_crossing_period / peak_period, s)
    peak_enhancement = 3.3               # JONSWAP gamma
    shaping_filter = "thesis" | "fit"    # (6.21)-(6.23) default, or a least-squares fit
    filter_order = 3                     # second-order sections of the fit

    [vessel]
    model = "second_order" | "none"      # (6.25), or boom tip = sea surface
    natural_frequency = 0.393            # rad/s
    damping_ratio = 0.6
    gain = 0.5

    [winch]
    model = "first_order" | "second_order"
    gain = 1.0                           # K, 1/s (first order, (6.1))
    natural_frequency = 1.4              # rad/s (second order)
    damping_ratio = 0.7
    delay = 0.2                          # s
    stroke_max = 3.0                     # m        (hard)
    speed_max = 1.5                      # m/s      (hard)
    command_rate_max = 0.1               # m/sample (hard, first order)
    accel_max = 1.0                      # m/s^2    (hard, second order)
    tension_min = 5000.0                 # N        (soft; needs [unit] mass, static_tension)

    [unit]
    a = 0.8959                           # s^2 (6.2)
    b = 0.1658                           # s
    model = "linear" | "quadratic"       # simulation plant: (6.2) or (6.3)
    b_quadratic = 0.2                    # s^2/m, (6.3)
    mass = 125000.0                      # kg (with added mass)
    static_tension = 50000.0             # N at the unit

    [controller]
    q = 553.6                            # 1/m^2, weight on the unit's heave
    r = 1.0                              # 1/m^2, weight on the command
    horizon = 50
    sample_time = 0.05                   # s
    solver = "daqp" | "qpoases" | "osqp" | "qrqp" | "ipopt"
    preview_time = 0.0                   # s
    measurement_noise = 0.01             # m, std of the sampled position sensor (LQG)
    controllers = ["passive", "lqr", "lqg", "mpc"]

    [simulation]
    duration = 300.0                     # s
    seed = 1
    substeps = 5                         # plant integration steps per control sample
    warmup = 30.0                        # s discarded from the metrics
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.files import apply_overrides, check_kind, read_problem
from cable_ocp.scene.parts import parse_meta


@dataclass(frozen=True)
class SeaSpec:
    """``[sea]``: see module docstring."""

    spectrum: str = "bretschneider"
    significant_wave_height: float = 3.048
    modal_frequency: float | None = None
    zero_crossing_period: float | None = None
    peak_period: float | None = None
    peak_enhancement: float = 3.3
    shaping_filter: str = "thesis"
    filter_order: int = 3


@dataclass(frozen=True)
class VesselSpec:
    """``[vessel]`` (004 eq. (6.25))."""

    model: str = "second_order"
    natural_frequency: float = 0.393
    damping_ratio: float = 0.6
    gain: float = 0.5


@dataclass(frozen=True)
class WinchSpec:
    """``[winch]`` (004 eqs. (6.1), (6.12)) and its limits."""

    model: str = "first_order"
    gain: float = 1.0
    natural_frequency: float = 1.4
    damping_ratio: float = 0.7
    delay: float = 0.0
    stroke_max: float | None = None
    speed_max: float | None = None
    command_rate_max: float | None = None
    accel_max: float | None = None
    tension_min: float | None = None


@dataclass(frozen=True)
class UnitSpec:
    """``[unit]`` (004 eqs. (6.2), (6.3))."""

    a: float = 0.8959
    b: float = 0.1658
    model: str = "linear"
    b_quadratic: float = 0.0
    mass: float = 0.0
    static_tension: float = 0.0
    cable_scene: str | None = None


@dataclass(frozen=True)
class ControllerSpec:
    """``[controller]``."""

    q: float = 553.6
    r: float = 1.0
    horizon: int = 50
    sample_time: float = 0.05
    solver: str = "daqp"
    terminal: str = "dare"
    preview_time: float = 0.0
    measurement_noise: float = 0.01
    tension_penalty: float = 1e6
    controllers: tuple = ("passive", "lqr", "lqg", "mpc")


@dataclass(frozen=True)
class SimulationSpec:
    """``[simulation]``."""

    duration: float = 300.0
    seed: int = 1
    substeps: int = 5
    warmup: float = 30.0


@dataclass(frozen=True)
class HeaveScene:
    """A complete heave scene."""

    sea: SeaSpec = field(default_factory=SeaSpec)
    vessel: VesselSpec = field(default_factory=VesselSpec)
    winch: WinchSpec = field(default_factory=WinchSpec)
    unit: UnitSpec = field(default_factory=UnitSpec)
    controller: ControllerSpec = field(default_factory=ControllerSpec)
    simulation: SimulationSpec = field(default_factory=SimulationSpec)
    meta: dict[str, str] = field(default_factory=dict, compare=False, hash=False)
    raw: dict[str, Any] = field(default_factory=dict, compare=False, hash=False, repr=False)

    @property
    def title(self) -> str:
        """``[meta] title``, or an empty string."""
        return self.meta.get("title", "")

    def with_overrides(self, overrides: dict[str, Any]) -> HeaveScene:
        """A new scene with dotted-key overrides applied to the source dict."""
        return scene_from_dict(apply_overrides(self.raw, overrides))


_CHOICES = {
    ("sea", "spectrum"): ("bretschneider", "pierson_moskowitz", "jonswap"),
    ("sea", "shaping_filter"): ("thesis", "fit"),
    ("vessel", "model"): ("second_order", "none"),
    ("winch", "model"): ("first_order", "second_order"),
    ("unit", "model"): ("linear", "quadratic"),
    ("controller", "solver"): ("daqp", "qpoases", "osqp", "qrqp", "ipopt"),
    ("controller", "terminal"): ("dare", "none"),
}
_CONTROLLERS = ("passive", "lqr", "lqg", "mpc")


def _build(cls: type, table: str, data: dict[str, Any]) -> Any:
    if not isinstance(data, dict):
        raise CableOCPError(f"[{table}] must be a table")
    known = {f.name: f for f in fields(cls)}
    kwargs: dict[str, Any] = {}
    for key, val in data.items():
        if key not in known:
            raise CableOCPError(
                f"unknown key [{table}] {key!r}; valid keys: {', '.join(sorted(known))}"
            )
        default = known[key].default
        if (table, key) in _CHOICES and val not in _CHOICES[(table, key)]:
            raise CableOCPError(
                f"[{table}] {key} = {val!r} is invalid; valid: {_CHOICES[(table, key)]}"
            )
        if key == "controllers":
            if not isinstance(val, list) or any(v not in _CONTROLLERS for v in val):
                raise CableOCPError(
                    f"[controller] controllers = {val!r} is invalid; give a list of {_CONTROLLERS}"
                )
            val = tuple(val)
        elif isinstance(default, bool):
            pass
        elif isinstance(default, int) and not isinstance(val, int):
            raise CableOCPError(f"[{table}] {key} = {val!r} must be an integer")
        elif key == "cable_scene":
            if not isinstance(val, str):
                raise CableOCPError(f"[{table}] {key} = {val!r} must be a file path (string)")
        elif isinstance(default, float) or default is None:
            if isinstance(val, bool) or not isinstance(val, (int, float)):
                raise CableOCPError(f"[{table}] {key} = {val!r} must be a number")
            val = float(val)
        kwargs[key] = val
    return cls(**kwargs)


def scene_from_dict(data: dict[str, Any]) -> HeaveScene:
    """Validate a parsed TOML document and return the scene.

    Raises
    ------
    CableOCPError
        On unknown tables or keys, wrong types, invalid choices or inconsistent values.
    """
    tables = {"sea": SeaSpec, "vessel": VesselSpec, "winch": WinchSpec, "unit": UnitSpec,
              "controller": ControllerSpec, "simulation": SimulationSpec}
    kwargs: dict[str, Any] = {"raw": copy.deepcopy(data)}
    for key, val in data.items():
        if key in tables:
            kwargs[key] = _build(tables[key], key, val)
        elif key == "meta":
            kwargs["meta"] = parse_meta(val)
        elif key in ("title", "source"):
            raise CableOCPError(f"{key} = ...: put it in the [meta] table ([meta] {key} = "
                                "\"...\"), as in every scene kind")
        else:
            raise CableOCPError(
                f"unknown top-level table [{key}]; valid: meta, {', '.join(tables)}"
            )
    scene = HeaveScene(**kwargs)
    check(scene)
    return scene


#: Sign rules for numeric keys: (table, key) -> (rule, unit); rule ">0" or ">=0". Optional keys
#: (None = not given) are only checked when given.
_SIGN_RULES: dict[tuple[str, str], tuple[str, str]] = {
    ("sea", "significant_wave_height"): (">0", "m"),
    ("sea", "modal_frequency"): (">0", "rad/s"),
    ("sea", "zero_crossing_period"): (">0", "s"),
    ("sea", "peak_period"): (">0", "s"),
    ("sea", "peak_enhancement"): (">0", "JONSWAP gamma, usually 1-7"),
    ("sea", "filter_order"): (">0", "second-order sections"),
    ("vessel", "natural_frequency"): (">0", "rad/s"),
    ("vessel", "damping_ratio"): (">0", "-"),
    ("vessel", "gain"): (">0", "-"),
    ("winch", "gain"): (">0", "1/s"),
    ("winch", "natural_frequency"): (">0", "rad/s"),
    ("winch", "damping_ratio"): (">0", "-"),
    ("winch", "delay"): (">=0", "s"),
    ("winch", "stroke_max"): (">0", "m"),
    ("winch", "speed_max"): (">0", "m/s"),
    ("winch", "command_rate_max"): (">0", "m per sample"),
    ("winch", "accel_max"): (">0", "m/s^2"),
    ("winch", "tension_min"): (">=0", "N"),
    ("unit", "a"): (">0", "s^2"),
    ("unit", "b"): (">0", "s"),
    ("unit", "b_quadratic"): (">=0", "s^2/m"),
    ("unit", "mass"): (">=0", "kg"),
    ("unit", "static_tension"): (">=0", "N"),
    ("controller", "q"): (">=0", "1/m^2"),
    ("controller", "r"): (">0", "1/m^2"),
    ("controller", "horizon"): (">0", "samples"),
    ("controller", "sample_time"): (">0", "s"),
    ("controller", "preview_time"): (">=0", "s"),
    ("controller", "measurement_noise"): (">0", "m"),
    ("controller", "tension_penalty"): (">0", "1/m^2"),
    ("simulation", "duration"): (">0", "s"),
    ("simulation", "seed"): (">=0", "-"),
    ("simulation", "substeps"): (">0", "-"),
    ("simulation", "warmup"): (">=0", "s"),
}


def _check_signs(sc: HeaveScene) -> None:
    for (table, key), (rule, unit) in _SIGN_RULES.items():
        val = getattr(getattr(sc, table), key)
        if val is None:
            continue
        ok = math.isfinite(val) and (val > 0 if rule == ">0" else val >= 0)
        if not ok:
            bound = "> 0" if rule == ">0" else ">= 0"
            raise CableOCPError(f"[{table}] {key} = {val!r} must be finite and {bound} ({unit})")


def check(sc: HeaveScene) -> None:
    """Validate a scene built in Python (``scene_from_dict`` calls it on every file).

    Raises
    ------
    CableOCPError
        Naming the offending key: a value of the wrong sign (limits, weights, times, model
        coefficients; see ``_SIGN_RULES``), a missing or ambiguous sea frequency, a delay that is
        not a whole number of samples, or inconsistent options.
    """
    _check_signs(sc)
    s = sc.sea
    given = [k for k in ("modal_frequency", "zero_crossing_period", "peak_period")
             if getattr(s, k) is not None]
    if len(given) != 1:
        raise CableOCPError(
            "[sea] give exactly one of modal_frequency (rad/s), zero_crossing_period (s), "
            f"peak_period (s); got {given or 'none'}"
        )
    if s.significant_wave_height <= 0:
        raise CableOCPError(f"[sea] significant_wave_height = {s.significant_wave_height} must "
                            "be > 0 m")
    if sc.unit.cable_scene is not None:
        raise CableOCPError(
            f"[unit] cable_scene = {sc.unit.cable_scene!r}: identifying a, b from a cable scene "
            "needs the cable-dynamics model, which is not available yet; give [unit] a and b "
            "(cable_ocp.heave.identify fits them to a recorded response)"
        )
    if sc.unit.model == "quadratic" and not sc.unit.b_quadratic > 0:
        raise CableOCPError("[unit] model = 'quadratic' needs b_quadratic > 0 (s^2/m, eq. (6.3))")
    c = sc.controller
    if c.sample_time <= 0 or c.horizon < 1:
        raise CableOCPError(f"[controller] sample_time = {c.sample_time} must be > 0 and "
                            f"horizon = {c.horizon} >= 1")
    ratio = sc.winch.delay / c.sample_time
    if abs(ratio - round(ratio)) > 1e-9:
        raise CableOCPError(
            f"[winch] delay = {sc.winch.delay} s must be an integer multiple of [controller] "
            f"sample_time = {c.sample_time} s"
        )
    if sc.winch.accel_max is not None and sc.winch.model != "second_order":
        raise CableOCPError("[winch] accel_max needs model = 'second_order'; limit "
                            "command_rate_max (m per sample) for the first-order winch")
    if sc.winch.tension_min is not None and not (sc.unit.mass > 0):
        raise CableOCPError("[winch] tension_min needs [unit] mass > 0 and static_tension")
    if sc.simulation.duration <= sc.simulation.warmup:
        raise CableOCPError(f"[simulation] duration = {sc.simulation.duration} s must exceed "
                            f"warmup = {sc.simulation.warmup} s")


def load_scene(path: str | Path, overrides: dict[str, Any] | None = None) -> HeaveScene:
    """Read and validate a heave TOML file, with optional dotted-key ``overrides``.

    Raises
    ------
    CableOCPError
        When the file cannot be read, is a statics or dynamics scene, or does not validate.
    """
    data = read_problem(path)
    check_kind(data, "heave", path)
    if overrides:
        data = apply_overrides(data, overrides)
    return scene_from_dict(data)
