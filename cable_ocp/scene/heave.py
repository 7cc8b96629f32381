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
    drum_radius = 0.5                    # m        (the drive: torque, power; needs tension)
    drum_inertia = 500.0                 # kg m^2   (drum, gear and motor at the drum shaft)
    torque_max = 4.0e4                   # N m      (soft in the MPC; needs drum_radius)
    power_max = 5.0e4                    # W        (the MPC: linearised, a speed limit)

    [unit]
    a = 0.8959                           # s^2 (6.2)
    b = 0.1658                           # s
    model = "linear" | "quadratic"       # simulation plant: (6.2) or (6.3)
    b_quadratic = 0.2                    # s^2/m, (6.3)
    mass = 125000.0                      # kg (with added mass)
    static_tension = 50000.0             # N at the unit
    cable_scene = "../dynamics/x.toml"   # a dynamic scene (path relative to this file): a, b
                                         # are identified from it unless a and b are given

    [passive_compensator]                # an in-line gas-spring cylinder (controllers phc*)
    area = 0.05                          # m^2, piston area
    gas_volume = 0.5                     # m^3, gas volume at the static position
    pressure = 1.0e6                     # Pa at the static position (default: the static
                                         # tension it carries / area: static_tension, or
                                         # the cable's static top tension on plant "cable")
    polytropic_exponent = 1.4            # 1 isothermal, 1.4 adiabatic
    damping = 2.0e4                      # N s/m (> 0: the massless piston's only dynamics)
    stroke_max = 2.0                     # m, the end stops at +-stroke_max from static

    [controller]
    q = 553.6                            # 1/m^2, weight on the unit's heave (default:
                                         # calibrated, 6.3.6's LQR then gives 2.96e-4 m)
    r = 1.0                              # 1/m^2, weight on the command
    horizon = 50
    sample_time = 0.05                   # s
    solver = "daqp" | "qpoases" | "osqp" | "qrqp" | "ipopt"
    preview_time = 0.0                   # s
    measurement_noise = 0.01             # m, std of the sampled unit-depth sensor
    winch_noise = 0.001                  # m, std of the winch-position sensor (cable plant)
    boom_tip_noise = 0.05                # m, std of the motion sensor's boom-tip heave
    depth_bias_time = 60.0               # s, estimator time constant of a depth offset
    controllers = ["passive", "lqr", "lqg", "mpc"]   # and "phc", "phc+lqr", "phc+lqg",
                                                     # "phc+mpc" (passive compensator)
                                                     # "printed-g3", "printed-g5" (the
                                                     # thesis' gains G3, G5 of 6.2.6)

    [simulation]
    duration = 300.0                     # s
    seed = 1
    substeps = 5                         # plant integration steps per control sample
    warmup = 30.0                        # s discarded from the metrics
    plant = "model" | "cable"            # the design model (6.2)/(6.3), or the cable scene

    [identification]                     # the experiment of Huang (1992), 6.2.3, on the cable
    excitation = "multisine" | "chirp" | "step" | "sea"
    duration = 180.0                     # s
    amplitude = 0.28                     # m RMS of the boom-tip motion (default: the sea's)
    band = [0.39, 2.4]                   # rad/s (multisine, chirp; default from the sea)
    noise = 0.01                         # m, depth-sensor noise (default measurement_noise)
    seed = 7

    [deployment]                         # lowering through resonance (cable plant)
    final_length = 600.0                 # m (from the cable scene's length)
    payout_speed = 0.5                   # m/s
    schedule_lengths = [100.0, 200.0]    # m, where a, b and the LQR gain are tabulated
    fixed_length = 100.0                 # m, the length of the fixed-gain design
    window = 10.0                        # m of length per row of the result table
    ramp_time = 20.0                     # s, smooth start of the pay-out
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.gas_spring import gas_stiffness
from cable_ocp.scene.fields import check_keys, choice, integer, number
from cable_ocp.scene.files import apply_overrides, check_kind, read_problem
from cable_ocp.scene.parts import parse_meta

#: the parameters of a cable scene's line and unit that the inverse problem of Huang (1992)
#: 6.4 (2) can solve for (:mod:`cable_ocp.heave.inverse`; here so that the command line
#: names them without importing the heave package)
INVERSE_UNKNOWNS = ("length", "axial_stiffness", "mass_per_length", "unit_mass",
                    "added_mass", "unit_drag", "tangential_drag", "diameter", "axial_damping")

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
    """``[vessel]`` (Huang 1992, eq. (6.25))."""

    model: str = "second_order"
    natural_frequency: float = 0.393
    damping_ratio: float = 0.6
    gain: float = 0.5


@dataclass(frozen=True)
class WinchSpec:
    """``[winch]`` (Huang 1992, eqs. (6.1), (6.12)) and its limits."""

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
    drum_radius: float | None = None
    drum_inertia: float = 0.0
    torque_max: float | None = None
    power_max: float | None = None


