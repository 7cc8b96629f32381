"""Helpers shared by the baseline methods: the unsupported-scene error, the end checks of
the z-parametrised methods, the accuracy contract (error estimates, refinement up to a
limit, ``"inaccurate"`` above ``solver.accuracy``: :func:`refine_to_accuracy`), and
independent checks of an answer (equilibrium by shooting, seabed penetration)."""


from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.interpolate import CubicSpline

from cable_ocp.errors import CableOCPError

if TYPE_CHECKING:
    from cable_ocp.scene import Scene
    from cable_ocp.statics.solution import StaticsSolution

def unsupported(method: str, reason: str) -> CableOCPError:
    """The error a method raises for a scene it cannot represent (names solver.method).

    Parameters
    ----------
    method : str
        The method's ``solver.method`` name, quoted in the message.
    reason : str
        What about the scene the method cannot represent, appended to the message.

    Returns
    -------
    CableOCPError
        The error (returned, not raised: the caller raises it).
    """
    return CableOCPError(f"solver.method = {method!r} cannot represent this scene: {reason}")


def rising_fixed_ends(scene: Scene, method: str, why: str) -> tuple[float, float]:
    """Heights (m) of end_a and end_b for the z-parametrised methods (Wang et al. (1993),
    Chucheepsakul (1991)), which
    need both ends fixed and end_b above end_a; ``why`` cites the method's equations.

    Parameters
    ----------
    scene : Scene
        The scene; both ends must have all three position components fixed and end_b
        must lie strictly above end_a, else :func:`unsupported` is raised.
    method : str
        The method's ``solver.method`` name, for the error message.
    why : str
        The method's reason for fixed ends (its equations), for the error message.
    """
    ea, eb = scene.end_a, scene.end_b
    if not all(ea.fixed_mask) or not all(eb.fixed_mask):
        raise unsupported(method, f"both end_a and end_b need a fully fixed position ({why})")
    za, zb = float(ea.position[2]), float(eb.position[2])  # type: ignore[arg-type]
    if not zb > za:
        raise unsupported(method, f"end_b (z = {zb} m) must lie above end_a (z = {za} m): z "
                                  "is the independent variable and the cable must rise "
                                  "monotonically from end_a to end_b")
    return za, zb


#: the independent shooting check's threshold (relative landing error): a gross-error
#: detector, not the accuracy test (that is the error estimate against ``solver.accuracy``).
#: Shooting the cable equations from a method's end_a state carries that state's error
#: along the line (1-2x the estimate on the benchmark scenes, more on long taut lines,
#: where shooting is ill-conditioned), so a threshold at ``solver.accuracy`` would reject
#: right answers; an answer that is no equilibrium at all misses by far more.
EQUILIBRIUM_LIMIT = 1e-2


@dataclass
class Estimate:
    """A method's a-posteriori error estimate at one resolution.

    Attributes
    ----------
    value : float
        Relative error estimate (-): the larger of the end-force error over the largest
        tension and the position (and length) error over the length; ``inf`` when no
        estimate could be formed (``detail["note"]`` says why).
    detail : dict
        ``method`` (how), ``observed_order``, ``force_N``, ``position_m``, ``algebraic``
        and any notes; goes to ``diagnostics["error_estimate_detail"]``.
    order : float
        The order used in the Richardson factor (observed, clipped), or nan.
    """

    value: float
    detail: dict[str, Any] = field(default_factory=dict)
    order: float = math.nan


def compare(fine: StaticsSolution, coarse: StaticsSolution, param: str = "s"
            ) -> tuple[float, float, float]:
    """Differences between two solutions of one scene at different resolutions.

    Returns (end-force difference, N; position difference, m; largest tension, N): the
    largest component difference of the forces at both ends, and the largest position
    difference at the coarse solution's nodes (the fine solution interpolated there by a
    cubic spline: exact where the nodes are shared) or of the lengths. ``param`` says how nodes are
    matched: ``"s"`` by s/L (methods discretised in arc length), ``"z"`` by the height
    above end_a (methods discretised in z: Wang's RK4 steps, the FEM's elements).

    Parameters
    ----------
    fine : StaticsSolution
        The solution at the finer resolution; interpolated at the coarse one's nodes.
        Its largest tension is the third value returned.
    coarse : StaticsSolution
        The solution at the coarser resolution.
    param : {"s", "z"}, default "s"
        How nodes are matched (any value other than ``"z"`` matches by s/L).
    """
    dforce = max(float(np.max(np.abs(fine.force_a - coarse.force_a))),
                 float(np.max(np.abs(fine.force_b - coarse.force_b))))

    def par(sol: StaticsSolution) -> np.ndarray:
        if param == "z":
            return sol.position[:, 2] - sol.position[0, 2]
        return sol.s / sol.length

    pf, pc = par(fine), par(coarse)
    u, idx = np.unique(pf, return_index=True)
    if u.size >= 4:
        # a cubic spline: exact at shared nodes (nested meshes), and O(h^4) between them
        # where the meshes are not nested (solve_bvp's adaptive meshes)
        at = CubicSpline(u, fine.position[idx], axis=0)(np.clip(pc, u[0], u[-1]))
    else:
        at = np.stack([np.interp(pc, u, fine.position[idx, k]) for k in range(3)], axis=1)
    dpos = max(float(np.max(np.abs(at - coarse.position))), abs(fine.length - coarse.length))
    return dforce, dpos, float(fine.max_tension)


