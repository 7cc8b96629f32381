"""The ``[response]`` table of a dynamic scene: defaults of ``cable-ocp response``.

Schema (all optional; the command line wins)::

    [response]
    frequencies = [5.0, 40.0, 36]   [start, stop, N]: N frequencies, rad/s (> 0)
    amplitudes = [0.0254, 0.0508]   excitation amplitudes, m (> 0)
    outputs = ["top_tension", "unit_z"]
                                    top_tension, unit_tension, unit_x, unit_y, unit_z,
                                    node_x:K, node_y:K, node_z:K
    excitation = "heave"            "heave" | "horizontal" | "circular"
    damping_ratio = 0.0             modal damping ratio of the linear curve (-)
    tolerance = 0.01                relative amplitude change over the last two periods
                                    that counts as periodic (-)
    max_periods = 192               cap on the periods of a time run after the ramp
    ramp_periods = 10.0             periods of the smooth ramp-in of the motion (an undamped
                                    line keeps the free vibration a short ramp starts)
    tension_scale = 380.0           N/m: the figure plots the tensions' ratios divided by
                                    it (Fig. 3.5's K)
    frequency_scale = 6.912         rad/s: the figure's frequency axis as w / it (Fig.
                                    3.5's omega_nc)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.fields import check_keys, choice, integer, number

__all__ = ["RESPONSE_KEYS", "ResponseDefaults", "parse_response"]

RESPONSE_KEYS = {"frequencies", "amplitudes", "outputs", "excitation", "damping_ratio",
                 "tolerance", "max_periods", "ramp_periods",
                 "tension_scale", "frequency_scale"}


@dataclass(frozen=True)
class ResponseDefaults:
    """The file's defaults of a frequency-response sweep (None: not given).

    Attributes
    ----------
    frequencies : tuple (start, stop, N) or None
        rad/s, rad/s, count.
    amplitudes : tuple of float
        m (empty: the scene's own amplitude).
    outputs : tuple of str
        Output names (empty: the command's default); checked when the sweep starts.
    excitation : str or None
        ``"heave"``, ``"horizontal"`` or ``"circular"``.
    damping_ratio : float or None
        -.
    tolerance : float or None
        -.
    max_periods : int or None
        Periods.
    ramp_periods : float or None
        Periods.
    tension_scale : float or None
        N/m (the figure only).
    frequency_scale : float or None
        rad/s (the figure only).
    """

    frequencies: tuple[float, float, int] | None = None
    amplitudes: tuple[float, ...] = ()
    outputs: tuple[str, ...] = ()
    excitation: str | None = None
    damping_ratio: float | None = None
    tolerance: float | None = None
    max_periods: int | None = None
    ramp_periods: float | None = None
    tension_scale: float | None = None
    frequency_scale: float | None = None


def parse_response(t: Any) -> ResponseDefaults:
    """Validate a ``[response]`` table (module docstring).

    Raises
    ------
    CableOCPError
        An unknown key (the valid ones listed) or an invalid value (named).
    """
    t = check_keys(t, RESPONSE_KEYS, "response")
    freqs = None
    if "frequencies" in t:
        v = t["frequencies"]
        if not isinstance(v, list) or len(v) != 3:
            raise CableOCPError(f"response.frequencies = {v!r}: expected [start, stop, N] "
                                "(rad/s, rad/s, count)")
        lo = number(v[0], "response.frequencies[0]", positive=True, unit="rad/s")
        hi = number(v[1], "response.frequencies[1]", positive=True, unit="rad/s")
        freqs = (lo, hi, integer(v[2], "response.frequencies[2]", 1, 10000))
    amps: tuple[float, ...] = ()
    if "amplitudes" in t:
        v = t["amplitudes"]
        if not isinstance(v, list) or not v:
            raise CableOCPError(f"response.amplitudes = {v!r}: expected a list of amplitudes "
                                "(m)")
        amps = tuple(number(a, f"response.amplitudes[{i}]", positive=True, unit="m")
                     for i, a in enumerate(v))
    outs: tuple[str, ...] = ()
    if "outputs" in t:
        v = t["outputs"]
        if not isinstance(v, list) or not all(isinstance(s, str) for s in v):
            raise CableOCPError(f"response.outputs = {v!r}: expected a list of names, e.g. "
                                '["top_tension", "unit_z"]')
        outs = tuple(v)
    exc = (choice(t["excitation"], "response.excitation", ("heave", "horizontal", "circular"))
           if "excitation" in t else None)
    zeta = (number(t["damping_ratio"], "response.damping_ratio", nonneg=True)
            if "damping_ratio" in t else None)
    tol = number(t["tolerance"], "response.tolerance", positive=True) if "tolerance" in t \
        else None
    cap = integer(t["max_periods"], "response.max_periods", 2, 100000) \
        if "max_periods" in t else None
    ramp = number(t["ramp_periods"], "response.ramp_periods", nonneg=True) \
        if "ramp_periods" in t else None
    scales = {k: number(t[k], f"response.{k}", positive=True)
              for k in ("tension_scale", "frequency_scale") if k in t}
    return ResponseDefaults(frequencies=freqs, amplitudes=amps, outputs=outs, excitation=exc,
                            damping_ratio=zeta, tolerance=tol, max_periods=cap,
                            ramp_periods=ramp, **scales)