@dataclass(frozen=True)
class PassiveCompensatorSpec:
    """``[passive_compensator]``: an in-line gas-spring cylinder between the boom tip and the
    line (:mod:`cable_ocp.physics.gas_spring`); ``pressure`` None: the static tension it
    carries over ``area`` (:func:`compensator_pressure`)."""

    area: float = 0.05
    gas_volume: float = 0.5
    pressure: float | None = None
    polytropic_exponent: float = 1.4
    damping: float = 2.0e4
    stroke_max: float = 2.0


@dataclass(frozen=True)
class UnitSpec:
    """``[unit]`` (Huang 1992, eqs. (6.2), (6.3))."""

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

    q: float = 553.6  # 1/m^2; a calibration: 6.3.6's LQR gives the thesis' 2.96e-4 m
    r: float = 1.0
    horizon: int = 50
    sample_time: float = 0.05
    solver: str = "daqp"
    terminal: str = "dare"
    preview_time: float = 0.0
    measurement_noise: float = 0.01
    winch_noise: float = 0.001
    boom_tip_noise: float = 0.05
    depth_bias_time: float = 60.0
    tension_penalty: float = 1e6
    controllers: tuple = ("passive", "lqr", "lqg", "mpc")


@dataclass(frozen=True)
class SimulationSpec:
    """``[simulation]``."""

    duration: float = 300.0
    seed: int = 1
    substeps: int = 5
    warmup: float = 30.0
    plant: str = "model"


@dataclass(frozen=True)
class IdentificationSpec:
    """``[identification]``: the identification experiment on the cable scene (Huang (1992),
    section 6.2.3).

    ``None`` values take defaults from the rest of the scene (see
    :mod:`cable_ocp.heave.identify_cable`).
    """

    excitation: str = "multisine"
    duration: float = 180.0
    amplitude: float | None = None
    band: tuple | None = None
    noise: float | None = None
    seed: int = 7


@dataclass(frozen=True)
class DeploymentSpec:
    """``[deployment]``: lowering the unit with the compensator on (cable plant)."""

    final_length: float | None = None
    payout_speed: float = 0.5
    schedule_lengths: tuple | None = None
    fixed_length: float | None = None
    window: float | None = None
    ramp_time: float = 20.0


@dataclass(frozen=True)
class HeaveScene:
    """A complete heave scene."""

    sea: SeaSpec = field(default_factory=SeaSpec)
    vessel: VesselSpec = field(default_factory=VesselSpec)
    winch: WinchSpec = field(default_factory=WinchSpec)
    unit: UnitSpec = field(default_factory=UnitSpec)
    controller: ControllerSpec = field(default_factory=ControllerSpec)
    simulation: SimulationSpec = field(default_factory=SimulationSpec)
    identification: IdentificationSpec = field(default_factory=IdentificationSpec)
    deployment: DeploymentSpec | None = None
    passive_compensator: PassiveCompensatorSpec | None = None
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
    ("simulation", "plant"): ("model", "cable"),
    ("identification", "excitation"): ("multisine", "chirp", "step", "sea"),
}
_CONTROLLERS = ("passive", "lqr", "lqg", "mpc", "phc", "phc+lqr", "phc+lqg", "phc+mpc")
#: the thesis' printed gains as controllers (Huang 1992, 6.2.4-6.2.6) -> the delay, s, of the
#: plant each was designed for (G3: none, (6.6); G5: the 0.2 s of Fig. 6.17, (6.14));
#: :mod:`cable_ocp.heave.printed` runs them on that delay
PRINTED_CONTROLLERS = {"printed-g3": 0.0, "printed-g5": 0.2}
_CONTROLLERS += tuple(PRINTED_CONTROLLERS)


@dataclass(frozen=True)
class _Num:
    """A number in a range: ``low``/``high`` inclusive, ``positive`` = > 0; ``why`` says
    where the bound comes from."""

    unit: str
    low: float | None = None
    high: float | None = None
    positive: bool = False
    why: str = ""


@dataclass(frozen=True)
class _Int:
    """An integer in ``[low, high]``."""

    low: int
    high: int
    why: str = ""


_WAVES = ("ocean wind seas and swell have peak periods of about 3-25 s; the bounds add "
          "model-basin waves and the longest swell")
_SHIP = "ship heave natural periods are 5-25 s (0.25-1.3 rad/s)"
_RATIO = ("below 0.01 a resonance amplifies by more than 50x; above 10 the two poles are more "
          "than 400x apart and the block is a first-order lag")