def observed_order(rel_fine: float, rel_coarse: float, low: float, high: float,
                   fallback: float) -> float:
    """log2(rel_coarse / rel_fine) clipped to [low, high]; ``fallback`` when either
    difference is zero or not finite (nothing to observe: e.g. an exact method).

    Parameters
    ----------
    rel_fine : float
        Relative difference (-) between the finer pair of solutions (e.g. N and N/2).
    rel_coarse : float
        Relative difference (-) between the coarser pair, one halving of the resolution
        further (e.g. N/2 and N/4).
    low, high : float
        Clip range of the order (-).
    fallback : float
        The order (-) returned when either difference is zero or not finite (not
        clipped).
    """
    if rel_fine > 0 and rel_coarse > 0 and math.isfinite(rel_fine) and math.isfinite(rel_coarse):
        return float(np.clip(math.log2(rel_coarse / rel_fine), low, high))
    return fallback


class MeshCache:
    """Successful solutions of one scene by resolution ``n``, for the refinement loop and
    the estimate's coarser solves.

    ``solve(n, warm)`` solves at ``n`` (from ``warm`` when given); :meth:`solve_at` reuses
    a cached cold solution, :meth:`get` solves a missing coarser resolution warm-started
    from the next finer one it has (None when that fails).
    """

    def __init__(self, solve: Callable[[int, StaticsSolution | None], StaticsSolution]
                 ) -> None:
        self._solve = solve
        self.solutions: dict[int, StaticsSolution] = {}

    def solve_at(self, n: int, warm: StaticsSolution | None) -> StaticsSolution:
        """The solution at resolution ``n``: the cached one when no warm start is given
        and ``n`` was solved, else a new solve (cached when it succeeds).

        Parameters
        ----------
        n : int
            The resolution (elements, segments or steps: the method's unit).
        warm : StaticsSolution or None
            Warm start passed to the method's solve; None: reuse the cached solution at
            ``n`` if there is one, else solve cold.
        """
        if warm is None and n in self.solutions:
            return self.solutions[n]
        sol = self._solve(n, warm)
        if sol.success:
            self.solutions[n] = sol
        return sol

    def get(self, n: int) -> StaticsSolution | None:
        if n not in self.solutions:
            finer = [k for k in self.solutions if k > n]
            self.solve_at(n, self.solutions[min(finer)] if finer else None)
        return self.solutions.get(n)


