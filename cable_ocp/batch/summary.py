"""The extremes of a batch: for every output, its smallest and largest value over the
solved cases and the parameter values of the cases that gave them (the swept keys with
their units, :mod:`cable_ocp.scene.units`), so that a summary reads "largest max_tension
4.35 kN at layout.psi0_deg = 150 deg, environment.current.speed = 1 m/s"."""

from __future__ import annotations

import math
from typing import Any

from cable_ocp.scene.units import key_unit

__all__ = ["extremes"]


def extremes(res: Any) -> dict[str, dict[str, Any]]:
    """Min and max of each output of a :class:`cable_ocp.batch.BatchResult` over its cases
    with status ``solved``.

    Parameters
    ----------
    res : BatchResult
        The batch (its ``rows``, ``outputs`` and swept inputs, :meth:`BatchResult.swept`).

    Returns
    -------
    dict
        Output column -> ``min``, ``max`` (the values, in the column's unit),
        ``min_case``, ``max_case`` (case indices) and ``min_at``, ``max_at`` (swept key ->
        that case's value, problem-file units); the first case wins a tie. Outputs without
        a finite value in any solved case are left out. ``units`` gives each swept key's
        unit.
    """
    keys = res.swept()
    ok = [r for r in res.rows if r["status"] == "solved"]
    out: dict[str, dict[str, Any]] = {}
    for col in res.outputs:
        vals = [r for r in ok if isinstance(r.get(col), (int, float))
                and math.isfinite(r[col])]
        if not vals:
            continue
        lo = min(vals, key=lambda r: (r[col], r["case"]))
        hi = max(vals, key=lambda r: (r[col], -r["case"]))
        out[col] = {"min": lo[col], "min_case": lo["case"],
                    "min_at": {k: lo.get(k) for k in keys},
                    "max": hi[col], "max_case": hi["case"],
                    "max_at": {k: hi.get(k) for k in keys},
                    "units": {k: key_unit(k) for k in keys}}
    return out
