"""Snap loads: the peak tension that ends a slack spell, found in a run's samples.

A line goes slack where an element's tension falls to the no-compression law's floor
(:func:`cable_ocp.physics.elasticity.smooth_tension` < :data:`SLACK_TENSION`); it snaps
when every element is taut again and the falling unit (or the line's own mass) is caught.
:func:`snap_report` splits the samples into slack spells (samples with at least one slack
element) and taut spells; the snap of a taut spell that follows a slack one is its largest
element tension. The report gives the largest snap of the run: its peak tension (N), time
(s), element and location (the unstretched arc length of the element's middle from end_a,
m), the times the slack spell before it began and ended (s), and how many snaps the run
had. The peak is taken on the output samples: a run that must resolve it sets
``simulation.output_step`` to a few time steps at most (the closed-form check of a mass
dropped on a line, tests/dynamics/test_snap.py, uses output_step = time_step).

``simulation.start = "dropped"`` (with ``drop_height`` h, m) starts a run slack: the line
straight down from end_b with every node raised by h (1 - s / L), the unit h above where
the line goes taut, at rest (the planar and lumped-mass models; the closed form of the
snap is W (1 + sqrt(1 + 2 k h / W)) for a massless line of stiffness k = EA / L).

The models call it on their outputs (the planar and lumped-mass models; the axial model
reports slack without following it): ``SimulationResult.snap``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from cable_ocp.physics.elasticity import SLACK_SMOOTHING

__all__ = ["SLACK_TENSION", "dropped_message", "no_snap", "snap_report"]

#: an element whose tension is at or below this is slack in :func:`snap_report`, N (the
#: smooth no-compression law gives delta_T / 2 = 0.005 N at zero strain and less below)
SLACK_TENSION = SLACK_SMOOTHING


def dropped_message(sim: Any) -> str:
    """The start's message of ``simulation.start = "unstrained"`` or ``"dropped"`` (the
    scene's :class:`~cable_ocp.scene.dynamic_parts.Simulation`)."""
    if sim.start == "dropped":
        return (f"straight down from end_b and slack, the unit {sim.drop_height:g} m above "
                "where the line goes taut, at rest")
    return "hanging straight down, unstretched, at rest"


def no_snap() -> dict[str, Any]:
    """The ``snap`` entry of a run without a snap (every field None, ``count`` 0)."""
    return {"occurred": False, "count": 0, "peak_tension": None, "time": None,
            "segment": None, "location": None, "slack_from": None, "taut_at": None}


def snap_report(t: np.ndarray, tensions: np.ndarray, element_mid_s: np.ndarray,
                slack_tension: float = SLACK_TENSION) -> dict[str, Any]:
    """The largest snap of a run (see the module docstring).

    Parameters
    ----------
    t : ndarray (n_t,)
        Sample times, s.
    tensions : ndarray (n_t, N)
        Element tensions, N.
    element_mid_s : ndarray (N,) or (n_t, N)
        Unstretched arc length of each element's middle from end_a, m (per sample when
        the length varies).
    slack_tension : float
        An element at or below this tension is slack, N.

    Returns
    -------
    dict
        ``occurred`` (bool), ``count`` (snaps in the run), ``peak_tension`` (N), ``time``
        (s), ``segment`` (element index from end_a), ``location`` (m from end_a),
        ``slack_from`` (s: the first slack sample of the spell before the snap),
        ``taut_at`` (s: the first sample with every element taut again).
    """
    t = np.asarray(t, dtype=float)
    ten = np.asarray(tensions, dtype=float)
    out = no_snap()
    if ten.ndim != 2 or ten.shape[0] < 2 or ten.shape[1] == 0:
        return out
    slack = np.any(~(ten > slack_tension), axis=1)  # a NaN tension counts as slack
    starts = np.where(slack[:-1] & ~slack[1:])[0] + 1  # first taut sample after slack
    if starts.size == 0:
        return out
    best = None
    for k in starts:
        nxt = np.where(slack[k:])[0]
        stop = k + int(nxt[0]) if nxt.size else t.size
        window = ten[k:stop]
        j, e = np.unravel_index(int(np.argmax(window)), window.shape)
        peak = float(window[j, e])
        if best is None or peak > best[0]:
            prev = np.where(~slack[:k])[0]
            begin = int(prev[-1]) + 1 if prev.size else 0
            best = (peak, k + int(j), int(e), k, begin)
    assert best is not None
    peak, row, e, k, begin = best
    mids = np.asarray(element_mid_s, dtype=float)
    loc = mids[row, e] if mids.ndim == 2 else mids[e]
    out.update(occurred=True, count=int(starts.size), peak_tension=peak,
               time=float(t[row]), segment=e, location=float(loc),
               slack_from=float(t[begin]), taut_at=float(t[k]))
    return out