#: Every numeric key of a heave scene: its range, unit and the reason for the bounds.
#: Optional keys (None = not given) are only checked when given.
RULES: dict[tuple[str, str], _Num | _Int] = {
    ("sea", "significant_wave_height"): _Num(
        "m", low=1e-3, high=30.0,
        why="the largest significant wave heights measured are about 20 m; below 1 mm "
            "there is no sea to compensate"),
    ("sea", "modal_frequency"): _Num("rad/s", low=0.15, high=16.0, why=_WAVES),
    ("sea", "zero_crossing_period"): _Num("s", low=0.3, high=28.0, why=_WAVES),
    ("sea", "peak_period"): _Num("s", low=0.4, high=40.0, why=_WAVES),
    ("sea", "peak_enhancement"): _Num(
        "-", low=1.0, high=10.0,
        why="JONSWAP gamma: 1 is Pierson-Moskowitz, 3.3 the JONSWAP mean, up to ~7 in "
            "fetch-limited seas"),
    ("sea", "filter_order"): _Int(2, 6, why="second-order sections of the least-squares fit"),
    ("vessel", "natural_frequency"): _Num("rad/s", low=0.05, high=10.0, why=_SHIP),
    ("vessel", "damping_ratio"): _Num("-", low=0.01, high=10.0, why=_RATIO),
    ("vessel", "gain"): _Num("-", positive=True, high=10.0,
                             why="the boom tip moves gain x the vessel's heave response "
                                 "(0.5 in Huang 1992, 6.3.6)"),
    ("winch", "gain"): _Num("1/s", low=0.01, high=1000.0,
                            why="winch bandwidths are 0.1-20 1/s (1 in Huang 1992, 6.3.6)"),
    ("winch", "natural_frequency"): _Num("rad/s", low=0.01, high=1000.0,
                                         why="winch bandwidths are 0.1-20 rad/s"),
    ("winch", "damping_ratio"): _Num("-", low=0.01, high=10.0, why=_RATIO),
    ("winch", "delay"): _Num("s", low=0.0, high=60.0,
                             why="command delays are tenths of a second (0.2 s in Huang "
                                 "1992, Fig. 6.17); 60 s is longer than any wave period"),
    ("winch", "stroke_max"): _Num("m", positive=True, high=1000.0,
                                  why="heave-compensator strokes are a few metres"),
    ("winch", "speed_max"): _Num("m/s", positive=True, high=100.0,
                                 why="winch line speeds are 1-3 m/s"),
    ("winch", "command_rate_max"): _Num("m per sample", positive=True, high=100.0,
                                        why="0.1 m per 0.05 s sample is a fast winch"),
    ("winch", "accel_max"): _Num("m/s^2", positive=True, high=1000.0,
                                 why="winch accelerations are a few m/s^2"),
    ("winch", "tension_min"): _Num("N", low=0.0, high=1e10,
                                   why="above any cable's breaking load"),
    ("winch", "drum_radius"): _Num("m", positive=True, high=100.0,
                                   why="winch drums have radii of 0.2-3 m"),
    ("winch", "drum_inertia"): _Num("kg m^2", low=0.0, high=1e9,
                                    why="drum, gear and motor referred to the drum shaft"),
    ("winch", "torque_max"): _Num("N m", positive=True, high=1e10,
                                  why="above any winch motor's torque"),
    ("winch", "power_max"): _Num("W", positive=True, high=1e10,
                                 why="above any winch drive's power (tens of MW)"),
    ("unit", "a"): _Num("s^2", low=1e-3, high=1e4,
                        why="the unit's natural period 2 pi sqrt(a) from 0.2 s to 10 min"),
    ("unit", "b"): _Num("s", positive=True, high=1e4,
                        why="damping time b/a of the unit; b = 0.1658 s in Huang 1992, 6.3.6"),
    ("unit", "b_quadratic"): _Num("s^2/m", low=0.0, high=1e4,
                                  why="0.07-0.42 s^2/m in Huang 1992, 6.2.6 and 6.3.6"),
    ("unit", "mass"): _Num("kg", low=0.0, high=1e8,
                           why="more than any crane vessel lifts (~2e7 kg)"),
    ("unit", "static_tension"): _Num("N", low=0.0, high=1e10,
                                     why="above any cable's breaking load"),
    ("controller", "q"): _Num("1/m^2", low=0.0, high=1e10,
                              why="q/r up to 1e10 keeps the Riccati equation well posed"),
    ("controller", "r"): _Num("1/m^2", low=1e-10, high=1e10,
                              why="q/r up to 1e10 keeps the Riccati equation well posed"),
    ("controller", "horizon"): _Int(1, 100000, why="samples; see the cost limits"),
    ("controller", "sample_time"): _Num("s", low=1e-3, high=10.0,
                                        why="a control sample of 1 ms to 10 s"),
    ("controller", "preview_time"): _Num("s", low=0.0, high=600.0,
                                         why="wave forecasts reach tens of seconds"),
    ("controller", "measurement_noise"): _Num(
        "m", low=1e-6, high=10.0,
        why="a noise-free sensor makes the Kalman filter singular; depth sensors give "
            "~1 cm"),
    ("controller", "tension_penalty"): _Num("1/m^2", low=1e-6, high=1e12,
                                            why="the soft tension limit's weight"),
    ("simulation", "duration"): _Num("s", positive=True, high=1e6,
                                     why="about 12 days; see the cost limits"),
    ("simulation", "seed"): _Int(0, 2**32 - 1, why="a 32-bit seed"),
    ("simulation", "substeps"): _Int(1, 100000, why="plant steps per control sample"),
    ("simulation", "warmup"): _Num("s", low=0.0, high=1e6, why="less than the duration"),
    ("controller", "winch_noise"): _Num(
        "m", low=1e-9, high=10.0,
        why="the winch-position sensor (an encoder) of the cable plant's estimator; "
            "a noise-free sensor makes the Kalman filter singular"),
    ("controller", "boom_tip_noise"): _Num(
        "m", low=1e-6, high=10.0,
        why="the vessel motion sensor's boom-tip heave; '5 cm or 5 %' is a common spec"),
    ("controller", "depth_bias_time"): _Num(
        "s", low=0.0, high=1e6, why="the estimator's depth-offset state (0: none)"),
    ("identification", "duration"): _Num(
        "s", low=1.0, high=1e5, why="an identification record of seconds to hours"),
    ("identification", "amplitude"): _Num(
        "m", positive=True, high=100.0, why="RMS of the prescribed boom-tip motion"),
    ("identification", "noise"): _Num(
        "m", low=0.0, high=10.0, why="the depth sensor's noise in the experiment (0: none)"),
    ("identification", "seed"): _Int(0, 2**32 - 1, why="a 32-bit seed"),
}

