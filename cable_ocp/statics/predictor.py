"""The continuation predictor of sweeps and sessions: Lagrange extrapolation of solutions.

Along a line of scenes that differ in one number (a sweep, a grid's line in a batch), the
start of the next solve is the polynomial extrapolation through the last solutions, on
their node arrays and, when one solver produced them all, on its unknowns (fewer Newton
steps than starting from the previous solution). Used by
:func:`cable_ocp.statics.solver.sweep` and :class:`cable_ocp.statics.solver.SolveSession`.
"""

from __future__ import annotations

import math
from typing import Any

from cable_ocp.statics.solution import StaticsSolution

__all__ = ["PREDICTOR_MAX_GAIN", "PREDICTOR_POINTS", "extrapolate", "lagrange_weights",
           "predict"]

#: most points of the polynomial predictor in a sweep (4: cubic extrapolation; on the De
#: Zoysa sweep it takes 3 Newton steps per point where the secant takes 4)
PREDICTOR_POINTS = 4
#: largest sum of |Lagrange weights| of a prediction (uniform steps: 15 for the cubic,
#: 7 for the quadratic, 3 for the secant); beyond it (a long step after short ones) the
#: oldest points are dropped, and without a usable secant the previous solution is used
PREDICTOR_MAX_GAIN = 16.0


def lagrange_weights(vs: list[float], v: float) -> list[float]:
    """Lagrange weights of the values at ``vs`` for extrapolation to ``v``.

    Parameters
    ----------
    vs : list of float
        The distinct abscissae of the known points.
    v : float
        The abscissa of the prediction.
    """
    return [math.prod((v - vs[j]) / (vs[i] - vs[j]) for j in range(len(vs)) if j != i)
            for i in range(len(vs))]


def extrapolate(points: list[tuple[float, StaticsSolution]], v: float) -> StaticsSolution:
    """Lagrange extrapolation to ``v`` through (value, solution) points of one mesh, on
    the node arrays and, when one solver produced every point, on its unknowns (node by
    node: where the mesh points moved with the kinks between the points, the interval
    ends are extrapolated alike).

    Parameters
    ----------
    points : list of (float, StaticsSolution)
        The known points, oldest first, on one mesh.
    v : float
        The value to extrapolate to.

    Returns
    -------
    StaticsSolution
        Status ``"predicted"``: a start for a solver, not a solution.
    """
    weights = lagrange_weights([float(x) for x, _ in points], v)

    def comb(arrays: list[Any]) -> Any:
        return sum(wt * a for wt, a in zip(weights, arrays, strict=True))

    sols = [sol for _, sol in points]
    out = StaticsSolution(
        status="predicted", message=f"extrapolated through {len(points)} solutions",
        s=comb([x.s for x in sols]), position=comb([x.position for x in sols]),
        tension_vector=comb([x.tension_vector for x in sols]),
        length=float(comb([x.length for x in sols])))
    own = [x._unknowns for x in sols]
    if all(u is not None and u[0] is own[-1][0] and u[1].shape == own[-1][1].shape
           for u in own):
        mesh = own[-1][2]
        if any(u[2] != mesh for u in own):
            edges = comb([u[2].interval_edges() for u in own])
            try:
                mesh = mesh.with_edges(edges)
            except ValueError:  # the interval ends would not increase: no prediction
                return out
        out._unknowns = (own[-1][0], comb([u[1] for u in own]), mesh)
    return out


def predict(points: list[tuple[float, StaticsSolution]], v: float,
            fallback: StaticsSolution | None) -> StaticsSolution | None:
    """The start of a continuation step to ``v`` from the distinct points of one line
    (the last one the previous solution): points are dropped, oldest first, while the
    prediction's gain (sum of |Lagrange weights|) exceeds :data:`PREDICTOR_MAX_GAIN`;
    with two or more left, their extrapolation, else ``fallback``.

    Parameters
    ----------
    points : list of (float, StaticsSolution)
        The last solutions on the line, oldest first (shortened in place).
    v : float
        The value of the next scene.
    fallback : StaticsSolution or None
        The start without a prediction (the previous solution).
    """
    while len(points) >= 2 and sum(abs(x) for x in lagrange_weights(
            [float(x) for x, _ in points], float(v))) > PREDICTOR_MAX_GAIN:
        points.pop(0)
    return extrapolate(points, float(v)) if len(points) >= 2 else fallback
