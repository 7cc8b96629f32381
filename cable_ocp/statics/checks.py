"""Checks of a statics answer that do not depend on how it was computed.

Every statics method's result passes through :func:`check_physical` before it is returned:
a profile that leaves the water (above the free surface) or passes below the seabed where
no contact is modelled is not an answer to the scene's physics, so it gets a non-success
status (``"above_surface"``, ``"below_seabed"``) with where and by how much, never
``"solved"``.
"""

from __future__ import annotations

import math

import numpy as np

from cable_ocp.scene import Scene
from cable_ocp.statics.solution import StaticsSolution

#: relative tolerance on the water column (times the cable length), m/m: about the
#: solver's own position accuracy, so that an end fixed exactly at z = 0 or at the surface
#: is never flagged
REL_TOL = 1e-6


def _where(sol: StaticsSolution, i: int) -> str:
    x, y, z = (float(v) for v in sol.position[i])
    return f"at s = {float(sol.s[i]):.4g} m from end_a, (x, y, z) = ({x:.4g}, {y:.4g}, {z:.4g}) m"


def check_physical(scene: Scene, sol: StaticsSolution) -> StaticsSolution:
    """Mark ``sol`` (in place, and return it) when its profile leaves the water column.

    * above the surface z = ``environment.water_depth``: status ``"above_surface"``;
    * below the seabed plane z = 0 by more than the cable's radius when the scene has no
      ``[environment.seabed]`` (no contact model): status ``"below_seabed"``; a dip within
      the radius (the cable touching the plane) is a warning. With a seabed table,
      contact is modelled and penetration is judged by the solver's contact logic.

    Only results that would otherwise be used (``"solved"``, ``"inaccurate"``) are marked.
    A tension above the last row of ``cable.tension_strain`` is a warning (the law there is
    the table's straight continuation).

    Parameters
    ----------
    scene : Scene
        The scene solved: ``environment.water_depth`` (m, the free surface's z), whether it
        has an ``[environment.seabed]`` table, and its cables' diameters (m; the smallest
        one's radius is the allowance below the plane z = 0).
    sol : StaticsSolution
        The answer to check; ``status``, ``message`` and ``diagnostics["warnings"]`` are
        updated in place. The tolerance is :data:`REL_TOL` times its length (m, at
        least 1 m).
    """
    if sol.status not in ("solved", "inaccurate") or not np.all(np.isfinite(sol.position)):
        return sol
    table = scene.cable.tension_strain
    if table and not scene.segments:
        t_max = float(np.max(np.linalg.norm(sol.tension_vector, axis=1)))
        if t_max > table[-1][0]:
            warnings = sol.diagnostics.setdefault("warnings", [])
            note = (f"the largest tension, {t_max:.6g} N, is above the last row of "
                    f"cable.tension_strain ({table[-1][0]:.6g} N): the law there is the "
                    "straight continuation of the table's end slope; extend the table")
            if note not in warnings:
                warnings.append(note)
    tol = REL_TOL * max(float(sol.length), 1.0)
    z = sol.position[:, 2]
    depth = scene.environment.water_depth
    i_top = int(np.argmax(z))
    if z[i_top] > depth + tol:
        sol.status = "above_surface"
        sol.message = (
            f"the profile rises {z[i_top] - depth:.4g} m above the free surface "
            f"(environment.water_depth = {depth:g} m) {_where(sol, i_top)}; the model holds "
            "for a line in the water only: check water_depth and the end positions, or the "
            "buoyancy")
        return sol
    if scene.environment.seabed is None:
        i_low = int(np.argmin(z))
        # the profile is the cable's centreline: a centreline within the cable's radius of
        # the plane is a cable touching the seabed, not through it (e.g. an anchored line
        # leaving its anchor a fraction of a degree below horizontal dips by fractions of
        # a millimetre before it rises)
        radius = 0.5 * min(c.diameter for c in (scene.segments or (scene.cable,)))
        if z[i_low] < -max(tol, radius):
            sol.status = "below_seabed"
            sol.message = (
                f"the profile passes {-z[i_low]:.4g} m below the seabed plane z = 0 "
                f"{_where(sol, i_low)}; the scene has no [environment.seabed] table, so "
                "contact is not modelled: add one (depth_offset, friction) to model contact")
        elif z[i_low] < -tol:
            warnings = sol.diagnostics.setdefault("warnings", [])
            note = (
                f"the cable's centreline dips {-z[i_low] * 1e3:.3g} mm below the seabed "
                f"plane z = 0 {_where(sol, i_low)}, within the cable's radius "
                f"({radius * 1e3:.3g} mm): it touches the seabed there; contact is not "
                "modelled (no [environment.seabed] table)")
            if note not in warnings:  # the check may run twice on one solution
                warnings.append(note)
    return sol


def is_finite_solution(sol: StaticsSolution) -> bool:
    """True when every array of ``sol`` is finite."""
    return bool(np.all(np.isfinite(sol.position)) and np.all(np.isfinite(sol.tension_vector))
                and math.isfinite(sol.length))
