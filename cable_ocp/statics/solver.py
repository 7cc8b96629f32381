"""Solving statics problems: one scene, a sweep, a session of many (the drivers).

* :func:`solve`: a scene, a problem file or a dict, by the method its ``[solver]`` names
  (:mod:`cable_ocp.statics.registry`); collocation and multiple shooting by
  :func:`solve_collocation`, which refines the mesh towards ``solver.accuracy``;
* :func:`solve_with_contact`: seabed contact at an anchored end_a switched on or off as
  the solution demands;
* :func:`sweep` and :class:`SolveSession`: many scenes in a row, each solver built once per
  scene structure and every solve warm-started, along a line from the continuation
  predictor (:mod:`cable_ocp.statics.predictor`).

The solver of one discretised line, :class:`StaticsSolver`, lives in
:mod:`cable_ocp.statics.line_solver` (importable from here too, as before).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.physics import seabed
from cable_ocp.scene import Scene, apply_overrides, load_scene, scene_from_dict
from cable_ocp.statics.checks import check_physical
from cable_ocp.statics.formulation import _structure_key, reference_length
from cable_ocp.statics.line_solver import COMPILE_FLAG, NEWTON_MAX_STEPS, StaticsSolver
from cable_ocp.statics.predictor import PREDICTOR_POINTS, predict
from cable_ocp.statics.registry import get_method, register
from cable_ocp.statics.solution import StaticsSolution

__all__ = ["COMPILE_FLAG", "NEWTON_MAX_STEPS", "PREDICTOR_POINTS", "SolveSession",
           "StaticsSolver", "can_ground", "penetration", "solve", "solve_collocation",
           "solve_with_contact", "sweep"]


def can_ground(scene: Scene) -> bool:
    """True when the scene models the seabed and end_a is fixed on it (an anchor)."""
    sb = scene.environment.seabed
    if sb is None or not all(scene.end_a.fixed_mask):
        return False
    gap = seabed.gap(sb, np.asarray(scene.end_a.position, dtype=float))[0]
    return abs(gap) <= 1e-6 * reference_length(scene)


def penetration(sol: StaticsSolution, scene: Scene) -> float:
    """Largest depth below the seabed of the computed (suspended) nodes, m (0 if none).

    Parameters
    ----------
    sol : StaticsSolution
        A solution of ``scene``.
    scene : Scene
        The scene (its seabed).
    """
    gaps = seabed.gap(scene.environment.seabed, sol.position[sol.node_offset + 1:])
    return float(max(0.0, -np.min(gaps))) if gaps.size else 0.0


def solve_with_contact(scene: Scene, get: Callable[[bool], StaticsSolver],
                       warm_start: StaticsSolution | None,
                       error_estimate: bool | None = None) -> StaticsSolution:
    """Solve, switching seabed contact at end_a on or off as the solution demands.

    Without ``[environment.seabed]`` this is a plain solve. With it: a solution that
    passes below the seabed next to an anchored end_a is re-solved with a grounded part
    (touchdown formulation); a grounded solution whose grounded length comes out negative
    is re-solved without. A result that still passes below the seabed (contact away from
    end_a, which is not modelled) is a failure, never a solution.

    Parameters
    ----------
    scene : Scene
        The scene to solve.
    get : callable
        ``get(grounded) -> StaticsSolver``: the scene's solver without or with a grounded
        part (built on first use by the caller's cache).
    warm_start : StaticsSolution or None
        A neighbouring solution (a grounded one starts the grounded solver).
    error_estimate : bool, optional
        Override ``solver.error_estimate``.
    """
    kw = {"error_estimate": error_estimate}
    grounded = bool(warm_start is not None and warm_start.node_offset and can_ground(scene))
    sol = get(grounded).solve(scene, warm_start=warm_start, **kw)
    if scene.environment.seabed is None or sol.status not in ("solved", "inaccurate"):
        return sol
    tol = 1e-6 * reference_length(scene)
    why = ""
    if not grounded and can_ground(scene) and penetration(sol, scene) > tol:
        alt = get(True).solve(scene, warm_start=sol, **kw)
        if alt.status not in ("solved", "inaccurate") or alt.grounded_length <= 0:
            alt = get(True).solve(scene, **kw)  # cold, from the catenary with touchdown
        if alt.status in ("solved", "inaccurate") and alt.grounded_length > 0:
            sol = alt
        else:
            why = f"; the solve with contact at end_a did not converge ({alt.message})"
            if len(scene.segments) > 1:
                why += ("; note that the grounded part is limited to the first segment: "
                        "contact of later segments or of a body at a joint is not modelled "
                        "yet")
    elif grounded and sol.grounded_length < 0:
        sol = get(False).solve(scene, warm_start=sol, **kw)
    depth = penetration(sol, scene) if sol.status in ("solved", "inaccurate") else 0.0
    if depth > tol:
        first = scene.segments[0].length if scene.segments else sol.length
        if sol.node_offset and sol.grounded_length >= first * (1.0 - 1e-6) \
                and len(scene.segments) > 1:
            why += ("; the grounded part reached the end of the first segment: contact of "
                    "later segments or of a body at a joint is not modelled yet")
        elif not why:
            why = ("; contact away from an anchored end_a is not modelled yet"
                   if can_ground(scene) else
                   "; end_a is not anchored on the seabed, and contact elsewhere is not "
                   "modelled yet")
        sol.status = "below_seabed"
        sol.message = f"the cable passes {depth:.3g} m below the seabed" + why
    return sol


def solve_collocation(scene: Scene, warm_start: StaticsSolution | None = None
                      ) -> StaticsSolution:
    """Solve one scene by collocation or multiple shooting, with accuracy control.

    Builds its solvers (use :class:`StaticsSolver` to reuse one across solves). Seabed
    contact is switched on where needed (:func:`solve_with_contact`). When the error
    estimate exceeds ``solver.accuracy`` and ``solver.refine`` is true, the number of
    intervals is doubled (each solve warm-started from the previous one) up to
    ``solver.max_intervals``; the diagnostics list the refinement steps.

    Parameters
    ----------
    scene : Scene
        The scene (``solver.method`` "collocation" or "multiple_shooting").
    warm_start : StaticsSolution, optional
        A neighbouring solution to start from.
    """
    t0 = time.perf_counter()
    cache: dict[tuple, StaticsSolver] = {}

    def getter(n: int) -> Callable[[bool], StaticsSolver]:
        def get(grounded: bool) -> StaticsSolver:
            if (n, grounded) not in cache:
                StaticsSolver(scene, intervals=n, cache=cache, grounded=grounded)
            return cache[(n, grounded)]
        return get

    n = scene.solver.intervals
    sol = solve_with_contact(scene, getter(n), warm_start)
    history = [(n, sol.error_estimate)]
    opts = scene.solver
    while (sol.status == "inaccurate" and opts.refine and 2 * n <= opts.max_intervals
           and not sol.diagnostics.get("algebraic_error_dominates")):
        n *= 2
        sol = solve_with_contact(scene, getter(n), sol)
        history.append((n, sol.error_estimate))
    build = sum(sv.build_time_s for sv in cache.values())
    if sol.status == "inaccurate" and opts.refine and 2 * n > opts.max_intervals:
        sol.diagnostics.setdefault("warnings", []).append(
            f"mesh refinement stopped at solver.max_intervals = {opts.max_intervals} with "
            f"the error estimate {sol.error_estimate:.1e} above solver.accuracy = "
            f"{opts.accuracy:.0e}")
    if len(history) > 1:
        sol.diagnostics["refinement"] = [
            {"intervals": k, "error_estimate": e} for k, e in history]
        sol.wall_time_s = time.perf_counter() - t0 - build
    sol.diagnostics["build_time_s"] = build
    return sol


def solve(scene: Scene | str | Path | dict[str, Any], overrides: dict[str, Any] | None = None,
          warm_start: StaticsSolution | None = None) -> StaticsSolution:
    """Solve a scene with the method its ``[solver]`` names.

    Parameters
    ----------
    scene : Scene, path or dict
        A validated scene, a TOML problem file, or a problem as a dictionary (the TOML
        tables as nested dicts, validated by :func:`cable_ocp.scene.scene_from_dict`).
    overrides : dict, optional
        Dotted-key overrides, e.g. ``{"layout.psi0_deg": 90}``.
    warm_start : StaticsSolution, optional
        A neighbouring solution to start from.

    Returns
    -------
    StaticsSolution
        Check ``status`` (``"solved"`` or why not) before using the numbers.

    Raises
    ------
    CableOCPError
        When the scene is invalid (the message names the key).
    """
    if isinstance(scene, dict):
        scene = scene_from_dict(apply_overrides(scene, overrides or {}))
    elif isinstance(scene, (str, Path)):
        scene = load_scene(scene, overrides)
    elif isinstance(scene, Scene):
        if overrides:
            scene = scene.with_overrides(overrides)
    else:
        raise CableOCPError(f"solve(scene): expected a Scene, a problem file path or a dict, "
                            f"got {type(scene).__name__}")
    return check_physical(scene, get_method(scene.solver.method)(scene, warm_start=warm_start))


class SolveSession:
    """Solve many scenes in a row, as a load-case batch does: each solver is built once per
    scene structure and kept, and each solve starts from the previous converged solution
    when the solve just before was of the same structure, falling back to a cold start when
    the warm start fails.

    Parameters
    ----------
    error_estimate : bool, optional
        Override ``solver.error_estimate`` of every scene.
    solvers : dict, optional
        The built solvers by structure, shared with other sessions (the lines of a mooring
        system: each line warm-starts from its own last solution, and lines of the same
        structure share one built solver); None: this session's own.
    """

    def __init__(self, error_estimate: bool | None = None,
                 solvers: dict[tuple, dict[tuple, StaticsSolver]] | None = None) -> None:
        self.error_estimate = error_estimate
        self._caches: dict[tuple, dict[tuple, StaticsSolver]] = {} if solvers is None \
            else solvers
        self._prev: dict[tuple, StaticsSolution] = {}
        self._last_key: tuple | None = None
        #: (value, solution) of the last solves along one line of a continuation, and the
        #: key that varies along it
        self._line: list[tuple[float, StaticsSolution]] = []
        self._line_key: str | None = None

    def solve(self, scene: Scene, warm: bool = True,
              along: tuple[str, float] | None = None) -> StaticsSolution:
        """Solve ``scene`` (any method; collocation and shooting reuse their solvers);
        ``warm=False`` starts cold (the previous solution is no neighbour of this scene:
        a warm start from far costs more than a cold one).

        ``along``: ``(key, value)``, the one key in which this scene differs from the
        last ones solved and its value (a continuation along a line of a grid, as
        :func:`sweep` does); the start is then extrapolated through up to
        :data:`PREDICTOR_POINTS` previous solutions on that line (fewer Newton steps),
        falling back to the previous solution where Newton fails from it. ``None``, or
        another key, starts a new line.

        Parameters
        ----------
        scene : Scene
            The scene to solve.
        warm : bool
            Start from the previous solution when it is of the same structure.
        along : (str, float), optional
            The key that varies along the current line and this scene's value of it.
        """
        key = (_structure_key(scene) if scene.solver.method in ("collocation",
                                                                 "multiple_shooting")
               else ("method", scene.solver.method))
        # warm only from the solve just before, of the same structure: an older solution of
        # this structure (before other structures were solved) is no neighbour, and a warm
        # start from far fails slowly (seconds) before the cold start
        prev = self._prev.get(key) if warm and key == self._last_key else None
        self._last_key = key
        if prev is None or along is None or along[0] != self._line_key:
            self._line = []
        self._line_key = None if along is None else along[0]
        start = _predicted(self._line, None if along is None else along[1], prev)
        if key[0] == "method":
            sol = solve(scene, warm_start=prev)
            if prev is not None and not sol.converged:
                sol = solve(scene)
        else:
            cache = self._caches.setdefault(key, {})

            def get(grounded: bool) -> StaticsSolver:
                n = scene.solver.intervals
                if (n, grounded) not in cache:
                    StaticsSolver(scene, cache=cache, grounded=grounded)
                return cache[(n, grounded)]

            sol = solve_with_contact(scene, get, start, self.error_estimate)
            if start is not prev and not sol.converged:
                sol = solve_with_contact(scene, get, prev, self.error_estimate)
            if prev is not None and not sol.converged:
                sol = solve_with_contact(scene, get, None, self.error_estimate)
                sol.diagnostics["start"] = "cold (the warm start failed)"
            if (sol.status == "inaccurate" and scene.solver.refine
                    and not sol.diagnostics.get("algebraic_error_dominates")):
                sol = solve_collocation(scene, warm_start=sol)
        if sol.converged:
            self._prev[key] = sol
            if along is not None and not sol.node_offset and (
                    not self._line or sol.s.shape == self._line[-1][1].s.shape):
                self._line = [*self._line[-(PREDICTOR_POINTS - 1):], (float(along[1]), sol)]
            else:
                self._line = []
        else:
            self._line = []
        return sol


def _predicted(line: list[tuple[float, StaticsSolution]], v: float | None,
               prev: StaticsSolution | None) -> StaticsSolution | None:
    """The start of a session's continuation step to ``v``: the prediction through the
    points of ``line`` (:func:`cable_ocp.statics.predictor.predict`; the last one
    ``prev``, the values distinct and none equal to ``v``), else ``prev``."""
    if prev is None or v is None or not line or line[-1][1] is not prev:
        return prev
    pts = [(x, s) for x, s in line if x != v]
    if len(pts) != len(line) or len({x for x, _ in pts}) != len(pts):
        return prev
    return predict(pts, v, prev)


def sweep(scene: Scene, key: str, values: Iterable[Any],
          error_estimate: bool | None = None) -> list[StaticsSolution]:
    """Solve ``scene`` for each value of one dotted key, warm-starting along the way.

    The solver is built once and reused while the scene structure stays the same (end
    positions, forces, a fixed length, the tension, ``layout.psi0_deg``); otherwise a new
    one is built. When the key is numeric, each point starts from a polynomial
    extrapolation through up to :data:`PREDICTOR_POINTS` previous solutions (fewer Newton
    steps), else from the previous solution; if Newton fails from the prediction, it is
    retried from the previous solution.
    A point whose error estimate misses ``solver.accuracy`` is refined like a single solve
    (:func:`solve_collocation`).

    Parameters
    ----------
    scene : Scene
        The scene at the start of the sweep.
    key : str
        The dotted key that varies (e.g. ``"layout.psi0_deg"``).
    values : iterable
        Its values, in the order solved.
    error_estimate : bool, optional
        Override ``solver.error_estimate``.

    Returns
    -------
    list of StaticsSolution
        One per value, each with ``diagnostics["sweep"]``.

    Examples
    --------
    >>> sols = sweep(load_scene("problems/dezoysa_sea_buggy.toml"), "layout.psi0_deg",
    ...              range(0, 181, 10))  # doctest: +SKIP
    """
    if scene.solver.method != "collocation":
        method = get_method(scene.solver.method)
        out: list[StaticsSolution] = []
        for v in values:
            prev = out[-1] if out and out[-1].converged else None
            sc = scene.with_overrides({key: v})
            sol = check_physical(sc, method(sc, warm_start=prev))
            sol.diagnostics["sweep"] = {"key": key, "value": v}
            out.append(sol)
        return out
    caches: dict[tuple, dict[tuple, StaticsSolver]] = {}
    out = []
    done: list[tuple[Any, tuple, StaticsSolution]] = []  # (value, structure, solution)
    for v in values:
        sc = scene.with_overrides({key: v})
        k = _structure_key(sc)
        cache = caches.setdefault(k, {})

        def get(grounded: bool, sc: Scene = sc, cache: dict = cache) -> StaticsSolver:
            n = sc.solver.intervals
            if (n, grounded) not in cache:
                StaticsSolver(sc, cache=cache, grounded=grounded)
            return cache[(n, grounded)]

        prev = done[-1][2] if done and done[-1][2].converged else None
        start = prev
        # the last points solved on this structure without seabed contact, numeric values
        pts: list[tuple[float, StaticsSolution]] = []
        for val, key_i, s_i in reversed(done):
            if (len(pts) == PREDICTOR_POINTS or key_i != k or not s_i.converged
                    or s_i.node_offset or not isinstance(val, (int, float))
                    or any(val == x for x, _ in pts)
                    or (pts and s_i.s.shape != pts[0][1].s.shape)):  # a refined point
                break
            pts.insert(0, (val, s_i))
        if prev is not None and pts and pts[-1][1] is prev and isinstance(v, (int, float)):
            start = predict(pts, v, prev)
        known = {id(x) for x in cache.values()}
        sol = solve_with_contact(sc, get, start, error_estimate)
        if start is not prev and not sol.converged:
            sol = solve_with_contact(sc, get, prev, error_estimate)
        built = [x.build_time_s for x in cache.values() if id(x) not in known]
        if built:  # this point built solvers (the first point of each structure)
            sol.diagnostics["build_time_s"] = float(sum(built))
        if sol.status == "inaccurate" and sc.solver.refine:
            # this point needs a finer mesh than the sweep's: refine it on its own (the
            # next points keep the sweep's solver and warm-start from this solution)
            sol = solve_collocation(sc, warm_start=sol)
        sol.diagnostics["sweep"] = {"key": key, "value": v}
        out.append(sol)
        done.append((v, k, sol))
    return out


# both transcriptions are solved by solve_collocation (the scene's solver.method picks one)
register("collocation", solve_collocation)
register("multiple_shooting", solve_collocation)