#: ``[deployment]`` keys, checked only when the table is given.
DEPLOYMENT_RULES: dict[str, _Num] = {
    "final_length": _Num("m", positive=True, high=1e5, why="the unstretched length at the end"),
    "payout_speed": _Num("m/s", positive=True, high=10.0,
                         why="crane and winch pay-out speeds are up to a few m/s"),
    "fixed_length": _Num("m", positive=True, high=1e5, why="the fixed-gain design's length"),
    "window": _Num("m", positive=True, high=1e5, why="length per row of the result table"),
    "ramp_time": _Num("s", low=0.0, high=1e4, why="the pay-out's smooth start and stop"),
}


#: ``[passive_compensator]`` keys, checked only when the table is given.
COMPENSATOR_RULES: dict[str, _Num] = {
    "area": _Num("m^2", positive=True, high=100.0, why="piston areas of 0.01-1 m^2"),
    "gas_volume": _Num("m^3", positive=True, high=1e4,
                       why="the cylinder's and accumulators' gas volume"),
    "pressure": _Num("Pa", positive=True, high=1e9, why="gas pressures up to ~40 MPa"),
    "polytropic_exponent": _Num("-", low=1.0, high=1.67,
                                why="1 isothermal to 5/3 adiabatic monatomic gas"),
    "damping": _Num("N s/m", positive=True, high=1e10,
                    why="the massless piston's stroke moves at the rate force / damping"),
    "stroke_max": _Num("m", positive=True, high=100.0,
                       why="compensator strokes are a few metres"),
}

#: the relative mismatch of ``pressure * area`` and the static tension allowed
COMPENSATOR_BALANCE = 0.01


def _key(table: str, key: str) -> str:
    return f"{table}.{key}"


def _value(table: str, key: str, val: Any) -> Any:
    """One value of ``[table]``, checked (type, range, choice) and converted."""
    name = _key(table, key)
    if (table, key) in _CHOICES:
        return choice(val, name, _CHOICES[(table, key)])
    if key == "controllers":
        if (not isinstance(val, list) or not val
                or any(not isinstance(v, str) or v not in _CONTROLLERS for v in val)
                or len(set(val)) != len(val)):
            raise CableOCPError(f"{name} = {val!r}: give a list of distinct names from "
                                + ", ".join(f'"{c}"' for c in _CONTROLLERS))
        return tuple(val)
    if key == "cable_scene":
        if not isinstance(val, str):
            raise CableOCPError(f"{name} = {val!r}: expected a file path (string)")
        return val
    if key in ("band", "schedule_lengths"):
        return _number_list(name, val, 2 if key == "band" else None)
    if table == "deployment":
        return _checked(DEPLOYMENT_RULES[key], val, name)
    if table == "passive_compensator":
        return _checked(COMPENSATOR_RULES[key], val, name)
    return _checked(RULES[(table, key)], val, name)


def _number_list(name: str, val: Any, size: int | None) -> tuple:
    """A list of positive finite numbers, strictly increasing (``size`` entries if given)."""
    what = f"a list of {size} numbers" if size else "a list of numbers"
    if (not isinstance(val, list) or not val or (size is not None and len(val) != size)
            or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in val)):
        raise CableOCPError(f"{name} = {val!r}: expected {what}")
    out = tuple(float(v) for v in val)
    if not all(math.isfinite(v) and v > 0 for v in out) or any(
            b <= a for a, b in zip(out[:-1], out[1:], strict=True)):
        raise CableOCPError(f"{name} = {val!r}: must be finite, > 0 and increasing")
    return out


