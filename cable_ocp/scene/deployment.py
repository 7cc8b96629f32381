"""The ``[deployment]`` table of a dynamic scene: an optimal pay-out (or haul-in) schedule.

The problem of :mod:`cable_ocp.schedule` (docs/deployment.md): lower the unit from
``cable.length`` to ``target_length`` (a recovery when the target is shorter) in the least
time, on the scene's axial or planar line with the vessel's motion given, inside the limits
below. A limit left out is not imposed. (A heave scene's ``[deployment]`` table,
:mod:`cable_ocp.scene.heave`, is another problem: the scheduled-gain compensator on a
lowering at a chosen speed.)

Schema (SI units)::

    [deployment]
    target_length = 1050.0       m, unstretched length at the end (required; > 0, not the
                                 start length)
    objective = "time"           "time" (least duration) | "time_energy" (duration plus
                                 energy_weight times the winch's energy, the integral of
                                 |T_top dL/dt|)
    energy_weight = 1e-6         s/J, with "time_energy" (default 0)
    speed_max = 1.0              m/s, |dL/dt| <= speed_max
    accel_max = 0.2              m/s^2, |d^2L/dt^2| <= accel_max (the control's bound)
    power_max = 5e5              W, |T_top dL/dt| <= power_max
    tension_min = 5000.0         N, every constrained tension >= tension_min (> 0 keeps the
                                 line taut with a margin)
    tension_max = 2e5            N, every constrained tension <= tension_max (the MBL over a
                                 safety factor)
    tension_at = "line"          "line": the whole line, every element's tension and both
                                 ends' (the pull on the unit, the top's); or a list of the
                                 named points "unit" and "top" alone
    tension_margin = 0.0         N, >= 0: the OCP keeps its tensions this far inside the
                                 limits (a robust margin for the sea it does not know)
    rest_tolerance = 0.05        m/s, > 0: at the end the winch is stopped and the unit's
                                 speed is below this
    hold = 20.0                  s, 0..600: the OCP goes on this long after the arrival, the
                                 winch stopped, its tensions kept inside the limits (default:
                                 the forward check's 20 s, schedule.forward.CHECK_HOLD, with
                                 the check; none for the OCP alone, solve_schedule; 0: the
                                 OCP ends at the arrival)
    time_step = 0.2              s, the OCP's nominal step (default simulation.time_step):
                                 the steps are duration / steps, the count fixed from the
                                 warm start
    segments = 10                elements of the OCP's line (default simulation.segments)
    check_rounds = 4             int, 0..10: the schedule is re-simulated on the forward
                                 simulator and, while a limit is broken by more than
                                 check_tolerance, re-solved with that limit moved inwards by
                                 the excess seen, at most this often (0: no check)
    check_tolerance = 0.01       -, in (0, 0.5): the relative excess the check accepts
    check_time_step = 0.01       s, the check's step (default simulation.time_step)
    check_segments = 20          the check's elements (default simulation.segments)
    ahc_stroke = 2.0             m: the active heave compensation on top (a compensating
                                 length of gain g in [0, 1] on the measured heave,
                                 |g heave| <= ahc_stroke); off when neither is given
    ahc_speed = 1.0              m/s: |g d(heave)/dt| <= ahc_speed
    replan_interval = 10.0       s, the receding-horizon form: re-planned this often
    preview = 20.0               s, ... with this preview of the vessel's motion
    [deployment.sea]             the vessel's heave as a seeded sea (instead of the scene's
                                 [top_motion] heave; no other motion of the top then)
    significant_height = 2.0     m, H_s of the heave (required)
    peak_frequency = 0.6         rad/s, the spectrum's peak omega_m (required)
    spectrum = "bretschneider"   "bretschneider" | "jonswap" (gamma 3.3)
    seed = 1                     int, the first realisation's seed
    realisations = 1             int, solved together: one schedule for all
    unseen = 20                  int, the realisations of the check (other seeds)
    components = 64              int, harmonics of each realisation
    fade_in = 30.0               s, the heave faded in (quintic) from rest
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.fields import check_keys, choice, integer, number

__all__ = ["DEPLOYMENT_KEYS", "MAX_HOLD", "OBJECTIVES", "SEA_KEYS", "DeploymentProblem",
           "SeaState", "TENSION_POINTS", "parse_deployment"]

DEPLOYMENT_KEYS = {"target_length", "objective", "energy_weight", "speed_max", "accel_max",
                   "power_max", "tension_min", "tension_max", "tension_at",
                   "tension_margin", "rest_tolerance", "hold", "time_step", "segments",
                   "check_rounds", "check_tolerance", "check_time_step", "check_segments",
                   "ahc_stroke", "ahc_speed", "replan_interval", "preview", "sea"}
SEA_KEYS = {"significant_height", "peak_frequency", "spectrum", "seed", "realisations",
            "unseen", "components", "fade_in"}
#: the objectives of ``deployment.objective``
OBJECTIVES = ("time", "time_energy")
#: the named points of ``deployment.tension_at``
TENSION_POINTS = ("unit", "top")
#: s, the longest ``deployment.hold`` (its steps are the OCP's, at ``time_step`` each)
MAX_HOLD = 600.0


@dataclass(frozen=True)
class SeaState:
    """A seeded sea of the vessel's heave (``[deployment.sea]``).

    Attributes
    ----------
    significant_height : float
        H_s of the heave, m.
    peak_frequency : float
        The spectrum's peak, rad/s.
    spectrum : str
        ``"bretschneider"`` or ``"jonswap"``.
    seed : int
        The first design realisation's seed.
    realisations : int
        Design realisations solved together.
    unseen : int
        Realisations of the check (seeds not among the design ones).
    components : int
        Harmonics per realisation.
    fade_in : float
        s, the heave's quintic fade-in from rest.
    """

    significant_height: float
    peak_frequency: float
    spectrum: str = "bretschneider"
    seed: int = 1
    realisations: int = 1
    unseen: int = 20
    components: int = 64
    fade_in: float = 30.0


@dataclass(frozen=True)
class DeploymentProblem:
    """The optimal pay-out problem of a dynamic scene (module docstring; None: not imposed).

    Attributes
    ----------
    target_length : float
        m.
    objective : str
        ``"time"`` or ``"time_energy"``.
    energy_weight : float
        s/J.
    speed_max, accel_max, power_max : float or None
        m/s, m/s^2, W.
    tension_min, tension_max : float or None
        N.
    tension_at : tuple of str
        ``("line",)`` or named points of :data:`TENSION_POINTS`.
    tension_margin : float
        N.
    rest_tolerance : float
        m/s.
    hold : float or None
        s after the arrival that the OCP keeps the limits (None: the caller's default:
        the forward check's hold in :func:`cable_ocp.schedule.planning.verified_schedule`,
        none in ``solve_schedule``).
    time_step : float or None
        s (None: the scene's ``simulation.time_step``).
    segments : int or None
        (None: the scene's ``simulation.segments``).
    check_rounds : int
        Re-solves the forward check may ask for (0: no check).
    check_tolerance : float
        -, relative.
    check_time_step : float or None
        s (None: the scene's ``simulation.time_step``).
    check_segments : int or None
        (None: the scene's ``simulation.segments``).
    ahc_stroke, ahc_speed : float or None
        m, m/s (both None: no compensation).
    replan_interval, preview : float
        s.
    sea : SeaState or None
        The seeded sea (None: the scene's ``[top_motion]``).
    """

    target_length: float
    objective: str = "time"
    energy_weight: float = 0.0
    speed_max: float | None = None
    accel_max: float | None = None
    power_max: float | None = None
    tension_min: float | None = None
    tension_max: float | None = None
    tension_at: tuple[str, ...] = ("line",)
    tension_margin: float = 0.0
    rest_tolerance: float = 0.05
    hold: float | None = None
    time_step: float | None = None
    segments: int | None = None
    check_rounds: int = 4
    check_tolerance: float = 0.01
    check_time_step: float | None = None
    check_segments: int | None = None
    ahc_stroke: float | None = None
    ahc_speed: float | None = None
    replan_interval: float = 10.0
    preview: float = 20.0
    sea: SeaState | None = None

    @property
    def ahc(self) -> bool:
        """True when the heave compensation is on top (a stroke or a speed limit given)."""
        return self.ahc_stroke is not None or self.ahc_speed is not None


def _sea(t: Any) -> SeaState:
    t = check_keys(t, SEA_KEYS, "deployment.sea")
    for key in ("significant_height", "peak_frequency"):
        if key not in t:
            raise CableOCPError(f"deployment.sea.{key} is missing: the sea needs "
                                "significant_height (m) and peak_frequency (rad/s)")
    kw: dict[str, Any] = dict(
        significant_height=number(t["significant_height"], "deployment.sea.significant_height",
                                  nonneg=True, unit="m"),
        peak_frequency=number(t["peak_frequency"], "deployment.sea.peak_frequency",
                              positive=True, unit="rad/s"))
    if "spectrum" in t:
        kw["spectrum"] = choice(t["spectrum"], "deployment.sea.spectrum",
                                ("bretschneider", "jonswap"))
    for key, lo, hi in (("seed", 0, 2**31 - 1), ("realisations", 1, 50), ("unseen", 1, 1000),
                        ("components", 4, 2000)):
        if key in t:
            kw[key] = integer(t[key], f"deployment.sea.{key}", lo, hi)
    if "fade_in" in t:
        kw["fade_in"] = number(t["fade_in"], "deployment.sea.fade_in", nonneg=True, unit="s")
    return SeaState(**kw)


def parse_deployment(t: Any, start_length: float) -> DeploymentProblem:
    """Validate a dynamic scene's ``[deployment]`` table (module docstring).

    Parameters
    ----------
    t : Any
        The table as read from TOML.
    start_length : float
        ``cable.length``, m (the target must differ from it).

    Raises
    ------
    CableOCPError
        An unknown key (the valid ones listed), a missing target or an invalid value (named).
    """
    t = check_keys(t, DEPLOYMENT_KEYS, "deployment")
    if "target_length" not in t:
        raise CableOCPError("deployment.target_length is missing: the unstretched length (m) "
                            "at the end of the pay-out (or haul-in)")
    target = number(t["target_length"], "deployment.target_length", positive=True, unit="m")
    if abs(target - start_length) <= 1e-9 * start_length:
        raise CableOCPError(f"deployment.target_length = {target} m: equals cable.length = "
                            f"{start_length} m; give a longer (pay-out) or shorter (haul-in) "
                            "length")
    kw: dict[str, Any] = {"target_length": target}
    if "objective" in t:
        kw["objective"] = choice(t["objective"], "deployment.objective", OBJECTIVES)
    if "energy_weight" in t:
        kw["energy_weight"] = number(t["energy_weight"], "deployment.energy_weight",
                                     nonneg=True, unit="s/J")
    for key, unit in (("speed_max", "m/s"), ("accel_max", "m/s^2"), ("power_max", "W"),
                      ("tension_max", "N"), ("time_step", "s"), ("ahc_speed", "m/s"),
                      ("ahc_stroke", "m"), ("rest_tolerance", "m/s"),
                      ("replan_interval", "s"), ("preview", "s"), ("check_time_step", "s")):
        if key in t:
            kw[key] = number(t[key], f"deployment.{key}", positive=True, unit=unit)
    for key in ("tension_min", "tension_margin"):
        if key in t:
            kw[key] = number(t[key], f"deployment.{key}", nonneg=True, unit="N")
    if "hold" in t:
        kw["hold"] = number(t["hold"], "deployment.hold", low=0.0, high=MAX_HOLD,
                            unit="s", why="the time after the arrival, the winch stopped, "
                            "that the OCP keeps the limits (0: none)")
    for key, lo_n, hi_n in (("segments", 1, 2000), ("check_segments", 1, 2000),
                            ("check_rounds", 0, 10)):
        if key in t:
            kw[key] = integer(t[key], f"deployment.{key}", lo_n, hi_n)
    if "check_tolerance" in t:
        tol = number(t["check_tolerance"], "deployment.check_tolerance", positive=True,
                     unit="-")
        if not tol < 0.5:
            raise CableOCPError(f"deployment.check_tolerance = {tol}: give a relative excess "
                                "in (0, 0.5), e.g. 0.01")
        kw["check_tolerance"] = tol
    if "tension_at" in t:
        v = t["tension_at"]
        if v == "line":
            kw["tension_at"] = ("line",)
        elif (isinstance(v, list) and v and len(set(v)) == len(v)
              and all(isinstance(s, str) and s in TENSION_POINTS for s in v)):
            kw["tension_at"] = tuple(v)
        else:
            raise CableOCPError(f'deployment.tension_at = {v!r}: valid are "line" or a list '
                                'of distinct names from "unit", "top"')
    lo, hi = kw.get("tension_min"), kw.get("tension_max")
    margin = kw.get("tension_margin", 0.0)
    if lo is not None and hi is not None and hi - margin <= lo + margin:
        raise CableOCPError(f"deployment.tension_max = {hi} N: must exceed tension_min = {lo} N "
                            f"by more than twice tension_margin = {margin} N")
    if kw.get("objective") == "time_energy" and not kw.get("energy_weight"):
        raise CableOCPError('deployment.energy_weight: objective = "time_energy" needs a '
                            "weight > 0 (s/J)")
    if "sea" in t:
        kw["sea"] = _sea(t["sea"])
    return DeploymentProblem(**kw)