def richardson_coarser(n: int, sol: StaticsSolution, get: Callable[[int], StaticsSolution | None],
                       param: str, low: float, high: float, unit: str,
                       min_coarse: int = 4) -> Estimate:
    """Richardson estimate of the N solution from the N/2 and N/4 solutions of the method.

    With d1 = |x_N - x_{N/2}| and d2 = |x_{N/2} - x_{N/4}| (end forces over the largest
    tension, positions and length over the length, :func:`compare`), the observed order is
    q = log2(d2/d1) clipped to [``low``, ``high``], and the estimate is d1 / (2^q - 1), as
    the collocation solver does (:func:`cable_ocp.statics.error_estimate.richardson_estimate`).
    With 2 <= N < 4, or when the N/4 solve fails, q = ``high`` (the nominal order) from two
    solutions; below N = 2, or when the N/2 solve fails, no estimate (``inf``). When N/4
    is below ``min_coarse`` units (too coarse to show the order: on 10/5/2 elements the
    FEM's order looked like 1.6 and the estimate was 2.8x too small, Huang's method on the
    high-speed tow 3.8x), q = ``low`` from two solutions, the conservative end of the range.
    ``get(m)`` returns the method's (success) solution on m units, or None.

    Parameters
    ----------
    n : int
        The resolution N of ``sol`` (in ``unit``).
    sol : StaticsSolution
        The method's solution on N units, the one estimated.
    get : callable
        ``get(m) -> StaticsSolution or None``: the method's successful solution on m
        units (e.g. :meth:`MeshCache.get`), or None when that solve fails.
    param : {"s", "z"}
        How nodes are matched in :func:`compare`.
    low, high : float
        Clip range of the observed order (-); ``high`` is the nominal order.
    unit : str
        Name of the resolution's unit in messages (e.g. ``"elements"``).
    min_coarse : int, default 4
        Fewest units N/4 from which the order is observed; below it (N >= 4), q =
        ``low``.
    """
    if n < 2:
        return Estimate(math.inf, {"note": f"no estimate below 2 {unit}"})
    half = get(n // 2)
    if half is None:
        return Estimate(math.inf, {"note": f"the solve on N/2 = {n // 2} {unit} failed"})
    f1, p1, tmax = compare(sol, half, param)
    rel1 = max(f1 / tmax, p1 / sol.length)
    coarse_ok = n // 4 >= min_coarse
    quarter = get(n // 4) if n >= 4 and coarse_ok else None
    how = f"Richardson, N = {n}/{n // 2}"
    if n >= 4 and not coarse_ok:
        q = low
        how += (f" {unit}, order {q:g} (N/4 = {n // 4} {unit} is below {min_coarse}: too "
                "coarse to observe the order)")
    elif quarter is not None:
        f2, p2, _ = compare(half, quarter, param)
        q = observed_order(rel1, max(f2 / tmax, p2 / sol.length), low, high, high)
        how += f"/{n // 4} {unit}, observed order {q:.2f} (clipped to [{low:g}, {high:g}])"
    else:
        q = high
        how += f" {unit}, assumed order {q:g} (no N/4 solution)"
    factor = 1.0 / (2.0**q - 1.0)
    return Estimate(factor * rel1, {"method": how, "observed_order": q,
                                    "force_N": factor * f1, "position_m": factor * p1}, q)


def coarser_estimate(cache: MeshCache, param: str, low: float, high: float, unit: str,
                     algebraic: Callable[[StaticsSolution], float]
                     ) -> Callable[[int, StaticsSolution], Estimate]:
    """The ``estimate`` of :func:`refine_to_accuracy` for a method refined on ``cache``:
    :func:`richardson_coarser` from its N/2 and N/4 solutions plus the iterate's algebraic
    error ``algebraic(sol)`` (relative, -; also kept as ``detail["algebraic"]``).

    Parameters
    ----------
    cache : MeshCache
        The method's solutions by resolution; each estimated solution is stored in it.
    param : {"s", "z"}
        How nodes are matched (:func:`compare`).
    low, high : float
        Clip range of the observed order (-); ``high`` is the nominal order.
    unit : str
        Name of the resolution's unit in messages (e.g. ``"elements"``).
    algebraic : callable
        ``algebraic(sol) -> float``: the solution's algebraic error, added to the
        estimate.
    """
    def estimate(n: int, sol: StaticsSolution) -> Estimate:
        cache.solutions[n] = sol
        est = richardson_coarser(n, sol, cache.get, param, low, high, unit)
        alg = algebraic(sol)
        est.detail["algebraic"] = alg
        est.value += alg
        return est

    return estimate


def finer_within_max_intervals(scene: Scene, top_order: float, unit: str
                               ) -> Callable[[int, Estimate], tuple[int | None, str]]:
    """The ``finer`` of :func:`refine_to_accuracy` for a method whose only limit is
    ``solver.max_intervals``: :func:`double_within` it.

    Parameters
    ----------
    scene : Scene
        The statics problem: its ``solver.accuracy`` and ``solver.max_intervals``.
    top_order : float
        The method's highest convergence order (-), for the prediction.
    unit : str
        Name of the resolution's unit in messages (e.g. ``"segments"``).
    """
    def finer(n: int, est: Estimate) -> tuple[int | None, str]:
        lim = scene.solver.max_intervals
        return double_within(n, est, scene.solver.accuracy, lim,
                             f"solver.max_intervals = {lim}", top_order, unit)

    return finer


def refine_to_accuracy(scene: Scene, method: str, start: Any,
                       solve_at: Callable[[Any, StaticsSolution | None], StaticsSolution],
                       estimate: Callable[[Any, StaticsSolution], Estimate],
                       finer: Callable[[Any, Estimate], tuple[Any, str]],
                       warm_start: StaticsSolution | None = None,
                       describe: Callable[[Any], dict[str, Any]] | None = None,
                       label: Callable[[Any], str] = str,
                       retry_cold: bool = True) -> StaticsSolution:
    """The accuracy contract of ``solver.accuracy``, shared by every baseline method.

    Solve at the resolution ``start``; unless ``solver.error_estimate`` is false, attach
    the method's error estimate and, while it exceeds ``solver.accuracy`` and
    ``solver.refine`` is true, solve again at ``finer(level, estimate)`` (warm-started
    from the previous level) until the estimate meets the accuracy or ``finer`` returns
    ``(None, why)`` (the method's limit). Refinement also stops when a refined solve fails
    (retried once cold if ``retry_cold``) or when refining did not lower the estimate (the
    discretisation is not converging on this scene). A result whose estimate still exceeds
    the accuracy (or that has no estimate) is reported as ``"inaccurate"``, with the
    estimate, the accuracy and what stopped the refinement in the message and in
    ``diagnostics["warnings"]``;
    ``"solved"`` means estimate <= ``solver.accuracy``. ``diagnostics["refinement"]``
    lists the levels tried (``wall_time_s`` then covers all of them and their estimates),
    ``describe(level)`` gives the ``diagnostics["mesh"]`` entry and ``label(level)`` names
    a level in messages (e.g. "40 segments").

    Parameters
    ----------
    scene : Scene
        The scene; its ``solver.accuracy``, ``solver.error_estimate`` and
        ``solver.refine`` set the contract.
    method : str
        The method's ``solver.method`` name, for messages.
    start : object
        The first resolution level (a number of intervals, or solve_bvp's tolerance).
    solve_at : callable
        ``solve_at(level, warm) -> StaticsSolution``: the method's solve at ``level``
        from the warm start ``warm`` (None: cold).
    estimate : callable
        ``estimate(level, sol) -> Estimate``: the method's error estimate of ``sol``.
    finer : callable
        ``finer(level, estimate) -> (next_level, why)``: the next level, or
        ``(None, why)`` at the method's limit (``why`` goes into the message).
    warm_start : StaticsSolution, optional
        Warm start of the first solve.
    describe : callable, optional
        ``describe(level) -> dict``, the ``diagnostics["mesh"]`` entry of a level;
        default ``{"intervals": level}``.
    label : callable, default str
        ``label(level) -> str``, a level's name in messages.
    retry_cold : bool, default True
        Retry a failed refined solve once from a cold start.

    Returns
    -------
    StaticsSolution
        The last level that succeeded (or the first level's failed solve), with
        ``error_estimate`` and ``diagnostics["error_estimate_detail"]`` set (unless the
        first solve failed or ``solver.error_estimate`` is false); ``"inaccurate"`` when
        the estimate exceeds the accuracy.
    """
    opts = scene.solver
    describe = describe or (lambda level: {"intervals": level})
    t0 = time.perf_counter()
    level = start
    sol = solve_at(level, warm_start)
    sol.diagnostics["mesh"] = describe(level)
    if not sol.success or not opts.error_estimate:
        return sol
    est = estimate(level, sol)
    history = [{**describe(level), "error_estimate": est.value}]
    why = ""
    while not est.value <= opts.accuracy:
        if not opts.refine:
            why = "solver.refine = false"
            break
        nxt, why = finer(level, est)
        if nxt is None:
            break
        new = solve_at(nxt, sol)
        if not new.success and retry_cold:
            cold = solve_at(nxt, None)
            new = cold if cold.success else new
        if not new.success:
            why = (f"the refined solve at {label(nxt)} did not succeed "
                   f"({new.status}: {new.message})")
            break
        new_est = estimate(nxt, new)
        history.append({**describe(nxt), "error_estimate": new_est.value})
        better = new_est.value < est.value
        level, sol, est = nxt, new, new_est
        sol.diagnostics["mesh"] = describe(level)
        if not better and not est.value <= opts.accuracy:
            why = (f"refining to {label(level)} did not lower the estimate "
                   f"({history[-2]['error_estimate']:.1e} -> {est.value:.1e}): the "
                   "discretisation does not converge on this scene")
            break
    sol.error_estimate = est.value
    sol.diagnostics["error_estimate_detail"] = est.detail
    if len(history) > 1:
        sol.diagnostics["refinement"] = history
        sol.wall_time_s = time.perf_counter() - t0  # every level and estimate
    if not est.value <= opts.accuracy:
        if math.isfinite(est.value):
            what = (f"the error estimate {est.value:.1e} exceeds solver.accuracy = "
                    f"{opts.accuracy:.0e}")
        else:
            what = (f"there is no error estimate ({est.detail.get('note', 'not available')}),"
                    f" so solver.accuracy = {opts.accuracy:.0e} is not established")
        sol.status = "inaccurate"
        sol.message = (f"{method}: converged on {label(level)}, but {what}; refinement "
                       f"stopped: {why}")
        sol.diagnostics.setdefault("warnings", []).append(
            f"refinement stopped on {label(level)} ({why}): {what}")
    else:
        sol.message += f"; error estimate {est.value:.1e} <= solver.accuracy"
    return sol


def double_within(n: int, est: Estimate, accuracy: float, limit: int, limit_text: str,
                  top_order: float, unit: str) -> tuple[int | None, str]:
    """Next resolution 2N for :func:`refine_to_accuracy`, or None and why.

    None when 2N exceeds ``limit`` (``limit_text`` names it), or when even the method's
    highest order ``top_order`` predicts that ``limit`` cannot reach the accuracy:
    N (estimate / accuracy)^(1/top_order) > limit (doubling towards it would only cost
    time; the message gives the predicted N).

    Parameters
    ----------
    n : int
        The current resolution N (in ``unit``).
    est : Estimate
        The error estimate at N; its ``value`` (relative, -) predicts the N needed and
        its ``order`` is quoted in the message.
    accuracy : float
        The accuracy to reach (``solver.accuracy``, relative, -).
    limit : int
        Largest resolution allowed (in ``unit``).
    limit_text : str
        What sets ``limit``, for the message (e.g. ``"solver.max_intervals = 640"``).
    top_order : float
        The method's highest convergence order (-), for the prediction.
    unit : str
        Name of the resolution's unit in messages (e.g. ``"elements"``).
    """
    if 2 * n > limit:
        return None, f"N = {n} {unit}, and 2N would exceed {limit_text}"
    if math.isfinite(est.value) and est.value > 0:
        need = n * (est.value / accuracy) ** (1.0 / top_order)
        if need > limit:
            return None, (f"even at this method's highest order {top_order:g} (observed "
                          f"{est.order:.2f}) reaching it needs about N = {need:.2g} {unit}, "
                          f"beyond {limit_text}")
    return 2 * n, ""


def equilibrium_check(scene: Scene, sol: Any, method: str) -> Any:
    """Independent a-posteriori check of a baseline's answer: integrate the cable
    equations (:class:`~cable_ocp.statics.formulation.Formulation`, scipy's DOP853 at
    rtol 1e-10) from end_a with the method's own r(0), T(0) and L, and compare where the
    shot lands with the method's end_b. A method whose parametrisation cannot represent the
    true equilibrium (e.g. x(z) for a cable that dips below its anchor) can converge to a
    profile that is no equilibrium at all; a landing error over ``EQUILIBRIUM_LIMIT`` (1 %)
    of L (or of the largest tension) marks it ``"not_equilibrium"``.

    Parameters
    ----------
    scene : Scene
        The scene solved (its equations are rebuilt here, the current at full scale).
    sol : StaticsSolution
        The method's answer, checked only when it succeeded; ``status``, ``message`` and
        ``diagnostics["equilibrium_check"]`` (the relative landing error, -) are set in
        place, and it is returned.
    method : str
        The method's ``solver.method`` name, for the message.
    """
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
    if miss > EQUILIBRIUM_LIMIT:
        sol.status = "not_equilibrium"
        sol.message = (f"{method}: converged, but integrating the cable equations from its "
                       f"end_a state misses its end_b by {miss:.1e} (relative): the profile is "
                       "not an equilibrium (the method's parametrisation cannot represent it)")
    return sol


def seabed_check(scene: Scene, sol: Any, method: str) -> Any:
    """Mark a method's solution that passes below a modelled seabed as a failure.

    Parameters
    ----------
    scene : Scene
        The scene solved; only a scene with ``[environment.seabed]`` is checked.
    sol : StaticsSolution
        The method's answer, checked only when it succeeded; a penetration deeper than
        1e-6 of its length (m) makes it ``"seabed_contact"`` in place, and it is returned.
    method : str
        The method's ``solver.method`` name, for the message.
    """
    sb = scene.environment.seabed
    if sb is None or not sol.success:
        return sol
    depth = float(-np.min(sb.gap(sol.position)))
    if depth > 1e-6 * sol.length:
        sol.status = "seabed_contact"
        sol.message = (f"{method}: the profile passes {depth:.3g} m below the seabed and this "
                       "method has no contact model")
    return sol