def _checked(rule: _Num | _Int, val: Any, name: str) -> Any:
    if isinstance(rule, _Int):
        return integer(val, name, rule.low, rule.high, rule.why)
    nonneg = rule.low == 0.0  # "must be >= 0 (unit)" for a negative value
    return number(val, name, positive=rule.positive, nonneg=nonneg,
                  low=None if nonneg else rule.low, high=rule.high, unit=rule.unit,
                  why=rule.why)


def _build(cls: type, table: str, data: Any) -> Any:
    known = {f.name for f in fields(cls)}
    data = check_keys(data, known, table)
    return cls(**{key: _value(table, key, val) for key, val in data.items()})


_TABLES = {"sea": SeaSpec, "vessel": VesselSpec, "winch": WinchSpec, "unit": UnitSpec,
           "controller": ControllerSpec, "simulation": SimulationSpec,
           "identification": IdentificationSpec, "deployment": DeploymentSpec,
           "passive_compensator": PassiveCompensatorSpec}


def scene_from_dict(data: dict[str, Any], base_dir: str | Path | None = None) -> HeaveScene:
    """Validate a parsed TOML document and return the scene.

    ``base_dir`` is the directory that a relative ``[unit] cable_scene`` is read from (the
    heave file's; default the working directory); the scene keeps the resolved path.

    Parameters
    ----------
    data : dict
        The heave problem as read from TOML (tables ``meta``, ``sea``, ``vessel``,
        ``winch``, ``unit``, ``controller``, ``simulation``, ``identification``,
        ``deployment``), SI units; not modified.
    base_dir : str or Path, optional
        Directory a relative ``[unit] cable_scene`` path is taken from; None (default): the
        working directory.

    Raises
    ------
    CableOCPError
        On unknown tables or keys, wrong types, out-of-range values (:data:`RULES`),
        invalid choices or inconsistent values; the message names the key.
    """
    if not isinstance(data, dict):
        raise CableOCPError("a heave scene must be a table")
    data = resolve_cable_scene(data, base_dir)
    kwargs: dict[str, Any] = {"raw": copy.deepcopy(data)}
    for key, val in data.items():
        if key in _TABLES:
            kwargs[key] = _build(_TABLES[key], key, val)
        elif key == "meta":
            kwargs["meta"] = parse_meta(val)
        elif key in ("title", "source"):
            raise CableOCPError(f"{key} = ...: put it in the [meta] table ([meta] {key} = "
                                "\"...\"), as in every scene kind")
        else:
            raise CableOCPError(
                f"unknown top-level table [{key}]; valid: meta, {', '.join(_TABLES)}"
            )
    scene = HeaveScene(**kwargs)
    check(scene)
    return scene


def resolve_cable_scene(data: dict[str, Any], base_dir: str | Path | None) -> dict[str, Any]:
    """``[unit] cable_scene`` made absolute (relative to ``base_dir``, else the working
    directory), so that the scene and its overrides keep pointing at the same file.

    Parameters
    ----------
    data : dict
        The heave problem as read from TOML. Returned as is when it has no string
        ``[unit] cable_scene``, else a deep copy with that path resolved.
    base_dir : str or Path or None
        Directory a relative path is taken from; None: the working directory.
    """
    unit = data.get("unit")
    if not isinstance(unit, dict) or not isinstance(unit.get("cable_scene"), str):
        return data
    path = Path(unit["cable_scene"]).expanduser()
    if not path.is_absolute():
        path = Path(base_dir or ".") / path
    data = copy.deepcopy(data)
    data["unit"]["cable_scene"] = str(path.resolve())
    return data


def load_cable_scene(scene: HeaveScene) -> Any:
    """The dynamic scene of ``[unit] cable_scene`` (a :class:`~cable_ocp.dynamics.DynamicScene`).

    Raises
    ------
    CableOCPError
        Naming the key when the file is missing, not a dynamic scene, or invalid.
    """
    from cable_ocp.scene.dynamics import load_dynamic_scene

    path = scene.unit.cable_scene
    if path is None:
        raise CableOCPError("unit.cable_scene: is not given")
    try:
        return load_dynamic_scene(path)
    except CableOCPError as exc:
        raise CableOCPError(f"unit.cable_scene = {path!r}: {exc}") from None


def _rk4_gain(z: complex) -> float:
    """|R(z)| of the classical RK4 step, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24."""
    return abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)


#: |lambda| h_sim allowed for the RK4 plant integration: within it the step's amplification
#: is within 2 % of exp(lambda h_sim) (1.9 % at lambda h_sim = -1), and far inside RK4's
#: stability limit (2.79 on the negative real axis)
RK4_MAX_STEP = 1.0


