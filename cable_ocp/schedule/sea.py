"""The vessel's heave for the pay-out schedule: the scene's own motion or seeded seas.

A :class:`VesselMotion` is the vertical offset z(t) (m, positive up) of the top (end_b)
from ``end_b.position``, written once as a CasADi function of a symbolic time
(:meth:`VesselMotion.casadi_heave`, for the NLP in which t depends on the decisions; the
scene's own heave through :func:`cable_ocp.scene.motion.top_offset_expr`), evaluated on
numpy times (:meth:`VesselMotion.heave`, its exact rate by AD :meth:`VesselMotion.heave_rate`)
and as rows of ``top_motion.series`` for the forward simulator
(:meth:`VesselMotion.series_rows`).

A seeded sea (``[deployment.sea]``, :class:`cable_ocp.scene.deployment.SeaState`) is the
random-phase sum (the standard spectral representation, e.g. Faltinsen (1990), "Sea
loads on ships and offshore structures", eq. (2.67))

    z(t) = f(t) sum_i sqrt(2 S(w_i) dw) cos(w_i t + phi_i),

* S the one-sided spectrum of :mod:`cable_ocp.heave.sea` (Bretschneider (6.20) or JONSWAP,
  gamma 3.3), m^2 s/rad;
* w_i the midpoints of ``components`` equal bins of width dw = (:data:`BAND_HIGH` -
  :data:`BAND_LOW`) omega_m / components, the first bin's low edge the multiple k0 dw
  nearest to :data:`BAND_LOW` omega_m (so w_i = (k0 + i + 1/2) dw, the band shifted by at
  most dw / 2). The band holds the Bretschneider energy but
  for a fraction exp(-1.25 / 0.5^4) = 2e-9 below and 1 - exp(-1.25 / 4^4) = 0.49 % above
  (the cumulative of (6.20) is (H_s^2 / 16) exp(-1.25 (omega_m / w)^4)); JONSWAP, more
  peaked, loses less. On this grid every sum and difference of two frequencies is a
  multiple of dw, so over one period 2 pi / dw the mean of z^2 (no fade) is exactly
  sum a_i^2 / 2 = sum S(w_i) dw, the midpoint rule of m0; the record also repeats, its
  sign flipped, every 2 pi / dw (192 s for omega_m = 0.6 rad/s and 64 components): give
  more components for longer deployments;
* phi_i uniform on [0, 2 pi) from ``numpy.random.default_rng(seed)``;
* f(t) the quintic fade-in 10x^3 - 15x^4 + 6x^5, x = min(t / fade_in, 1) (1 when
  fade_in = 0), as the scene's ``ramp_time`` (:mod:`cable_ocp.scene.motion`): the heave
  starts from rest, its velocity and acceleration continuous.

The design realisations have the seeds seed, ..., seed + realisations - 1; the unseen ones
(the check) seed + :data:`UNSEEN_OFFSET` + j, j = 0 .. unseen - 1: disjoint from the design
seeds, since at most 50 design realisations are allowed (:mod:`cable_ocp.scene.deployment`).

Without a sea the motion is the scene's own ``[top_motion]`` heave: heave_amplitude and
heave_frequency with its ramp_time (r A sin(w t)) plus the dz column of a series; the axial
schedule handles heave only, so a horizontal, circular or tow motion is refused.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.sea import bretschneider, jonswap
from cable_ocp.numerics.ramp import smoothstep, smoothstep_rate
from cable_ocp.numerics.table import piecewise_linear
from cable_ocp.scene.dynamic_parts import TopMotion
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.motion import top_offset_expr

__all__ = ["BAND_HIGH", "BAND_LOW", "UNSEEN_OFFSET", "VesselMotion", "fade", "heave_rate",
           "sea_components", "vessel_motions"]

#: the band of the sea's components, in units of omega_m (module docstring)
BAND_LOW = 0.5
BAND_HIGH = 4.0
#: the unseen realisations' seeds start this far above the design seed
UNSEEN_OFFSET = 100_000


def fade(t: np.ndarray, fade_in: float) -> tuple[np.ndarray, np.ndarray]:
    """The quintic fade-in f(t) = 10x^3 - 15x^4 + 6x^5, x = clip(t / fade_in, 0, 1), and
    its rate df/dt (1/s); (1, 0) when ``fade_in = 0``.

    Parameters
    ----------
    t : numpy.ndarray
        Times, s.
    fade_in : float
        s, >= 0.
    """
    t = np.asarray(t, dtype=float)
    if fade_in <= 0.0:
        return np.ones_like(t), np.zeros_like(t)
    x = np.clip(t / fade_in, 0.0, 1.0)
    f = smoothstep(x)
    df = smoothstep_rate(x) / fade_in
    return f, df


def heave_rate(heave: ca.Function) -> ca.Function:
    """dh/dt (m/s) of a heave h(t) (m), by CasADi's AD (the one home of the heave's rate:
    :meth:`VesselMotion.heave_rate` and the OCP's rest condition,
    :mod:`cable_ocp.schedule.ocp`).

    Parameters
    ----------
    heave : casadi.Function
        h(t), m, of one scalar time, s.
    """
    t = ca.MX.sym("t")
    return ca.Function("heave_rate", [t], [ca.jacobian(heave(t), t)])


def _evaluate(fn: ca.Function, t: np.ndarray) -> np.ndarray:
    """A scalar Function of time on an array of times (same shape)."""
    t = np.asarray(t, dtype=float)
    flat = t.ravel()
    if flat.size == 0:
        return np.zeros(t.shape)
    return np.asarray(fn.map(flat.size)(flat[None, :])).reshape(t.shape)


def _fade_expr(t: ca.SX, fade_in: float) -> ca.SX:
    if fade_in <= 0.0:
        return ca.SX(1.0)
    x = ca.fmin(ca.fmax(t / fade_in, 0.0), 1.0)
    return smoothstep(x)


@dataclass(frozen=True)
class VesselMotion:
    """The top's vertical offset z(t) from ``end_b.position`` (m, up): a faded sum of
    harmonics plus a piecewise-linear series.

    z(t) = f(t) sum_i a_i cos(w_i t + phi_i) + s(t), f the quintic fade over ``fade_in``
    (:func:`fade`), s the linear interpolation of ``series`` (held after its last row).
    The scene's heave r A sin(w t) is the one harmonic (A, w, -pi/2) faded over its
    ``ramp_time``.

    Attributes
    ----------
    name : str
        E.g. ``"design seed 1"``, ``"unseen seed 100001"``, ``"scene"``.
    seed : int or None
        The phases' seed (None: the scene's own motion).
    amplitudes : tuple of float
        a_i, m.
    frequencies : tuple of float
        w_i, rad/s.
    phases : tuple of float
        phi_i, rad.
    fade_in : float
        s (0: no fade).
    series : tuple of (float, float)
        (t, dz) rows, s and m; empty: none.
    top_motion : TopMotion or None
        The scene's own heave as a ``[top_motion]`` (heave keys, ramp_time and series
        only), whose :func:`cable_ocp.scene.motion.top_offset_expr` is the CasADi form;
        None for a sea.
    """

    name: str
    seed: int | None
    amplitudes: tuple[float, ...] = ()
    frequencies: tuple[float, ...] = ()
    phases: tuple[float, ...] = ()
    fade_in: float = 0.0
    series: tuple[tuple[float, float], ...] = ()
    top_motion: TopMotion | None = None

    def _arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return (np.asarray(self.amplitudes, dtype=float),
                np.asarray(self.frequencies, dtype=float),
                np.asarray(self.phases, dtype=float))

    @functools.cached_property
    def _laws(self) -> tuple[ca.Function, ca.Function]:
        """(z(t), dz/dt(t)): :meth:`casadi_heave` and its derivative by AD, built once."""
        z = self.casadi_heave()
        return z, heave_rate(z)

    def heave(self, t: np.ndarray) -> np.ndarray:
        """The top's vertical offset z(t), m (same shape as ``t``): :meth:`casadi_heave`
        evaluated (the law's one writing).

        Parameters
        ----------
        t : numpy.ndarray
            Times, s.
        """
        return _evaluate(self._laws[0], t)

    def heave_rate(self, t: np.ndarray) -> np.ndarray:
        """dz/dt, m/s: the exact derivative of :meth:`heave`, by CasADi's AD of
        :meth:`casadi_heave` (a series' slope is taken on the interval right of a row; 0
        before the first row and after the last).

        Parameters
        ----------
        t : numpy.ndarray
            Times, s.
        """
        return _evaluate(self._laws[1], t)

    def casadi_heave(self) -> ca.Function:
        """``casadi.Function("heave", [t], [z])``: :meth:`heave` of a scalar SX time (s),
        m: the same law symbolically (the scene's own motion through
        :func:`cable_ocp.scene.motion.top_offset_expr`, its z component)."""
        t = ca.SX.sym("t")
        if self.top_motion is not None:
            z = top_offset_expr(self.top_motion, t)[2]
        else:
            a, w, p = self._arrays()
            z = ca.SX(0.0)
            for ai, wi, pi in zip(a, w, p, strict=True):
                z = z + float(ai) * ca.cos(float(wi) * t + float(pi))
            z = _fade_expr(t, self.fade_in) * z
            if self.series:
                rows = np.asarray(self.series, dtype=float)
                ts, zs = rows[:, 0], rows[:, 1]
                z = z + piecewise_linear(ts, zs, t, hold_before=True)
        return ca.Function("heave", [t], [z], ["t"], ["heave"])

    def series_rows(self, duration: float, step: float) -> list[list[float]]:
        """Rows [t, 0, 0, dz] of ``top_motion.series`` (s, m) at t = 0, step, ... up to
        and including ``duration``.

        Parameters
        ----------
        duration : float
            s, > 0.
        step : float
            s, > 0 (the simulator interpolates linearly between rows: the offset's error
            is about step^2 max|z''| / 8).
        """
        if not (duration > 0.0 and step > 0.0):
            raise CableOCPError(f"series_rows: duration = {duration} s and step = {step} s "
                                "must be > 0")
        n = max(1, math.ceil(duration / step - 1e-9))
        ts = np.linspace(0.0, n * step, n + 1)
        zs = self.heave(ts)
        return [[float(t), 0.0, 0.0, float(z)] for t, z in zip(ts, zs, strict=True)]

    @property
    def highest_frequency(self) -> float:
        """The largest harmonic frequency, rad/s (0 without harmonics)."""
        return max(self.frequencies, default=0.0)


def sea_components(spectrum: str, hs: float, omega_m: float, components: int
                   ) -> tuple[np.ndarray, np.ndarray, float]:
    """(w_i (rad/s), a_i = sqrt(2 S(w_i) dw) (m), dw (rad/s)) of a sea (module docstring).

    Parameters
    ----------
    spectrum : str
        ``"bretschneider"`` or ``"jonswap"`` (gamma 3.3).
    hs : float
        H_s, m.
    omega_m : float
        Peak frequency, rad/s.
    components : int
        Number of harmonics.
    """
    dw = (BAND_HIGH - BAND_LOW) * omega_m / components
    k0 = round(BAND_LOW * omega_m / dw)  # the band's low edge on the grid k dw
    w = (k0 + np.arange(components) + 0.5) * dw
    s = bretschneider(w, hs, omega_m) if spectrum == "bretschneider" else jonswap(
        w, hs, omega_m)
    return w, np.sqrt(2.0 * s * dw), dw


def _scene_motion(scene: DynamicScene) -> VesselMotion:
    tm = scene.top_motion
    for key, val in (("horizontal_amplitude", tm.horizontal_amplitude),
                     ("circular_radius", tm.circular_radius)):
        if val != 0.0:
            raise CableOCPError(f"top_motion.{key} = {val}: the axial pay-out schedule "
                                "handles heave only; remove it (or give a [deployment.sea])")
    if tm.tow is not None:
        raise CableOCPError("[top_motion.tow]: the axial pay-out schedule handles heave only; "
                            "remove the tow (or give a [deployment.sea])")
    if any(r[1] != 0.0 or r[2] != 0.0 for r in tm.series):
        raise CableOCPError("top_motion.series: a horizontal offset (dx, dy columns) is not "
                            "handled by the axial pay-out schedule; give dz only")
    amps: tuple[float, ...] = ()
    freqs: tuple[float, ...] = ()
    phases: tuple[float, ...] = ()
    if tm.heave_amplitude != 0.0:
        amps, freqs, phases = (tm.heave_amplitude,), (tm.heave_frequency,), (-0.5 * math.pi,)
    series = tuple((float(r[0]), float(r[3])) for r in tm.series)
    own = replace(TopMotion(), heave_amplitude=tm.heave_amplitude,
                  heave_frequency=tm.heave_frequency, ramp_time=tm.ramp_time,
                  series=tm.series)
    return VesselMotion(name="scene", seed=None, amplitudes=amps, frequencies=freqs,
                        phases=phases, fade_in=tm.ramp_time if amps else 0.0,
                        series=series, top_motion=own)


def vessel_motions(scene: DynamicScene, which: str = "design") -> list[VesselMotion]:
    """The vessel motions of a deployment (module docstring).

    Parameters
    ----------
    scene : DynamicScene
        A scene; its ``[deployment.sea]`` when given, else its ``[top_motion]`` heave.
    which : str
        ``"design"`` (the realisations the schedule is designed on, or the scene's own
        motion) or ``"unseen"`` (the check's realisations, seeds disjoint from the design
        ones; needs a sea).

    Raises
    ------
    CableOCPError
        ``which`` not one of the two; ``"unseen"`` without a sea; a scene motion that is
        not heave (the key named).
    """
    if which not in ("design", "unseen"):
        raise CableOCPError(f'vessel_motions: which = {which!r}; valid are "design", '
                            '"unseen"')
    sea = scene.deployment.sea if scene.deployment is not None else None
    if sea is None:
        if which == "unseen":
            raise CableOCPError('vessel_motions(which="unseen") needs a [deployment.sea]: '
                                "the scene's own [top_motion] is one motion, with no unseen "
                                "realisations")
        return [_scene_motion(scene)]
    w, a, _ = sea_components(sea.spectrum, sea.significant_height, sea.peak_frequency,
                             sea.components)
    if which == "design":
        seeds = [(f"design seed {sea.seed + j}", sea.seed + j) for j in range(sea.realisations)]
    else:
        seeds = [(f"unseen seed {sea.seed + UNSEEN_OFFSET + j}", sea.seed + UNSEEN_OFFSET + j)
                 for j in range(sea.unseen)]
    out = []
    for name, seed in seeds:
        phi = np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, sea.components)
        out.append(VesselMotion(name=name, seed=seed, amplitudes=tuple(map(float, a)),
                                frequencies=tuple(map(float, w)),
                                phases=tuple(map(float, phi)), fade_in=sea.fade_in))
    return out
