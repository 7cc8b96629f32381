"""Helpers shared by the baseline methods: the unsupported-scene error, the end checks of
the z-parametrised methods, the resolution (Richardson) estimate, and independent checks of
an answer (equilibrium by shooting, seabed penetration)."""


from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from cable_ocp.errors import CableOCPError

if TYPE_CHECKING:
    from cable_ocp.scene import Scene

def unsupported(method: str, reason: str) -> CableOCPError:
    """The error a method raises for a scene it cannot represent (names solver.method)."""
    return CableOCPError(f"solver.method = {method!r} cannot represent this scene: {reason}")


def rising_fixed_ends(scene: Scene, method: str, why: str) -> tuple[float, float]:
    """Heights (m) of end_a and end_b for the z-parametrised methods (000, 001), which
    need both ends fixed and end_b above end_a; ``why`` cites the method's equations."""
    ea, eb = scene.end_a, scene.end_b
    if not all(ea.fixed_mask) or not all(eb.fixed_mask):
        raise unsupported(method, f"both end_a and end_b need a fully fixed position ({why})")
    za, zb = float(ea.position[2]), float(eb.position[2])  # type: ignore[arg-type]
    if not zb > za:
        raise unsupported(method, f"end_b (z = {zb} m) must lie above end_a (z = {za} m): z "
                                  "is the independent variable and the cable must rise "
                                  "monotonically from end_a to end_b")
    return za, zb


UNRESOLVED_LIMIT = 1e-2  # the robustness matrix calls 1 % off a wrong answer


def with_resolution_check(scene: Scene, solve_fn: Callable, warm_start: Any, order: float,
                          method: str) -> Any:
    """Solve at N = ``solver.intervals`` and N/2 and attach a Richardson error estimate.

    est = max(end-force change / largest tension, length change / L) / (2^order - 1).
    A converged solution whose estimate exceeds 1 % is reported as ``"unresolved"``: the
    method's equations are solved but its discretisation is too coarse for the scene, and
    calling that a solution would put a wrong answer in a table. Used by the baselines that
    carry no estimate of their own (Wang's has one built in).
    """
    sol = solve_fn(scene, warm_start)
    n = scene.solver.intervals
    if not sol.success or n < 4:
        return sol
    half = solve_fn(scene.with_overrides({"solver.intervals": n // 2}), sol)
    if not half.success:
        sol.diagnostics["error_estimate_note"] = f"N/2 solve failed: {half.message}"
        return sol
    dforce = max(np.max(np.abs(sol.force_a - half.force_a)),
                 np.max(np.abs(sol.force_b - half.force_b))) / sol.max_tension
    diff = max(float(dforce), abs(sol.length - half.length) / sol.length)
    sol.error_estimate = diff / (2.0**order - 1.0)
    sol.diagnostics["error_estimate_detail"] = {
        "method": f"Richardson, N={n} vs N={n // 2}, assumed order {order}"}
    if sol.error_estimate > UNRESOLVED_LIMIT:
        sol.status = "unresolved"
        sol.message = (f"{method}: converged, but the N/2 comparison estimates a "
                       f"{sol.error_estimate:.1e} relative error (> 1 %): increase "
                       "solver.intervals")
    return sol


def equilibrium_check(scene: Scene, sol: Any, method: str) -> Any:
    """Independent a-posteriori check of a baseline's answer: integrate the cable
    equations (:class:`~cable_ocp.statics.formulation.Formulation`, scipy's DOP853 at
    rtol 1e-10) from end_a with the method's own r(0), T(0) and L, and compare where the
    shot lands with the method's end_b. A method whose parametrisation cannot represent the
    true equilibrium (e.g. x(z) for a cable that dips below its anchor) can converge to a
    profile that is no equilibrium at all; a landing error over 1 % of L (or of the largest
    tension) marks it ``"not_equilibrium"``."""
    if not sol.success:
        return sol
    from scipy.integrate import solve_ivp

    from cable_ocp.statics.formulation import Formulation

    form = Formulation(scene)
    sc = form.scales
    lam = sol.length / sc.length
    y0 = np.concatenate([sol.position[0] / sc.length, sol.tension_vector[0] / sc.force])

    def rhs(_s: float, y: np.ndarray) -> np.ndarray:
        return np.asarray(form.rhs(y, lam, 1.0)).ravel()

    shot = solve_ivp(rhs, (0.0, 1.0), y0, method="DOP853", rtol=1e-10, atol=1e-12)
    if not shot.success:
        return sol
    yb = shot.y[:, -1]
    miss = max(float(np.max(np.abs(yb[:3] * sc.length - sol.position[-1]))) / sol.length,
               float(np.max(np.abs(yb[3:] * sc.force - sol.tension_vector[-1])))
               / sol.max_tension)
    sol.diagnostics["equilibrium_check"] = miss
    if miss > UNRESOLVED_LIMIT:
        sol.status = "not_equilibrium"
        sol.message = (f"{method}: converged, but integrating the cable equations from its "
                       f"end_a state misses its end_b by {miss:.1e} (relative): the profile is "
                       "not an equilibrium (the method's parametrisation cannot represent it)")
    return sol


def seabed_check(scene: Scene, sol: Any, method: str) -> Any:
    """Mark a method's solution that passes below a modelled seabed as a failure."""
    sb = scene.environment.seabed
    if sb is None or not sol.success:
        return sol
    from cable_ocp.physics.seabed import gap

    depth = float(-np.min(gap(sb, sol.position)))
    if depth > 1e-6 * sol.length:
        sol.status = "seabed_contact"
        sol.message = (f"{method}: the profile passes {depth:.3g} m below the seabed and this "
                       "method has no contact model")
    return sol