def _check_integration(sc: HeaveScene) -> None:
    """The unit and winch are integrated with RK4 at ``h_sim = sample_time / substeps``:
    refuse a step too long for their fastest linear mode (``|lambda| h_sim > 1``)."""
    h = sc.controller.sample_time / sc.simulation.substeps
    a, b = sc.unit.a, sc.unit.b
    modes = [(complex(v), "unit.a and unit.b")
             for v in np.roots([a, b, 1.0])]  # a x'' + b x' + x = ...
    w = sc.winch
    if w.model == "first_order":
        modes.append((complex(-w.gain), "winch.gain"))
    else:
        modes += [(complex(v), "winch.natural_frequency")
                  for v in np.roots([1.0, 2 * w.damping_ratio * w.natural_frequency,
                                     w.natural_frequency**2])]
    pc = sc.passive_compensator
    if pc is not None and sc.unit.mass > 0:
        # the unit on the line in series with the compensator (its stiffest point: the end
        # stop in compression): (a s^2 + b s)(c s + k_p + k_c) + c s + k_p = 0
        k_p = gas_stiffness(pc.stroke_max, compensator_pressure(sc), pc.gas_volume, pc.area,
                            pc.polytropic_exponent)
        k_c, c = sc.unit.mass / a, pc.damping
        modes += [(complex(v), "passive_compensator.damping")
                  for v in np.roots([a * c, a * (k_p + k_c) + b * c, b * (k_p + k_c) + c, k_p])]
    lam, key = max(modes, key=lambda m: abs(m[0]))
    if abs(lam) * h > RK4_MAX_STEP:
        need = int(math.ceil(abs(lam) * sc.controller.sample_time / RK4_MAX_STEP))
        raise CableOCPError(
            f"simulation.substeps = {sc.simulation.substeps}: the plant step sample_time / "
            f"substeps = {h:.3g} s is too long for the fastest mode of the unit and winch "
            f"({abs(lam):.4g} 1/s, from {key}): RK4 needs |lambda| h <= {RK4_MAX_STEP:g} to "
            f"be stable and accurate (|R| = {_rk4_gain(lam * h):.3g} per step now); give "
            f"simulation.substeps >= {need}")


def check(scene: HeaveScene) -> None:
    """Validate a scene built in Python (``scene_from_dict`` calls it on every file).

    Raises
    ------
    CableOCPError
        Naming the offending key: a value out of its range (:data:`RULES`, with the reason),
        a missing or ambiguous sea frequency, a delay that is not a whole number of samples,
        a plant step too long for RK4, or inconsistent options.
    """
    for (table, key), rule in RULES.items():
        val = getattr(getattr(scene, table), key)
        if val is not None:
            _checked(rule, val, _key(table, key))
    if scene.deployment is not None:
        for key, rule in DEPLOYMENT_RULES.items():
            val = getattr(scene.deployment, key)
            if val is not None:
                _checked(rule, val, _key("deployment", key))
    if scene.passive_compensator is not None:
        for key, rule in COMPENSATOR_RULES.items():
            val = getattr(scene.passive_compensator, key)
            if val is not None:
                _checked(rule, val, _key("passive_compensator", key))
    for (table, key), options in _CHOICES.items():
        choice(getattr(getattr(scene, table), key), _key(table, key), options)
    s = scene.sea
    given = [k for k in ("modal_frequency", "zero_crossing_period", "peak_period")
             if getattr(s, k) is not None]
    if len(given) != 1:
        raise CableOCPError(
            "sea: give exactly one of modal_frequency (rad/s), zero_crossing_period (s), "
            f"peak_period (s); got {', '.join(given) if given else 'none'}"
        )
    _check_cable(scene)
    if scene.unit.model == "quadratic" and not scene.unit.b_quadratic > 0:
        raise CableOCPError(f'unit.b_quadratic = {scene.unit.b_quadratic!r}: must be > 0 with '
                            'unit.model = "quadratic" (s^2/m, Huang 1992, eq. (6.3))')
    c = scene.controller
    ratio = scene.winch.delay / c.sample_time
    if abs(ratio - round(ratio)) > 1e-9:
        raise CableOCPError(
            f"winch.delay = {scene.winch.delay!r}: must be an integer multiple of "
            f"controller.sample_time = {c.sample_time} s (exact shift register)"
        )
    if scene.winch.accel_max is not None and scene.winch.model != "second_order":
        raise CableOCPError('winch.accel_max: needs winch.model = "second_order"; limit '
                            "winch.command_rate_max (m per sample) for the first-order winch")
    if (scene.winch.tension_min is not None and not (scene.unit.mass > 0)
            and scene.unit.cable_scene is None):
        raise CableOCPError("winch.tension_min: needs unit.mass > 0 (kg) and "
                            "unit.static_tension (N)")
    if scene.simulation.warmup >= scene.simulation.duration:
        raise CableOCPError(f"simulation.warmup = {scene.simulation.warmup!r}: must be less than "
                            f"simulation.duration = {scene.simulation.duration} s")
    _check_drive(scene)
    _check_compensator(scene)
    _check_printed(scene)
    _check_integration(scene)


