"""The comparison on the cable plant and its per-controller metrics."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cable_ocp.heave.closed_loop import LoopRun, run_status
from cable_ocp.heave.simulate import Comparison
from cable_ocp.scene.heave import HeaveScene

__all__ = ["CABLE_FIELDS", "CableComparison", "CableMetrics", "heave_rms"]


# ------------------------------------------------------------------------------------------
# compare() on the cable
# ------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class CableComparison(Comparison):
    """Result of :func:`cable_ocp.heave.cable_compare.compare_cable` (the fields of
    :class:`cable_ocp.heave.simulate.Comparison` plus the cable's).

    Attributes
    ----------
    statuses, messages : dict
        Controller name -> status (:data:`cable_ocp.heave.simulate.STATUSES`) of its run on
        the plant, and its explanation.
    passive_heave_rms : float or None
        Heave RMS of the passive run on the same plant and sea (the baseline of
        ``reduction_pct``), m.
    warnings : list of str
        Remarks that do not change a status.
    json_extra : dict
        Top-level JSON fields: ``plant``, ``design_model`` (a, b used and where from),
        ``identified`` (see :func:`cable_ocp.heave.identify_cable.identified_json`).
    predicted_traces : dict
        The runs on the design model (same estimator, sensors, noise, sea).
    """

    json_extra: dict = field(default_factory=dict)
    predicted_traces: dict = field(default_factory=dict)


#: the cable-plant fields of a controller's metrics (None where the run is not solved)
CABLE_FIELDS = ("tension_unit_min", "tension_unit_max", "tension_top_min", "tension_top_max",
                "slack_samples", "slack_first_time_s", "plant_failed_at_s")


def _metrics_cable(sc: HeaveScene, run: LoopRun, name: str, G: np.ndarray | None) -> dict:
    """The metrics of :func:`cable_ocp.heave.simulate.compare` and the cable's; every value
    None (JSON null) but ``energy_index``, the solve time and ``plant_failed_at_s`` when
    the run is not solved."""
    from cable_ocp.heave.simulate import _metrics

    energy = (float(np.sqrt(np.sum(G**2))) if name in ("lqr", "lqg") and G is not None
              else None)
    times = run.times if name == "mpc" else None
    if run_status(run)[0] != "solved":
        d = dict.fromkeys(("heave_rms", "reduction_pct", "peak_winch_speed", "max_stroke",
                           "max_constraint_violation", "winch_speed_rms") + CABLE_FIELDS)
        d["energy_index"] = energy
        d["solve_time_median_s"] = (float(np.median(times)) if times is not None
                                    and times.size else None)
        d["plant_failed_at_s"] = run.plant_failed_at
        return d
    base = _metrics(sc, run.trace, run.commands, energy, times, sc.controller.sample_time)
    tr = run.trace
    keep = tr.t >= sc.simulation.warmup - 1e-12
    h = sc.controller.sample_time
    kk = np.arange(tr.min_element_tension.size) * h >= sc.simulation.warmup - 1e-12
    slack = tr.min_element_tension <= 0.0
    first = np.flatnonzero(slack & kk)
    return {**base.as_dict(),
            "tension_unit_min": float(np.min(tr.tension_unit[keep])),
            "tension_unit_max": float(np.max(tr.tension_unit[keep])),
            "tension_top_min": float(np.min(tr.tension_top[keep])),
            "tension_top_max": float(np.max(tr.tension_top[keep])),
            "slack_samples": int(np.count_nonzero(slack[kk])),
            "slack_first_time_s": float(first[0] * h) if first.size else None,
            "plant_failed_at_s": run.plant_failed_at}


@dataclass(frozen=True)
class CableMetrics:
    """Per-controller metrics on the cable plant (JSON fields).

    The fields of :class:`cable_ocp.heave.simulate.Metrics` for the run on the cable, and:
    ``heave_rms_predicted`` (m) and ``reduction_predicted_pct`` (%) of the same controller
    (estimator, sensors, noise, sea) on the design model; ``tension_unit_min/max``,
    ``tension_top_min/max`` (N, after the warm-up); ``slack_samples`` (samples after the
    warm-up with an element tension <= 0), ``slack_first_time_s`` (s or None);
    ``plant_failed_at_s`` (a Newton step of the cable did not converge there, or None).
    """

    values: dict

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return dict(self.values)

    def __getattr__(self, key: str) -> Any:
        try:
            return self.__dict__["values"][key]
        except KeyError as exc:
            raise AttributeError(key) from exc


def heave_rms(t: np.ndarray, x: np.ndarray, warmup: float) -> float:
    """RMS of ``x`` over ``t >= warmup``, m."""
    keep = t >= warmup - 1e-12
    return float(math.sqrt(np.mean(x[keep] ** 2)))
