"""A body's 6x6 stiffness at an evaluated state (CONVENTIONS "Mooring systems";
docs/systems.md, "Stiffness"; the parts: :mod:`cable_ocp.mooring.equilibrium`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from cable_ocp.mooring.model import Evaluation, SystemModel, condensed

__all__ = ["body_stiffness", "relative_asymmetry"]


def body_stiffness(model: SystemModel, ev: Evaluation, body: str) -> dict[str, Any]:
    """A body's 6x6 stiffness at an evaluated state (see the module notes).

    Parameters
    ----------
    model : SystemModel
        The model.
    ev : Evaluation
        An evaluation with its Jacobian, at an equilibrium of everything but ``body``.
    body : str
        The body's name.

    Returns
    -------
    dict
        ``mooring`` (6x6, N/m, N/rad, N m/m, N m/rad), ``hydrostatic`` (of the body's
        own load), ``total``, ``elastic`` and ``geometric`` (the parts of ``mooring``),
        ``moment`` (the mooring's moment on the body, N m: ``mooring - mooring^T``
        equals [moment]x when the lines are conservative).
    """
    jac = ev.jac.copy()  # type: ignore[union-attr]
    keep = np.arange(model.cols[body].start, model.cols[body].stop)
    free = model.free_dofs()
    elim = np.array([k for k in free if k not in set(keep.tolist())], dtype=int)
    for b in model.scene.bodies:  # the other bodies' own loads act in their equilibrium
        if b.name != body:
            c = model.cols[b.name]
            jac[c, c] += ev.own[b.name]
    k_moor = -condensed(jac, keep, elim)
    geo = -ev.geometric[body]
    hyd = -ev.own[body]
    load = ev.line_loads[body]
    return {"mooring": k_moor, "hydrostatic": hyd, "total": k_moor + hyd,
            "geometric": geo, "elastic": k_moor - geo, "moment": load[3:].copy(),
            "force": load[:3].copy()}


def relative_asymmetry(k: np.ndarray) -> float:
    """max |K - K^T| / max |K| (0 for a symmetric matrix).

    Parameters
    ----------
    k : ndarray
        A square matrix.
    """
    big = float(np.max(np.abs(k)))
    return 0.0 if big == 0.0 or not math.isfinite(big) else float(np.max(np.abs(k - k.T))) / big