def _has_tension(sc: HeaveScene) -> bool:
    """The plant carries a tension: ``[unit] mass`` and ``static_tension``, or a cable."""
    return (sc.unit.mass > 0 and sc.unit.static_tension > 0) or sc.unit.cable_scene is not None


def _check_drive(sc: HeaveScene) -> None:
    """The winch drive's keys: ``drum_radius`` needs a tension, the limits need the radius."""
    w = sc.winch
    for key in ("torque_max", "power_max"):
        if getattr(w, key) is not None and w.drum_radius is None:
            raise CableOCPError(f"winch.{key}: needs winch.drum_radius (m), the drum the "
                                "torque acts on")
    if w.drum_radius is not None and not _has_tension(sc):
        raise CableOCPError("winch.drum_radius: the torque R T needs the line tension: give "
                            "unit.mass > 0 (kg) and unit.static_tension > 0 (N), or "
                            "unit.cable_scene")


def compensator_pressure(sc: HeaveScene) -> float:
    """The compensator's static gas pressure, Pa: ``[passive_compensator] pressure``, else
    ``unit.static_tension / area``.

    Parameters
    ----------
    sc : HeaveScene
        A scene with ``[passive_compensator]``.
    """
    pc = sc.passive_compensator
    return pc.pressure if pc.pressure is not None else sc.unit.static_tension / pc.area


def _check_compensator(sc: HeaveScene) -> None:
    """Controllers ``phc*`` need ``[passive_compensator]``; it needs the unit's mass and
    static tension (the cable's stiffness ``m / a`` and the load it carries; on a cable
    scene they may come from it, and the load is then checked when the comparison runs,
    :func:`check_compensator_load`), a pressure that carries that load and a gas volume the
    stroke cannot exhaust."""
    pc = sc.passive_compensator
    phc = [c for c in sc.controller.controllers if c.startswith("phc")]
    if pc is None:
        if phc:
            raise CableOCPError(f"controller.controllers = {list(sc.controller.controllers)}: "
                                f"{', '.join(phc)} need a [passive_compensator] table (area, "
                                "gas_volume, damping, stroke_max, ...)")
        return
    on_cable = sc.unit.cable_scene is not None
    if not (sc.unit.mass > 0 and sc.unit.static_tension > 0):
        if not on_cable:
            raise CableOCPError("[passive_compensator]: needs unit.mass > 0 (kg; the line's "
                                "stiffness is mass / a) and unit.static_tension > 0 (N; the "
                                "load the gas carries)")
    elif not (on_cable and sc.simulation.plant == "cable"):
        check_compensator_load(sc, sc.unit.static_tension, "unit.static_tension")
    if not pc.area * pc.stroke_max < 0.9 * pc.gas_volume:
        raise CableOCPError(
            f"passive_compensator.stroke_max = {pc.stroke_max:g} m: area x stroke = "
            f"{pc.area * pc.stroke_max:g} m^3 must be < 0.9 gas_volume = "
            f"{0.9 * pc.gas_volume:g} m^3 (the gas cannot be compressed to nothing)")


def check_compensator_load(sc: HeaveScene, load: float, what: str) -> None:
    """Refuse a ``[passive_compensator] pressure`` whose gas force differs from the static
    ``load`` it carries by more than :data:`COMPENSATOR_BALANCE`.

    Parameters
    ----------
    sc : HeaveScene
        A scene with ``[passive_compensator]``.
    load : float
        The static tension the cylinder carries, N.
    what : str
        What ``load`` is, for the message (``"unit.static_tension"``, ...).
    """
    pc = sc.passive_compensator
    p0 = pc.pressure if pc.pressure is not None else load / pc.area
    force = p0 * pc.area
    if abs(force - load) > COMPENSATOR_BALANCE * load:
        raise CableOCPError(
            f"passive_compensator.pressure = {p0:g} Pa: with area = {pc.area:g} m^2 the gas "
            f"carries {force:.6g} N, not {what} = {load:g} N (more than "
            f"{100 * COMPENSATOR_BALANCE:g} % off); give pressure = {load / pc.area:.6g} Pa "
            "or leave it out")


