"""The static start of a dynamic scene (Huang (1992) section 5.6.1).

:func:`static_state` solves ``scene.statics`` with the statics solver. With a unit in a
current that varies with depth, the unit's drag at rest depends on the depth at which it
hangs, which the solve decides: the load is re-evaluated at the solved depth and the
scene re-solved (warm-started) until the depth changes by less than 1e-9 of the length.
"""

from __future__ import annotations

from dataclasses import replace

from cable_ocp.dynamics.bending_terms import flexible_warm_start
from cable_ocp.scene import End, Scene
from cable_ocp.scene.dynamics import DynamicScene, current_at
from cable_ocp.statics.solution import StaticsSolution

__all__ = ["static_scene", "static_state"]


def static_scene(scene: DynamicScene, unit_z: float | None = None) -> Scene:
    """The statics scene of the initial state, with the unit's drag in the current taken
    at height ``unit_z`` (m; default: the estimate used when the scene was read).

    Parameters
    ----------
    scene : DynamicScene
        The dynamic scene.
    unit_z : float, optional
        Height at which the unit's drag is taken, m.
    """
    st = scene.statics
    if scene.unit is None or unit_z is None:
        return st
    load = scene.unit.static_load(current_at(st.environment.current, unit_z),
                                  st.environment.water_density)
    return replace(st, end_a=End(position=(None, None, None), force=load))


def static_state(scene: DynamicScene, max_updates: int = 8) -> StaticsSolution:
    """Solve the static state of a dynamic scene with the statics solver.

    Returns the :class:`~cable_ocp.statics.solution.StaticsSolution` (check its
    ``status``); ``diagnostics["unit_current_updates"]`` counts the re-solves for a
    depth-varying current.

    Parameters
    ----------
    scene : DynamicScene
        The dynamic scene.
    max_updates : int
        Most re-solves for a depth-varying current.
    """
    from cable_ocp.statics.solver import solve  # heavy import, only when needed

    sol = flexible_warm_start(scene.statics)  # a line with EI: from its flexible statics
    if sol is None or not sol.success:
        sol = solve(scene.statics)
    cur = scene.statics.environment.current
    if scene.unit is None or cur is None or cur.uniform or not sol.success:
        return sol
    updates = 0
    for _ in range(max_updates):
        z = float(sol.position[0, 2])
        new = solve(static_scene(scene, z), warm_start=sol)
        updates += 1
        moved = abs(float(new.position[0, 2]) - z)
        sol = new
        if not sol.success or moved <= 1e-9 * scene.length:
            break
    sol.diagnostics["unit_current_updates"] = updates
    return sol