def _check_printed(sc: HeaveScene) -> None:
    """Controllers ``printed-g3``, ``printed-g5`` (the thesis' gains on ``[x, x', u]`` of
    (6.6)): a first-order winch, the design model as the plant, and a design delay that is a
    whole number of samples."""
    names = [c for c in sc.controller.controllers if c in PRINTED_CONTROLLERS]
    if not names:
        return
    ctrl = f"controller.controllers = {list(sc.controller.controllers)}"
    if sc.winch.model != "first_order":
        raise CableOCPError(f'{ctrl} with winch.model = "{sc.winch.model}": the printed gains '
                            f"({', '.join(names)}) act on [x, x', u] of the first-order winch "
                            '(6.5), (6.6); give winch.model = "first_order"')
    if sc.simulation.plant == "cable":
        raise CableOCPError(f'{ctrl} with simulation.plant = "cable": the printed gains '
                            f"({', '.join(names)}) run on the design model only; give "
                            'simulation.plant = "model"')
    h = sc.controller.sample_time
    for name in names:
        ratio = PRINTED_CONTROLLERS[name] / h
        if abs(ratio - round(ratio)) > 1e-9:
            raise CableOCPError(f"{ctrl}: {name} runs on a {PRINTED_CONTROLLERS[name]:g} s "
                                f"winch delay, not a whole number of controller.sample_time "
                                f"= {h:g} s; give a sample time that divides it (e.g. 0.01)")


def _check_cable(sc: HeaveScene) -> None:
    """The cable-scene keys: ``[unit] cable_scene`` readable and an axial, planar or
    lumped3d line with a unit, ``[simulation] plant = "cable"`` and ``[deployment]`` only
    with a cable scene (an axial or lumped3d one)."""
    if sc.unit.cable_scene is None:
        if sc.simulation.plant == "cable":
            raise CableOCPError('simulation.plant = "cable": needs unit.cable_scene = "PATH" '
                                "(a dynamic scene, relative to the heave file)")
        if sc.deployment is not None:
            raise CableOCPError('[deployment]: needs unit.cable_scene = "PATH" (the line '
                                "that is lowered, a dynamic scene)")
        return
    dyn = load_cable_scene(sc)
    model = dyn.simulation.model
    if model not in ("axial", "planar", "lumped3d"):
        raise CableOCPError(
            f"unit.cable_scene = {sc.unit.cable_scene!r}: its simulation.model = {model!r}; "
            'the heave plant and the identification take model = "axial" (a vertical line), '
            '"planar" (a line in the x-z plane, in a current along x) or "lumped3d" (a line '
            "in 3D, in any current)")
    if model == "planar" and sc.deployment is not None:
        raise CableOCPError(
            f"[deployment] with unit.cable_scene = {sc.unit.cable_scene!r}: its "
            'simulation.model = "planar"; a deployment (a changing length, a schedule over '
            'lengths) needs model = "axial" or "lumped3d"')
    if model != "axial" and dyn.unit is None:
        raise CableOCPError(f"unit.cable_scene = {sc.unit.cable_scene!r}: needs a [unit] at "
                            "end_a (the unit the winch lifts), not an anchor")
    h = sc.controller.sample_time
    ratio = h / dyn.simulation.time_step
    if abs(ratio - round(ratio)) > 1e-9 * max(1.0, ratio) or round(ratio) < 1:
        raise CableOCPError(
            f"unit.cable_scene: its simulation.time_step = {dyn.simulation.time_step} s "
            f"must divide controller.sample_time = {h} s (the cable is stepped per sample)")
    band = sc.identification.band
    if band is not None and not band[0] < band[1]:
        raise CableOCPError(f"identification.band = {list(band)}: must be [low, high] rad/s "
                            "with low < high")
    dep = sc.deployment
    if dep is not None:
        if dep.final_length is None:
            raise CableOCPError("deployment.final_length: is required (m)")
        if dep.final_length == dyn.length:
            raise CableOCPError(f"deployment.final_length = {dep.final_length}: equals the "
                                "cable scene's length (m): nothing is paid out")
        lo, hi = sorted((dyn.length, dep.final_length))
        for key in ("schedule_lengths", "fixed_length"):
            val = getattr(dep, key)
            vals = () if val is None else (val if isinstance(val, tuple) else (val,))
            if any(v < lo - 1e-9 or v > hi + 1e-9 for v in vals):
                raise CableOCPError(f"deployment.{key} = {val}: must lie between the cable "
                                    f"scene's length {dyn.length} m and deployment."
                                    f"final_length {dep.final_length} m")


def load_scene(path: str | Path, overrides: dict[str, Any] | None = None) -> HeaveScene:
    """Read and validate a heave TOML file, with optional dotted-key ``overrides``.

    Parameters
    ----------
    path : str or Path
        The heave problem file (UTF-8 TOML, SI units); a relative ``[unit] cable_scene`` in
        it is read from this file's directory.
    overrides : dict, optional
        Dotted key -> value (as ``--set`` gives them, e.g. ``{"winch.delay": 0.2}``),
        applied before validation; None (default): none.

    Raises
    ------
    CableOCPError
        When the file cannot be read, is a statics or dynamics scene, or does not validate.
    """
    data = read_problem(path)
    check_kind(data, "heave", path)
    if overrides:
        data = apply_overrides(data, overrides)
    return scene_from_dict(data, Path(path).parent)
