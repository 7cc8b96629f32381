"""Build once, solve many: the statics solver for one scene structure.

A :class:`StaticsSolver` builds the collocated residual G(w, p) = 0 once, with its sparse
Jacobian and the Newton step assembled per collocation interval
(:mod:`cable_ocp.statics.newton`), and solves it by Newton's method with a backtracking
line search on |G| (one CasADi call per step, on preallocated buffers):

* warm start (a neighbouring solution, e.g. the previous point of a sweep, or a
  prediction from the last points): Newton; if it fails, IPOPT from the same start;
* cold start (the drag-free catenary or another guess): Newton; only if that fails, IPOPT
  (``nlpsol``, a square system with zero objective, built on first use) from the same
  guess, then a ramp of the current from 0 to its value (Huang (1992), section 2.5), and
  the diagnostics say which did it.

The built functions are kept on disk (:mod:`cable_ocp.statics.cache`) so that another
process solving a scene of the same structure loads them instead of building them.

Mesh points on the drag's kinks (``solver.mesh``, :mod:`cable_ocp.statics.kinks`): the
interval widths are parameters of the built functions, so Newton moves the mesh onto the
kinks of its iterate as it converges, at no build cost (cold solves and starts from
another solver's solution; a warm start from this solver's own solution keeps its mesh
unless ``solver.mesh = "tracking"``).

Every solution is checked by evaluating the residual at the returned point; only a
residual within tolerance is reported as ``"solved"``.

The a-posteriori error estimate re-solves on N/2 and N/4 intervals (warm-started from the
fine solution) and applies Richardson's formula with the observed order (see
:meth:`StaticsSolver._estimate_error`).
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable, Iterable
from dataclasses import replace
from pathlib import Path
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import sparse_lu
from cable_ocp.numerics.compile import compile_function, is_compiled
from cable_ocp.physics import seabed
from cable_ocp.physics.drag import line_drag_factors
from cable_ocp.scene import Scene, SolverOptions, apply_overrides, load_scene, scene_from_dict
from cable_ocp.statics import cache as disk_cache
from cable_ocp.statics import kinks as kink_points
from cable_ocp.statics.checks import check_physical
from cable_ocp.statics.collocation import Collocation, Mesh
from cable_ocp.statics.formulation import (
    NX,
    P_CURRENT,
    P_END_A,
    P_END_B,
    Formulation,
    _structure_key,
    reference_length,
)
from cable_ocp.statics.initial_guess import initial_guess, touchdown_guess
from cable_ocp.statics.newton import (
    LINEAR_SOLVER,
    Kernel,
    NewtonResult,
    chord_newton,
    jacobian_functions,
    newton,
)
from cable_ocp.statics.registry import get_method, register
from cable_ocp.statics.shooting import MultipleShooting
from cable_ocp.statics.solution import StaticsSolution

__all__ = ["StaticsSolver", "solve", "sweep"]

_CONTINUATION_STEPS = (0.0, 0.1, 0.25, 0.5, 0.75, 1.0)
#: the C compiler's optimisation flag for the compiled Newton kernel
COMPILE_FLAG = "-O2"
#: most Newton steps per attempt (warm and cold; ``solver.max_iterations`` is IPOPT's)
NEWTON_MAX_STEPS = 30


class StaticsSolver:
    """Collocation (or multiple-shooting) solver for every scene sharing ``scene``'s structure.

    ``scene.solver.method`` picks the transcription: ``"collocation"`` (default) or
    ``"multiple_shooting"`` (:mod:`cable_ocp.statics.shooting`).

    Parameters
    ----------
    scene : Scene
        Validated scene; its ``solver`` options fix the mesh (``intervals``, ``degree``,
        ``scheme``) and tolerance unless overridden here.
    intervals, degree : int, optional
        Override the mesh.
    scheme : {"legendre", "radau"}, optional
        Override the collocation points.
    cache : dict, optional
        Solvers of the same scene on other meshes, keyed by (intervals, grounded); shared
        so that the error estimate, the refinement and the contact switch build each once.
    grounded : bool
        Seabed contact at end_a: the cable lies on the seabed from the anchor for an
        unknown length and lifts off tangentially (:mod:`cable_ocp.physics.seabed`).
    cold : {"newton", "ipopt"}
        How a solve without a warm start begins: Newton with a line search, IPOPT only if
        it fails (default); or IPOPT directly (as before Newton-first cold solves).

    Notes
    -----
    Parameters that may change between :meth:`solve` calls without a rebuild: end
    positions and forces, the fixed length, the prescribed tension and the current scale.
    Anything else (cable properties, the current profile, which components are fixed)
    changes the equations: build a new solver (``sweep`` does this automatically).
    """

    def __init__(self, scene: Scene, intervals: int | None = None, degree: int | None = None,
                 scheme: str | None = None, cache: dict[tuple, StaticsSolver] | None = None,
                 grounded: bool = False, cold: str = "newton"):
        if cold not in ("newton", "ipopt"):
            raise CableOCPError(f"cold = {cold!r}: valid are 'newton' and 'ipopt'")
        t0 = time.perf_counter()
        self.cold = cold
        opts = scene.solver
        self.scene = scene
        self.form = Formulation(scene)
        self.grounded = grounded
        transcription = MultipleShooting if opts.method == "multiple_shooting" else Collocation
        self.coll = transcription(self.form, intervals or opts.intervals, degree or opts.degree,
                                  scheme or opts.scheme, grounded=grounded)
        self.tol = opts.tolerance
        #: mesh points on the kinks of the drag (``solver.mesh = "kinks"`` or
        #: ``"tracking"``; collocation of order > 4 with a current): cold solves and
        #: solves from another solver's solution fit the mesh to the kinks
        self.fit_kinks = (opts.mesh in ("kinks", "tracking") and type(self.coll) is Collocation
                          and scene.environment.current is not None
                          and self.coll.mesh.order > 4)
        #: warm solves from this solver's own solutions move the mesh with the kinks too
        #: (``"tracking"``; with ``"kinks"`` they keep their start's mesh)
        self.track_kinks = self.fit_kinks and opts.mesh == "tracking"
        self._switches = kink_points.Switches(scene)
        self._lbx = -np.inf * np.ones(self.coll.n_w)
        if self.coll.free_length:
            self._lbx[self.coll.i_lam] = 1e-6
        self._ubx = np.inf * np.ones(self.coll.n_w)
        if grounded and self.form.segmented:
            # the grounded part stays on the first segment (scaled lengths)
            self._lbx[self.coll.i_g] = 0.0
            self._ubx[self.coll.i_g] = (1.0 - 1e-6) * scene.segments[0].length \
                / self.form.scales.length
        self._ipopt_fn: ca.Function | None = None
        self._sensitivity: ca.Function | None = None
        # solvers of the same scene on other meshes (by number of intervals), shared by the
        # error estimate and the mesh refinement so that no mesh is built twice
        self._cache = {} if cache is None else cache
        self._cache[(self.coll.mesh.intervals, grounded)] = self
        #: identifies the unknowns this solver produced (a warm start from its own
        #: solution skips the interpolation onto the mesh)
        self._token = object()
        #: where the Newton functions came from: "built" or "disk cache"
        self.build_source = "built"
        #: the Newton kernel runs compiled C (``solver.compile = "auto"`` with a compiler)
        self.compiled = False
        self._late_build_s = 0.0  # IPOPT, built on first use: wall and CPU seconds
        self._late_build_cpu_s = 0.0
        self._gj, self._kernel = self._newton_functions()
        self.build_time_s = time.perf_counter() - t0

    def _cache_structure(self, extra: tuple = (), blocks: bool = False) -> str:
        """Text of everything the built functions depend on (the on-disk cache's key):
        the structure without the solver options that do not enter the equations, the
        scales, the transcription and its mesh. ``blocks``: the key of the collocation
        interval functions, which do not depend on the numbers of intervals (their
        widths are parameters), so that the meshes of the error estimate and of the
        refinement share one entry."""
        opts = self.scene.solver
        key = tuple(x for x in self.form.key if not isinstance(x, SolverOptions))
        mesh = self.coll.mesh.uniform if isinstance(self.coll.mesh, Mesh) else self.coll.mesh
        n_w: int | None = self.coll.n_w
        if blocks and isinstance(mesh, Mesh):
            mesh = replace(mesh, intervals=0, segments=tuple(0 for _ in mesh.segments))
            n_w = None
        return repr((key, ("smoothing", opts.smoothing, "vertical_blend", opts.vertical_blend),
                     self.form.scales, self.form.moment_scale, type(self.coll).__name__,
                     mesh, self.grounded, n_w, LINEAR_SOLVER, *extra))

    def _newton_functions(self) -> tuple[ca.Function, Kernel]:
        """``GJ`` and the buffered Newton kernel. The transcription's block functions (the
        SX parts, whose size does not grow with the mesh) come from the on-disk cache or
        are built; the residual, its Jacobian and the Newton step are assembled from them."""
        n_w, n_p = self.coll.n_w, self.coll.n_p
        structure = self._cache_structure()
        key = self._cache_structure(blocks=True)
        stored = disk_cache.load(key, "blocks")
        if stored is not None and self.coll.set_block_functions(
                [stored[f"f{i}"] for i in range(len(stored))]):
            self.build_source = "disk cache"
        else:
            fns = self.coll.block_functions()
            disk_cache.save(key, "blocks", {f"f{i}": f for i, f in enumerate(fns)})
        g_fn = self.coll.residual
        gj, step = jacobian_functions(self.coll.blocks, n_w, n_p)
        if self.scene.solver.compile == "auto":
            kernel = self._compiled_kernel(structure, gj)
            if kernel is not None:
                return gj, kernel
        return gj, Kernel(g_fn, step)

    def _compiled_kernel(self, structure: str, gj: ca.Function) -> Kernel | None:
        """The Newton kernel compiled to C (``solver.compile = "auto"``), or None when it
        cannot be compiled (no compiler, compiling off, an unwritable cache folder).

        The residual G and ``GJ`` (G and its sparse Jacobian) are compiled; the Jacobian
        is factorised by a sparse LU whose factors and pivot order are kept
        (:mod:`cable_ocp.numerics.sparse_lu`), so that warm solves take chord steps
        (:func:`cable_ocp.statics.newton.chord_newton`). The libraries are named by the
        full cache key (versions, sources, structure, mesh): a cached library is loaded
        without generating its code.
        """
        if not sparse_lu.available():
            return None
        key = disk_cache.entry_key(structure, "compiled newton kernel")
        gj_c = compile_function(gj, COMPILE_FLAG, key=key, name=gj.name())
        if not is_compiled(gj_c):
            return None
        g_fn = compile_function(self.coll.residual, COMPILE_FLAG, key=key,
                                name=self.coll.residual.name())
        if not is_compiled(g_fn):
            return None
        self.compiled = True
        return Kernel(g_fn, gj_fn=gj_c, lu=sparse_lu.SparseLU(gj.sparsity_out(1)))

    @property
    def _ipopt(self) -> ca.Function:
        """IPOPT on the square system (zero objective), built (or loaded) on first use."""
        if self._ipopt_fn is None:
            t0, c0 = time.perf_counter(), time.process_time()
            opts = self.scene.solver
            structure = self._cache_structure(("ipopt", opts.tolerance, opts.max_iterations))
            fns = disk_cache.load(structure, "ipopt")
            if fns is not None and "ipopt" in fns:
                self._ipopt_fn = fns["ipopt"]
            else:
                w = ca.MX.sym("w", self.coll.n_w)
                p = ca.MX.sym("p", self.coll.n_p)
                g = self.coll.residual(w, p)
                self._ipopt_fn = ca.nlpsol("statics_ipopt", "ipopt", {
                    "x": w, "p": p, "f": 0, "g": g}, {
                    "print_time": False,
                    "error_on_fail": False,
                    "ipopt.print_level": 0,
                    "ipopt.sb": "yes",
                    "ipopt.tol": self.tol,
                    "ipopt.constr_viol_tol": self.tol,
                    "ipopt.max_iter": opts.max_iterations,
                    "ipopt.nlp_scaling_method": "none",
                    # square system: the primal step is fixed by the constraint Jacobian
                    # alone, so the Lagrangian Hessian buys nothing here and costs build
                    # and evaluation time
                    "ipopt.hessian_approximation": "limited-memory",
                    # the unknowns are already O(1); MUMPS' own scaling of this
                    # zero-Hessian KKT system made its fill-in explode at N = 320, d = 5
                    # (>1 GB, no progress)
                    "ipopt.mumps_scaling": 0,
                })
                disk_cache.save(structure, "ipopt", {"ipopt": self._ipopt_fn})
            dt = time.perf_counter() - t0
            self._late_build_s += dt
            self._late_build_cpu_s += time.process_time() - c0
            self.build_time_s += dt
        return self._ipopt_fn

    # -- public -------------------------------------------------------------------------
    @property
    def mesh(self):  # noqa: ANN201 - Mesh
        """The collocation mesh (of the last solve)."""
        return self.coll.mesh

    def params(self, scene: Scene | None = None, current_scale: float = 1.0,
               mesh: Mesh | None = None) -> np.ndarray:
        """The residual's parameter vector for ``scene`` (default the solver's) on
        ``mesh`` (default the current one): :meth:`Formulation.params` and the interval
        widths (:meth:`Collocation.params`)."""
        return self.coll.params(self.form.params(self.scene if scene is None else scene,
                                                 current_scale), mesh)

    def solve(self, scene: Scene | None = None, warm_start: StaticsSolution | None = None,
              error_estimate: bool | None = None, current_scale: float = 1.0
              ) -> StaticsSolution:
        """Solve ``scene`` (default: the one the solver was built for).

        Parameters
        ----------
        scene : Scene, optional
            A scene with the same structure (see class notes).
        warm_start : StaticsSolution, optional
            A neighbouring solution; Newton is tried first from it.
        error_estimate : bool, optional
            Compute the a-posteriori error estimate (default: ``scene.solver.error_estimate``).
        current_scale : float
            Multiplier on the current (homotopy parameter), 1 = as specified.

        Returns
        -------
        StaticsSolution
            Check ``success`` before use: a profile above the surface or below an
            unmodelled seabed is not a success (:func:`cable_ocp.statics.checks.check_physical`).
        """
        scene = self.scene if scene is None else scene
        sol = self._solve(scene, warm_start, error_estimate, current_scale)
        return check_physical(scene, sol)

    def _solve(self, scene: Scene, warm_start: StaticsSolution | None = None,
               error_estimate: bool | None = None, current_scale: float = 1.0
               ) -> StaticsSolution:
        """:meth:`solve` without the physical check (used for the coarse meshes too)."""
        if scene is not self.scene and _structure_key(scene) != self.form.key:
            raise CableOCPError(
                "this solver was built for another scene structure; build a new StaticsSolver "
                "(only end values, a fixed length, the tension and the current scale may change)"
            )
        p_form = self.form.params(scene, current_scale)
        diag: dict[str, Any] = {"method": scene.solver.method, "mesh": {
            "intervals": self.mesh.intervals, "degree": self.mesh.degree,
            "scheme": self.mesh.scheme, "order": self.mesh.order}, "terms": list(self.form.terms)}
        if getattr(self.mesh, "segments", ()):
            diag["mesh"]["segments"] = list(self.mesh.segments)  # intervals per segment
        t0, c0 = time.perf_counter(), time.process_time()
        late0, late0_cpu = self._late_build_s, self._late_build_cpu_s
        g_end: np.ndarray | None = None
        kappa = math.nan  # Newton's quadratic-convergence constant, for the re-solve
        moves = 0  # moves of the mesh onto the kinks during Newton's iteration
        self._checked: np.ndarray | None = None  # kinks found by Newton's moving mesh
        estimate = scene.solver.error_estimate if error_estimate is None else error_estimate
        fit = self.fit_kinks
        if warm_start is not None:
            w0 = self._from_solution(warm_start)  # its own mesh, or fitted to its kinks
            own = warm_start._unknowns is not None and warm_start._unknowns[0] is self._token
            # a warm start from this solver's own solution keeps its mesh ("kinks": a
            # sweep costs what it did), unless tracking or estimating the error (whose
            # coarse solves fit their meshes to the kinks)
            fit = fit and (not own or self.track_kinks or estimate)
            p = p0 = self.coll.params(p_form)
            res = self._newton(w0, p, warm=True, p_form=p_form if fit else None)
            w, it, ok, how, g_end = res.w, res.iterations, res.success, "newton", res.g
            p, kappa = (res.p if res.p is not None else p), res.kappa
            moves = res.remeshes if ok else 0
            diag["factorizations"] = res.factorizations
            if res.chord:
                diag["chord"] = res.message  # "converged": chord steps alone sufficed
            if not ok:
                p, self._checked = p0, None
                w, it, ok, how = self._ipopt_solve(w0, p)
                how = f"newton failed ({res.message}); " + how
                g_end = None
            diag["start"] = "warm"
        else:
            if self.fit_kinks:
                self.coll.set_mesh(self.coll.mesh.uniform)
            p = p0 = self.coll.params(p_form)
            w0, guess = self._guess(scene)
            diag["start"] = f"cold ({guess} guess)"
            if self.cold == "newton":
                res = self._newton(w0, p, p_form=p_form if fit else None)
                w, it, ok, how, g_end = res.w, res.iterations, res.success, \
                    "newton (line search)", res.g
                p, kappa = (res.p if res.p is not None else p), res.kappa
                moves = res.remeshes if ok else 0
                if not ok:
                    p, self._checked = p0, None
                    w, it, ok, how = self._ipopt_solve(w0, p)
                    how = f"newton failed ({res.message}); " + how
                    g_end = None
            else:
                w, it, ok, how = self._ipopt_solve(w0, p)
            if not ok and scene.environment.current is not None and current_scale != 0.0:
                w, it, ok, how = self._continuation(w0, p, current_scale)
                diag["continuation"] = how
        if ok and fit:
            if self._checked is not None:  # Newton fitted the mesh near the solution
                more, info = 0, {"re_solves": 0, "found": self._checked}
            else:
                # the solution's kinks decide the mesh: solve again (warm) where they lie
                # away from the mesh points
                w, p, g_end, more, info = self._refit(w, p, p_form, g_end, kappa)
            it += more
            _, _, length, g_len = self.coll.unpack(w, p)
            diag["mesh"]["kinks_s"] = self._arc_lengths(info.pop("found"), length, g_len)
            diag["mesh"]["moves"] = moves
            diag["mesh"].update(info)
        if self.fit_kinks and self.mesh.edges and np.all(np.isfinite(w)):
            _, _, length, g_len = self.coll.unpack(w, p)
            diag["mesh"]["points_s"] = self._arc_lengths(self.mesh.interval_edges(), length,
                                                         g_len)
        # a solver built on first use (IPOPT) is build time, not solve time
        wall = time.perf_counter() - t0 - (self._late_build_s - late0)
        diag["cpu_time_s"] = time.process_time() - c0 - (self._late_build_cpu_s - late0_cpu)
        diag["solver"] = how
        diag["build_source"] = self.build_source
        diag["compiled"] = self.compiled
        if self.fit_kinks:
            # "kinks": mesh points on kinks (found by this solve, kinks_s, or kept from
            # the warm start's solve); the interval ends in points_s
            diag["mesh"]["kind"] = "kinks" if self.mesh.edges else "uniform"
        sol = self._make_solution(w, p, ok, how, it, wall, diag, g_end)
        if sol.success and estimate:
            self._estimate_error(sol, scene, current_scale)
            if sol.error_estimate is not None:
                # the iterate's own (algebraic) error, from one Newton correction: the
                # estimate stays true whatever solver.tolerance allowed
                alg = self._algebraic_error(w, p, sol)
                sol.error_estimate += alg
                sol.diagnostics["error_estimate_detail"]["algebraic"] = alg
            if sol.error_estimate is not None and sol.error_estimate > scene.solver.accuracy:
                alg = sol.diagnostics["error_estimate_detail"].get("algebraic", 0.0)
                sol.status = "inaccurate"
                if alg > 0.5 * sol.error_estimate:
                    sol.diagnostics["algebraic_error_dominates"] = True
                    sol.message = (
                        f"the iterate's algebraic error {alg:.1e} (one more Newton correction) "
                        f"exceeds solver.accuracy = {scene.solver.accuracy:.0e}: lower "
                        f"solver.tolerance = {scene.solver.tolerance:.0e}")
                else:
                    sol.message = (
                        f"converged, but the discretisation error estimate "
                        f"{sol.error_estimate:.1e} exceeds solver.accuracy = "
                        f"{scene.solver.accuracy:.0e}; increase solver.intervals")
        return sol

    # -- mesh points on the kinks of the drag (:mod:`cable_ocp.statics.kinks`) -----------
    def _arc_lengths(self, sigma: np.ndarray, length: float, g: float) -> list[float]:
        """Unstretched arc lengths (m) of mesh coordinates sigma, for the total length
        ``length`` and the grounded length ``g`` (m)."""
        sig = np.asarray(sigma, dtype=float)
        if not self.form.segmented:
            return (g + sig * (length - g)).tolist()
        # per segment: its share of sigma maps onto its arc (the first starts at g)
        b = np.asarray(self.coll.mesh.bounds)
        k = np.clip(np.searchsorted(b, sig, side="right") - 1, 0, len(b) - 2)
        ss = self.coll._segment_s(length, g)
        s0 = np.array([a for a, _ in ss])[k]
        s1 = np.array([e for _, e in ss])[k]
        return (s0 + (sig - b[k]) / (b[k + 1] - b[k]) * (s1 - s0)).tolist()

    def _kinks_of(self, w: np.ndarray, mesh: Mesh) -> np.ndarray:
        """Kinks (sigma) of the profile of unknowns w on ``mesh``."""
        coll, sc = self.coll, self.form.scales
        xs = np.asarray(w[: coll.n_x]).reshape(mesh.n_nodes, coll.nx)
        tau = xs[:, 3:6]
        size = np.sqrt(np.einsum("ij,ij->i", tau, tau))
        t = tau / np.where(size > 0.0, size, 1.0)[:, None]
        offs = mesh.segment_offsets()
        seg = np.repeat(np.arange(len(offs) - 1), np.diff(offs)) if mesh.segments else None
        if coll.nx > NX:  # a stiff segment's tangent is (cos theta, 0, sin theta)
            stiff = np.asarray(self.form.stiff)[seg]
            th = xs[:, 6]
            t = np.where(stiff[:, None], np.stack([np.cos(th), 0.0 * th, np.sin(th)], 1), t)
        vals = self._switches(xs[:, :3] * sc.length, t, seg)
        return kink_points.find(mesh.sigma(), vals, offs)

    def _fitted_mesh(self, found: np.ndarray) -> Mesh:
        """The mesh with a point on each kink ``found`` (sigma; uniform without any)."""
        base = self.coll.mesh.uniform
        edges = kink_points.fitted_edges(base.segments or (base.intervals,),
                                         base.bounds or (0.0, 1.0), found)
        return base.with_edges(edges)

    @staticmethod
    def _same_mesh(a: Mesh, b: Mesh) -> bool:
        """True when no interval end of ``a`` is farther than :data:`kinks.GAP` from
        that of ``b`` (then ``a`` serves where ``b`` is asked for)."""
        return a == b or float(np.max(np.abs(a.interval_edges() - b.interval_edges()))) \
            <= kink_points.GAP

    def _refit(self, w: np.ndarray, p: np.ndarray, p_form: np.ndarray,
               g_end: np.ndarray | None, kappa: float = math.nan
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, int, dict[str, Any]]:
        """Fit the mesh to the kinks of the solution w and solve again from w (moved onto
        the new mesh by its collocation polynomials) while they lie away from the mesh
        points (twice at most). A failed re-solve keeps the solution on the mesh before.
        ``kappa``: Newton's quadratic-convergence constant of the solve of w.
        Returns (w, p, G at w, Newton steps taken, diagnostics: the kinks found (sigma),
        the number of re-solves and a note when one failed)."""
        steps, info = 0, {"re_solves": 0}
        found = self._kinks_of(w, self.coll.mesh)
        for _ in range(2):
            target = self._fitted_mesh(found)
            if self._same_mesh(self.coll.mesh, target):
                break
            old = self.coll.mesh
            w_new = self.coll.transfer(w, old, target)
            self.coll.set_mesh(target)
            p_new = self.coll.params(p_form)
            res = self._newton(w_new, p_new, warm=True, kappa=kappa)
            steps += res.iterations
            if not res.success:
                self.coll.set_mesh(old)
                info["note"] = ("the re-solve on the mesh fitted to the kinks failed "
                                f"({res.message}); the solution on the mesh before kept")
                break
            w, p, g_end = res.w, p_new, res.g
            info["re_solves"] += 1
            found = self._kinks_of(w, self.coll.mesh)
        info["found"] = found
        return w, p, g_end, steps, info

    # -- internals ----------------------------------------------------------------------
    def _guess(self, scene: Scene) -> tuple[np.ndarray, str]:
        sig = self.mesh.sigma()
        if self.form.nx > 6 and not self.grounded:
            tow = _towed_guess(scene, self.coll.node_s(sum(c.length for c in scene.segments)))
            if tow is not None:
                return self.coll.pack(*tow), "straight towed line"
        if scene.segments:
            scene = _mean_cable_scene(scene)
        if self.grounded:
            td = touchdown_guess(scene, sig)
            if td is not None and self.form.segmented:
                # the same catenary at this mesh's nodes (segment 1 starts at touchdown)
                length, g = td[2], td[3]
                sig_td = (self.coll.node_s(length, g) - g) / (length - g)
                td = touchdown_guess(scene, sig_td)
                if g >= self.scene.segments[0].length:  # keep the grounded part on segment 1
                    td = (td[0], td[1], length, 0.5 * self.scene.segments[0].length)
            if td is not None:
                return self.coll.pack(*td), "catenary with touchdown"
        r, t, length, kind = initial_guess(scene, sig, scene.solver.initial_guess)
        return self.coll.pack(r, t, length), kind

    def _from_solution(self, sol: StaticsSolution) -> np.ndarray:
        """Unknowns from a neighbouring solution (any mesh, grounded or not). With
        ``fit_kinks``, this solver's own solutions (and predictions from them) keep their
        mesh; another solver's are moved onto a mesh fitted to their kinks."""
        own = sol._unknowns
        if own is not None and own[0] is self._token:
            # this solver's own unknowns (or a prediction of them), on the mesh own[2]
            # (Newton moves a fitted mesh onto the kinks as it converges)
            w, mesh = own[1].copy(), own[2]
            target = mesh if self.fit_kinks else self.coll.mesh
            if target != mesh:
                w = self.coll.transfer(w, mesh, target)
            if target is not self.coll.mesh:
                self.coll.set_mesh(target)
            return w
        if self.fit_kinks:
            self.coll.set_mesh(self._fitted_mesh(self._solution_kinks(sol)))
        off = sol.node_offset
        g = sol.grounded_length if self.grounded else 0.0
        if self.grounded and not off:
            # switching contact on: the grounded length starts as the stretch that went
            # below the seabed at end_a (or a small fraction of the length)
            below = seabed.gap(self.scene.environment.seabed, sol.position) < 0
            first_above = int(np.argmin(below[1:])) + 1 if below[1:].any() else 0
            g = max(float(sol.s[first_above]), 1e-3 * sol.length)
        # contact switched off (not grounded, off > 0): the grounded nodes become part of
        # the profile
        keep = slice(off, None) if (self.grounded or not off) else slice(None)
        s_src, r_src, t_src = sol.s[keep], sol.position[keep], sol.tension_vector[keep]
        if self.form.segmented:
            r, t = self.coll.resample(s_src, r_src, t_src, sol.length, g)
            bend = sol.diagnostics.get("bending")
            b = None
            if self.form.nx > 6 and bend is not None and len(bend["angle_rad"]) == len(sol.s):
                src = np.zeros((len(s_src), 3))
                src[:, 0] = np.asarray(bend["angle_rad"])[keep]
                src[:, 1] = np.asarray(bend["moment_Nm"])[keep]
                b = self.coll.resample(s_src, r_src, src, sol.length, g)[1][:, :2]
            return self.coll.pack(r, t, sol.length, g, bending=b)
        s0 = g if self.grounded else 0.0
        sig = self.mesh.sigma()
        src = (s_src - s0) / (sol.length - s0)
        if len(src) == len(sig) and np.allclose(src, sig, atol=1e-12, rtol=0):
            r, t = r_src, t_src
        else:
            r = np.stack([np.interp(sig, src, r_src[:, k]) for k in range(3)], axis=1)
            t = np.stack([np.interp(sig, src, t_src[:, k]) for k in range(3)], axis=1)
        return self.coll.pack(r, t, sol.length, g)

    def _solution_kinks(self, sol: StaticsSolution) -> np.ndarray:
        """Kinks (sigma of this solver's collocated part) of another solver's solution,
        from its node arrays (a joint between segments appears there twice)."""
        off = sol.node_offset
        g = sol.grounded_length if self.grounded else 0.0
        s = sol.s[off:] if self.grounded or not off else sol.s
        r = sol.position[len(sol.s) - len(s):]
        tension = sol.tension_vector[len(sol.s) - len(s):]
        size = np.linalg.norm(tension, axis=1)
        t = tension / np.where(size > 0.0, size, 1.0)[:, None]
        bend = sol.diagnostics.get("bending")
        if self.form.nx > NX and bend is not None and len(bend["angle_rad"]) == len(sol.s):
            th = np.asarray(bend["angle_rad"])[len(sol.s) - len(s):]
            stiff_t = np.stack([np.cos(th), 0.0 * th, np.sin(th)], axis=1)
        else:
            stiff_t = None
        # the segment of each node: a joint appears twice, as the end of the segment
        # before it and the start of the next
        cum = np.cumsum([c.length for c in self.form.lines])[:-1]
        seg = np.searchsorted(cum, s, side="right")
        if cum.size:
            tol = 1e-9 * max(sol.length, 1.0)
            at_joint = np.abs(s[:, None] - cum[None, :]).min(axis=1) <= tol
            first = np.concatenate([at_joint[:-1] & at_joint[1:], [False]])
            seg = np.where(first & (seg > 0), seg - 1, seg)
        offs = [0, *np.searchsorted(seg, np.arange(1, len(self.form.lines))).tolist(), len(s)]
        if stiff_t is not None:
            stiff = np.asarray(self.form.stiff)[seg]
            t = np.where(stiff[:, None], stiff_t, t)
        vals = self._switches(r, t, seg)
        found = kink_points.find(np.asarray(s, dtype=float), vals, offs)
        return self.coll.sigma_of_s(found, sol.length, g) if found.size else found

    def _newton(self, w0: np.ndarray, p: np.ndarray, warm: bool = False,
                kappa: float = math.nan, p_form: np.ndarray | None = None) -> NewtonResult:
        """Newton with a line search from w0, within the bounds (a positive free length, a
        grounded part on the first segment); a free length that comes out non-positive is
        a failure. From a warm start on a fixed mesh, with a kernel that keeps its
        factorisation (the compiled one; the interpreted one from its first warm solve
        on, when the sparse LU helper is available), chord steps first, then Newton from
        where they stopped if they fail. ``factorizations`` counts the Jacobians factorised.

        With ``fit_kinks`` and ``p_form`` (the formulation's parameters), Newton may move
        the mesh onto the kinks of an iterate close to the solution (``remesh`` of
        :func:`cable_ocp.statics.newton.newton`): the result's ``p`` then holds the new
        mesh's parameters (the solver's mesh is the new one); a failure restores the mesh
        of w0."""
        counts = self._kernel.counts
        f0 = counts["step"] + counts["factor"]
        mesh0 = self.coll.mesh
        moving = {}
        if self.fit_kinks and p_form is not None:
            moving = {"remesh": functools.partial(self._remesh, p_form=p_form),
                      "unmesh": functools.partial(self._unmesh, mesh0)}
        # chord steps from a warm start on a fixed mesh (a moving mesh, which puts its
        # points on the kinks of Newton's iterates, takes Newton steps)
        chord = warm and not moving
        if chord and not self._kernel.can_chord and sparse_lu.available():
            # the interpreted kernel keeps LU factors from its first warm solve on (a cold
            # solve's few steps do not repay the LU's analysis)
            self._kernel.attach_lu(self._gj, sparse_lu.SparseLU(self._gj.sparsity_out(1)))
        if chord and self._kernel.can_chord:
            res = chord_newton(self._kernel, w0, p, self.tol, NEWTON_MAX_STEPS,
                               lb=self._lbx, ub=self._ubx)
            res.chord = True
            if not res.success:
                start = res.w if np.all(np.isfinite(res.w)) else w0
                fb = newton(self._kernel, start, p, self.tol, NEWTON_MAX_STEPS,
                            lb=self._lbx, ub=self._ubx, **moving)
                fb.iterations += res.iterations
                fb.message = f"chord steps stopped ({res.message}); newton: {fb.message}"
                fb.chord = True
                res = fb
        else:
            res = newton(self._kernel, w0, p, self.tol, NEWTON_MAX_STEPS, lb=self._lbx,
                         ub=self._ubx, kappa=kappa, **moving)
        res.factorizations = counts["step"] + counts["factor"] - f0
        if res.success and self.coll.free_length and res.w[self.coll.i_lam] <= 0:
            res.success, res.message = False, "non-positive free length"
        if not res.success and self.coll.mesh is not mesh0:
            self._unmesh(mesh0)
            res.p = None
        return res

    def _remesh(self, trial: np.ndarray, p_form: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray] | None:
        """Newton's moving mesh: the trial point moved onto the mesh fitted to its own
        kinks, and that mesh's parameters; None when the current mesh already fits them
        (within :data:`kinks.GAP`). The kinks found are kept for the solution
        (:attr:`_checked`: the trial is within Newton's :data:`REMESH_RESIDUAL` of it)."""
        found = self._kinks_of(trial, self.coll.mesh)
        target = self._fitted_mesh(found)
        self._checked = found
        if self._same_mesh(self.coll.mesh, target):
            return None
        moved = self.coll.transfer(trial, self.coll.mesh, target)
        self.coll.set_mesh(target)
        return moved, self.coll.params(p_form)

    def _unmesh(self, mesh: Mesh) -> None:
        """Back to ``mesh`` (Newton rejected the moved point): the check is void."""
        self.coll.set_mesh(mesh)
        self._checked = None

    def _newton_solve(self, w0: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, int, bool, str]:
        """Newton from w0 on the current mesh: (w, steps, success, "newton")."""
        res = self._newton(w0, p)
        return res.w, res.iterations, res.success, "newton"

    def _algebraic_error(self, w: np.ndarray, p: np.ndarray, sol: StaticsSolution) -> float:
        """Relative change of the end forces, positions and length under one more Newton
        correction -J(w)^-1 g(w) at the returned iterate (0 for a converged one): the
        algebraic part of the error, which the mesh comparison cannot see."""
        dw = self._kernel.step(w, p)[1]
        if not np.all(np.isfinite(dw)):
            return math.inf
        r0, t0, l0, _ = self.coll.unpack(w, p)
        r1, t1, l1, _ = self.coll.unpack(w + dw, p)
        tmax, length = max(sol.max_tension, 1e-300), max(sol.length, 1e-300)
        return float(max(np.max(np.abs(t1 - t0)) / tmax, np.max(np.abs(r1 - r0)) / length,
                         abs(l1 - l0) / length))

    # -- sensitivities: the line's stiffness at its fixed ends -----------------------------
    def _end_forces(self, ws: ca.MX) -> ca.MX:
        """Forces (N) the cable exerts on the end_a and end_b attachments, (6,), from the
        scaled unknowns: +T(0) and -T(L); with a grounded part, the anchor force is the
        touchdown tension less the seabed's axial gradient over the grounded length, along
        the grounded line (:func:`cable_ocp.physics.seabed.grounded_nodes` at s' = 0)."""
        coll, sc = self.coll, self.form.scales
        nx, last = coll.nx, self.mesh.n_nodes - 1
        tau0, tau_n = ws[3:6], ws[last * nx + 3: last * nx + 6]
        if self.grounded:
            tmag = ca.sqrt(ca.dot(tau0, tau0))
            e = tau0 / tmag
            k = seabed.axial_gradient(self.scene.environment.seabed,
                                      self.scene.cable.weight_in_water, e) * sc.length / sc.force
            fa = sc.force * ca.fmax(tmag - k * ws[coll.i_g], 0.0) * e
        else:
            fa = sc.force * tau0
        return ca.vertcat(fa, -sc.force * tau_n)

    def _sensitivity_functions(self) -> ca.Function:
        """``(w, p) -> (G_e, F_w)``: the Jacobians of the collocated residual in the end
        values p[P_END_A], p[P_END_B] (n_w x 6) and of the end forces (N) in the unknowns
        (6 x n_w), on the MX graph of the residual (the Jacobian in the unknowns, G_w,
        comes from the Newton functions)."""
        if self._sensitivity is None:
            n_p = self.coll.n_p
            w = ca.MX.sym("w", self.coll.n_w)
            head = ca.MX.sym("p_head", P_END_A.start)
            ends = ca.MX.sym("p_ends", P_END_B.stop - P_END_A.start)
            tail = ca.MX.sym("p_tail", n_p - P_END_B.stop)
            g = self.coll.residual(w, ca.vertcat(head, ends, tail))
            cheap = ca.Function("statics_sensitivity_parts", [w, head, ends, tail],
                                [ca.jacobian(g, ends), ca.jacobian(self._end_forces(w), w)])
            wp, pp = ca.MX.sym("w", self.coll.n_w), ca.MX.sym("p", n_p)
            args = (wp, pp[: P_END_A.start], pp[P_END_A.start: P_END_B.stop],
                    pp[P_END_B.stop:])
            self._sensitivity = ca.Function("statics_sensitivity", [wp, pp], cheap(*args),
                                            ["w", "p"], ["G_e", "F_w"])
        return self._sensitivity

    def end_stiffness(self, w: np.ndarray, p: np.ndarray) -> dict[str, dict[str, Any]]:
        """The line's stiffness at each end whose position is fully fixed, from the
        solver's own sensitivities.

        K[i][j] = dF_i/dx_j (N/m), F the force the cable exerts on that end's attachment
        (as :attr:`StaticsSolution.force_a`/``force_b`` report it) and x that end's
        position, the other end held as the scene says (fixed position or prescribed
        force) and the unstretched length held (a free-length scene holds the length it
        solved for, not the prescribed tension). Exact for the discretised equations:
        the implicit-function theorem on G(w, p) = 0 gives dw/dp = -G_w^-1 G_p, with the
        end positions among the parameters p (one sparse LU factorisation of G_w, one
        column per fixed end coordinate), then dF/dx = F_w dw/dp / ell.

        Parameters
        ----------
        w : ndarray
            Converged scaled unknowns of this solver.
        p : ndarray
            Parameter vector of the solve (:meth:`Formulation.params`).

        Returns
        -------
        dict
            ``{"a": {...}, "b": {...}}``, each with ``matrix`` (3x3 nested list of floats,
            N/m, with None entries where a derivative does not exist; or None) and ``note``
            (what is held, or why there is no matrix).
        """
        from scipy.sparse import csr_matrix
        from scipy.sparse.linalg import splu

        scene, ell = self.scene, self.form.scales.length
        held = "the unstretched length held"
        if self.coll.free_length:
            held += " (the length the prescribed tension gave; the tension is not held)"
        out: dict[str, dict[str, Any]] = {}
        fixed: list[str] = []  # ends with a fully fixed position, in the order a, b
        for key, end, other in (("a", scene.end_a, scene.end_b), ("b", scene.end_b,
                                                                  scene.end_a)):
            if not all(end.fixed_mask):
                free = ", ".join("xyz"[i] for i, f in enumerate(end.fixed_mask) if not f)
                out[key] = {"matrix": None, "note": (
                    f"end_{key}'s position is not fully fixed (free in {free}, where a force "
                    "is prescribed): no stiffness at a free end")}
                continue
            how = "fixed" if all(other.fixed_mask) else \
                "as the scene says (its prescribed force components held)"
            out[key] = {"matrix": None,
                        "note": f"end_{'b' if key == 'a' else 'a'} held {how}, {held}"}
            fixed.append(key)
        if not fixed:
            return out
        # parameter columns of the fixed ends among p[P_END_A], p[P_END_B] (scaled m)
        cols = [c for key in fixed for c in ((0, 1, 2) if key == "a" else (3, 4, 5))]
        g_p, f_w = self._sensitivity_functions()(w, p)
        g_w = self._gj(w, p)[1]
        h_w = g_w.sparse().tocsr()
        h_p = np.asarray(g_p.sparse().todense())[:, cols]
        if self.coll.free_length:
            # hold the unstretched length (the line as installed), not the tension: the
            # tension condition, the last residual (Collocation._boundary), becomes
            # "lam (+ g) keeps its value", with no dependence on the end positions
            n, last = self.coll.n_w, self.coll.n_w - 1
            h_w.data[h_w.indptr[last]: h_w.indptr[last + 1]] = 0.0
            hold = np.zeros(n)
            hold[self.coll.i_lam] = 1.0
            if self.coll.grounded:
                hold[self.coll.i_g] = 1.0
            h_w = h_w + csr_matrix((hold, (np.full(n, last), np.arange(n))), shape=(n, n))
            h_p[last] = 0.0
        try:
            dw = splu(h_w.tocsc()).solve(-h_p)  # one factorisation, one column per coordinate
        except RuntimeError as exc:  # "Factor is exactly singular"
            dfdx, why = None, f"the Jacobian is singular ({exc})"
        else:
            dfdx = np.asarray(f_w.sparse() @ dw) / ell  # (6, len(cols)), N/m
            why = "the sensitivity is not finite (ill-conditioned Jacobian)"
        if dfdx is None or not np.all(np.isfinite(dfdx)):
            for key in fixed:
                out[key]["note"] = f"not computed: {why}"
            return out
        for j, key in enumerate(fixed):
            rows = slice(0, 3) if key == "a" else slice(3, 6)  # F_a, F_b in the outputs
            mat = dfdx[rows, 3 * j: 3 * j + 3]
            k_list: list[list[float | None]] = [[float(v) for v in row] for row in mat]
            if key == "a" and self.grounded:
                if scene.environment.seabed.slope_deg != 0.0:  # type: ignore[union-attr]
                    out[key] = {"matrix": None, "note": (
                        "the anchor lies on a sloping seabed with the cable grounded: any "
                        "displacement off the seabed plane lifts the grounded part, where "
                        "the anchor force is not differentiable (one-sided contact)")}
                    continue
                for row in k_list:
                    row[2] = None
                out[key]["note"] += (
                    "; the z column is null: the cable lies on the seabed at the anchor, where "
                    "lifting the anchor changes the force at an unbounded rate (one-sided "
                    "contact), so dF/dz does not exist")
            out[key]["matrix"] = k_list
        return out

    def _ipopt_solve(self, w0: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, int, bool, str]:
        res = self._ipopt(x0=np.clip(w0, self._lbx, self._ubx), p=p, lbx=self._lbx,
                          ubx=self._ubx, lbg=0, ubg=0)
        st = self._ipopt.stats()
        w = np.asarray(res["x"]).reshape(-1)
        return w, int(st.get("iter_count", 0)), bool(st.get("success", False)), (
            f"ipopt ({st.get('return_status')})")

    def _continuation(self, w0: np.ndarray, p: np.ndarray, target: float
                      ) -> tuple[np.ndarray, int, bool, str]:
        w, total = w0, 0
        steps = [target * c for c in _CONTINUATION_STEPS]
        for k, c in enumerate(steps):
            pk = p.copy()
            pk[P_CURRENT] = c
            w_new, it, ok, how = self._newton_solve(w, pk) if k else (w, 0, False, "")
            if not ok:
                w_new, it, ok, how = self._ipopt_solve(w, pk)
            total += it
            if not ok:
                return w_new, total, False, (
                    f"continuation in current scale failed at {c:g} of the current ({how})")
            w = w_new
        return w, total, True, (
            f"current ramped {', '.join(f'{c:g}' for c in steps)} (Huang 1992, section 2.5)")

    def _make_solution(self, w: np.ndarray, p: np.ndarray, ok: bool, how: str, it: int,
                       wall: float, diag: dict[str, Any], g: np.ndarray | None = None
                       ) -> StaticsSolution:
        if g is None:  # else the residual at w, from the Newton iteration
            g = self._kernel.g(w, p)
        viol = float(np.max(np.abs(g))) if np.all(np.isfinite(g)) else math.inf
        r, t, length, g_len = self.coll.unpack(w, p)
        s = self.coll.node_s(length, g_len)
        finite = bool(np.all(np.isfinite(w)))
        offset = 0
        if self.grounded and finite:
            sb, cab = self.scene.environment.seabed, self.scene.cable
            tmag0 = float(np.linalg.norm(t[0]))
            e = t[0] / tmag0
            k = float(seabed.axial_gradient(sb, cab.weight_in_water, e))
            anchor = np.asarray(self.scene.end_a.position, dtype=float)
            ng = max(2, min(41, int(np.ceil(g_len / max(length, 1e-12) * len(s))) + 1))
            sg, rg, tg = seabed.grounded_nodes(anchor, e, tmag0, k, max(g_len, 0.0),
                                               cab.axial_stiffness, ng)
            s, r, t = (np.concatenate([sg[:-1], s]), np.vstack([rg[:-1], r]),
                       np.vstack([tg[:-1], t]))
            offset = ng - 1
            diag["touchdown"] = {"position": [float(v) for v in r[offset]],
                                 "grounded_length": float(g_len)}
        elif self.scene.environment.seabed is not None:
            diag["touchdown"] = None
        tol_ok = viol <= 10.0 * self.tol
        if ok and finite and tol_ok:
            status, msg = "solved", f"converged ({how}), max scaled residual {viol:.2e}"
        elif not finite:
            status, msg = "failed", f"non-finite iterate ({how})"
        elif ok and not tol_ok:
            status, msg = "failed", (
                f"solver reported success ({how}) but the scaled residual {viol:.2e} "
                f"exceeds 10 x tolerance {self.tol:.1e}")
        else:
            status, msg = "failed", f"did not converge ({how}); max scaled residual {viol:.2e}"
        sol = StaticsSolution(status=status, message=msg, s=s, position=r, tension_vector=t,
                              length=length, iterations=it, wall_time_s=wall,
                              constraint_violation=viol, diagnostics=diag, node_offset=offset)
        if finite:
            # the end stiffness, computed on first use (StaticsSolution.stiffness)
            sol._stiffness_source = functools.partial(self.end_stiffness, w.copy(), p.copy())
            # the unknowns themselves and their mesh, for a warm start by this solver
            sol._unknowns = (self._token, w.copy(), self.coll.mesh)
        tmax = float(np.max(np.linalg.norm(t, axis=1))) if finite else math.nan
        diag["smoothing_force_bound_N"] = self.form.smoothing_force_bound(length, tmax)
        diag["min_z"] = float(np.min(r[:, 2])) if finite else math.nan
        warnings = []
        sb = self.scene.environment.seabed
        if finite and sb is not None:
            diag["min_gap"] = float(np.min(seabed.gap(sb, r)))
        if finite and np.min(np.linalg.norm(t, axis=1)) <= 0.0:
            warnings.append("tension vanishes somewhere along the cable")
        diag["warnings"] = warnings
        if self.form.segmented and finite:
            self._segment_diagnostics(sol, r, offset, p)
        bend = self.coll.unpack_bending(w)
        if bend is not None:
            bend = np.vstack([np.zeros((offset, 2)), bend])  # grounded nodes: no bending
            # per node: tangent angle from +x towards +z (rad) and bending moment (N m);
            # zeros on flexible segments (planar beam-cable, formulation module)
            diag["bending"] = {"angle_rad": bend[:, 0].tolist(), "moment_Nm": bend[:, 1].tolist()}
            # axial force T . t on the stiff segments (T carries the shear there too):
            # a stiff segment in compression may sit on an unstable branch (an inverted
            # column), which a statics solve cannot tell from a stable one
            ang = bend[:, 0]
            axial = t[:, 0] * np.cos(ang) + t[:, 2] * np.sin(ang)
            on_stiff = np.zeros(len(axial), dtype=bool)
            offs = self.mesh.segment_offsets()
            for k, stiff in enumerate(self.form.stiff):
                if stiff:
                    on_stiff[offset + offs[k]: offset + offs[k + 1]] = True
            # tangent at an end on a stiff segment (T carries shear there, so T/|T| is not
            # the tangent): from theta (StaticsSolution.end_tangent)
            diag["end_tangents"] = {
                key: [math.cos(ang[i]), 0.0, math.sin(ang[i])] if on_stiff[i] else None
                for key, i in (("a", 0), ("b", len(ang) - 1))}
            worst = float(np.min(axial[on_stiff])) if on_stiff.any() else 0.0
            diag["bending"]["min_axial_force_N"] = worst
            if worst < -1e-6 * max(tmax, 1.0):
                warnings.append(
                    f"a stiff segment carries {-worst:.4g} N of compression: this equilibrium "
                    "may be unstable (e.g. an inverted column); check the branch")
        return sol

    def _segment_diagnostics(self, sol: StaticsSolution, r: np.ndarray, offset: int,
                             p: np.ndarray) -> None:
        """Per-body loads at the joints, and the free-surface check: a multi-segment line
        (a buoy may lift it) that would leave the water is a failure, never a profile."""
        diag, scene = sol.diagnostics, self.scene
        offs = self.mesh.segment_offsets()
        bodies = []
        for i, body in enumerate(scene.bodies):
            pos = r[offset + offs[body.joint] - 1]
            force = self.form.body_load(i, pos, float(p[P_CURRENT]))
            bodies.append({"joint": body.joint, "kind": body.kind,
                           "position": [float(v) for v in pos],
                           "force": [float(v) for v in force]})
        diag["bodies"] = bodies
        diag["joints"] = [[float(v) for v in r[offset + offs[k] - 1]]
                          for k in range(1, len(offs) - 1)]
        first = scene.segments[0].length
        if sol.status in ("solved", "inaccurate") and sol.grounded_length >= first:
            sol.status = "failed"
            sol.message = (
                f"the grounded length {sol.grounded_length:.6g} m reaches beyond the first "
                f"segment (cable.segments[0].length = {first:g} m); contact of later "
                "segments and bodies with the seabed is not modelled")

    def _coarse_solver(self, level: int) -> StaticsSolver:
        """Solver on N / 2**level intervals, built on first use (shared cache)."""
        n = self.mesh.intervals // 2**level
        if (n, self.grounded) not in self._cache:
            StaticsSolver(self.scene, intervals=n, degree=self.mesh.degree,
                          scheme=self.mesh.scheme, cache=self._cache, grounded=self.grounded)
        return self._cache[(n, self.grounded)]

    def _estimate_error(self, sol: StaticsSolution, scene: Scene, current_scale: float) -> None:
        """Richardson estimate with the observed order.

        With x_N, x_{N/2}, x_{N/4} the end forces and mesh-point positions on three nested
        meshes, the observed order is q = log2(|x_{N/2} - x_{N/4}| / |x_N - x_{N/2}|),
        clipped to [1, p] (p the scheme's nominal order), and the error of x_N is estimated
        as |x_N - x_{N/2}| / (2^q - 1). Using q rather than p keeps the estimate honest
        where a kink in the drag (a flow component changing sign) lowers the order.
        With fewer than 4 intervals, or when the N/4 solve fails, only two meshes are
        used, with q = min(p, d + 1) (the stage order, which the interior points follow).
        """
        n = self.mesh.intervals
        if n < 2:
            sol.diagnostics["error_estimate_detail"] = {"note": "needs at least 2 intervals"}
            return
        levels = 2 if n >= 4 else 1
        sols = [sol]
        for lev in range(1, levels + 1):
            c = self._coarse_solver(lev)._solve(scene, warm_start=sols[-1],
                                                error_estimate=False,
                                                current_scale=current_scale)
            if not c.success:
                if lev == 1:
                    sol.diagnostics["error_estimate_detail"] = {
                        "note": f"coarse solve failed: {c.message}"}
                    return
                levels = 1  # fall back to two meshes and the nominal order
                break
            sols.append(c)

        def diff(fine: StaticsSolution, coarse: StaticsSolution, solver: StaticsSolver
                 ) -> tuple[float, float]:
            """End-force and position differences. Positions are compared at every node
            of the finer solution (interior collocation points included: they converge
            only at the stage order d + 1), against the coarser solution's collocation
            polynomials; multiple-shooting solutions at their common nodes."""
            dforce = max(np.max(np.abs(fine.force_a - coarse.force_a)),
                         np.max(np.abs(fine.force_b - coarse.force_b)))
            fo, co = fine.node_offset, coarse.node_offset
            fpos, cpos = fine.position[fo:], coarse.position[co:]
            if solver.mesh.degree >= 1:
                g = fine.grounded_length
                sig = solver.coll.sigma_of_s(fine.s[fo:], fine.length, g)
                dpos = np.max(np.abs(fpos - solver.coll.interpolate(cpos, sig)))
            else:
                dpos = np.max(np.abs(fpos[::2] - cpos))
            return float(dforce), max(float(dpos), abs(fine.length - coarse.length),
                                      abs(fine.grounded_length - coarse.grounded_length))

        d1 = diff(sols[0], sols[1], self._coarse_solver(1))
        p = self.mesh.order
        # two meshes only: assume the order of the slowest-converging quantity compared,
        # the stage order d + 1 of the interior collocation points (not the mesh order)
        q = float(min(p, self.mesh.degree + 1) if self.mesh.degree >= 1 else p)
        if levels == 2:
            d2 = diff(sols[1], sols[2], self._coarse_solver(2))
            rel1 = max(d1[0] / sol.max_tension, d1[1] / sol.length)
            rel2 = max(d2[0] / sol.max_tension, d2[1] / sol.length)
            if rel1 > 0 and rel2 > 0:
                q = float(np.clip(np.log2(rel2 / rel1), 1.0, p))
        factor = 1.0 / (2.0**q - 1.0)
        force_n, pos_m = factor * d1[0], factor * d1[1]
        sol.error_estimate = max(force_n / sol.max_tension, pos_m / sol.length)
        sol.diagnostics["error_estimate_detail"] = {
            "force_N": force_n, "position_m": pos_m, "observed_order": q,
            "method": f"Richardson, N={n}/{n // 2}" + (f"/{n // 4}" if levels == 2 else "")
                      + f", observed order {q:.2f} (nominal {p})",
        }


# -- convenience API ---------------------------------------------------------------------

def _mean_cable_scene(scene: Scene) -> Scene:
    """A single-cable scene with the line's mean weight per length, the bodies' vertical
    loads spread over it (for the drag-free initial guesses of a multi-segment line)."""
    total = sum(c.length for c in scene.segments)  # type: ignore[misc]
    weight = sum(c.weight_in_water * c.length for c in scene.segments)  # type: ignore[operator]
    weight -= sum(b.static_load[2] for b in scene.bodies)
    cable = replace(scene.cable, weight_in_water=weight / total)
    return replace(scene, cable=cable, segments=(), segment_intervals=(), bodies=())


def _towed_guess(scene: Scene, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Guess for a towed line (end_a fixed, end_b free under a given load, a uniform
    current in the x-z plane): a straight line from end_a downstream, sloping down at
    0.1 rad, with the tension of the tangential drag and the end load accumulated from
    end_b; in still water a line hanging straight down. None when the scene is not of
    that kind."""
    cur, a, b = scene.environment.current, scene.end_a, scene.end_b
    if not all(a.fixed_mask) or any(b.fixed_mask):
        return None
    lens = [c.length for c in scene.segments]
    cum = np.concatenate([[0.0], np.cumsum(lens)])
    total = float(cum[-1])
    if cur is None or cur.max_speed == 0.0:
        # still water: the line hangs straight down from end_a, its tension the weight
        # below (a sinking line; an inverted start would land on the unstable branch)
        e = np.array([0.0, 0.0, -1.0])
        ft = [abs(c.weight_in_water) for c in scene.segments]
    else:
        rho = scene.environment.water_density
        ux = cur.ux[0] if cur.ux[0] != 0.0 else cur.max_speed
        e = np.array([math.copysign(math.cos(0.1), ux), 0.0, -math.sin(0.1)])
        # tangential drag per metre of each segment, N/m (0.5 rho C_t pi D U^2), plus the
        # weight's component along the 0.1 rad slope
        ft = [line_drag_factors(rho, c.diameter, c.normal_drag, c.tangential_drag)[1] * ux**2
              + abs(c.weight_in_water) * 0.1 for c in scene.segments]
    pull = float(np.linalg.norm([f or 0.0 for f in b.force]))

    def beyond(sv: float) -> float:
        """Drag on the line beyond arc length sv, N."""
        return sum(f * max(0.0, min(hi, total) - max(lo, sv))
                   for f, lo, hi in zip(ft, cum[:-1], cum[1:], strict=True))

    tmag = np.array([pull + beyond(float(v)) for v in s])
    tmag = np.maximum(tmag, 1e-6 * max(tmag.max(), 1.0))
    r = np.asarray(a.position, dtype=float) + np.outer(s, e)
    return r, np.outer(tmag, e), total


def _can_ground(scene: Scene) -> bool:
    """True when the scene models the seabed and end_a is fixed on it (an anchor)."""
    sb = scene.environment.seabed
    if sb is None or not all(scene.end_a.fixed_mask):
        return False
    gap = seabed.gap(sb, np.asarray(scene.end_a.position, dtype=float))[0]
    return abs(gap) <= 1e-6 * reference_length(scene)


def _penetration(sol: StaticsSolution, scene: Scene) -> float:
    """Largest depth below the seabed of the computed (suspended) nodes, m (0 if none)."""
    gaps = seabed.gap(scene.environment.seabed, sol.position[sol.node_offset + 1:])
    return float(max(0.0, -np.min(gaps))) if gaps.size else 0.0


def _solve_with_contact(scene: Scene, get: Callable[[bool], StaticsSolver],
                        warm_start: StaticsSolution | None,
                        error_estimate: bool | None = None) -> StaticsSolution:
    """Solve, switching seabed contact at end_a on or off as the solution demands.

    Without ``[environment.seabed]`` this is a plain solve. With it: a solution that
    passes below the seabed next to an anchored end_a is re-solved with a grounded part
    (touchdown formulation); a grounded solution whose grounded length comes out negative
    is re-solved without. A result that still passes below the seabed (contact away from
    end_a, which is not modelled) is a failure, never a solution.
    """
    kw = {"error_estimate": error_estimate}
    grounded = bool(warm_start is not None and warm_start.node_offset and _can_ground(scene))
    sol = get(grounded).solve(scene, warm_start=warm_start, **kw)
    if scene.environment.seabed is None or sol.status not in ("solved", "inaccurate"):
        return sol
    tol = 1e-6 * reference_length(scene)
    why = ""
    if not grounded and _can_ground(scene) and _penetration(sol, scene) > tol:
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
    depth = _penetration(sol, scene) if sol.status in ("solved", "inaccurate") else 0.0
    if depth > tol:
        first = scene.segments[0].length if scene.segments else sol.length
        if sol.node_offset and sol.grounded_length >= first * (1.0 - 1e-6) \
                and len(scene.segments) > 1:
            why += ("; the grounded part reached the end of the first segment: contact of "
                    "later segments or of a body at a joint is not modelled yet")
        elif not why:
            why = ("; contact away from an anchored end_a is not modelled yet"
                   if _can_ground(scene) else
                   "; end_a is not anchored on the seabed, and contact elsewhere is not "
                   "modelled yet")
        sol.status = "below_seabed"
        sol.message = f"the cable passes {depth:.3g} m below the seabed" + why
    return sol


def solve_collocation(scene: Scene, warm_start: StaticsSolution | None = None
                      ) -> StaticsSolution:
    """Solve one scene by collocation or multiple shooting, with accuracy control.

    Builds its solvers (use :class:`StaticsSolver` to reuse one across solves). Seabed
    contact is switched on where needed (:func:`_solve_with_contact`). When the error
    estimate exceeds ``solver.accuracy`` and ``solver.refine`` is true, the number of
    intervals is doubled (each solve warm-started from the previous one) up to
    ``solver.max_intervals``; the diagnostics list the refinement steps.
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
    sol = _solve_with_contact(scene, getter(n), warm_start)
    history = [(n, sol.error_estimate)]
    opts = scene.solver
    while (sol.status == "inaccurate" and opts.refine and 2 * n <= opts.max_intervals
           and not sol.diagnostics.get("algebraic_error_dominates")):
        n *= 2
        sol = _solve_with_contact(scene, getter(n), sol)
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
    """

    def __init__(self, error_estimate: bool | None = None) -> None:
        self.error_estimate = error_estimate
        self._caches: dict[tuple, dict[tuple, StaticsSolver]] = {}
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
        another key, starts a new line."""
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

            sol = _solve_with_contact(scene, get, start, self.error_estimate)
            if start is not prev and not sol.converged:
                sol = _solve_with_contact(scene, get, prev, self.error_estimate)
            if prev is not None and not sol.converged:
                sol = _solve_with_contact(scene, get, None, self.error_estimate)
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
    """The start of a continuation step to ``v``: the Lagrange extrapolation through the
    points of ``line`` (the last one ``prev``; points are dropped, oldest first, while the
    prediction's gain exceeds :data:`_PREDICTOR_MAX_GAIN`), else ``prev``."""
    if prev is None or v is None or not line or line[-1][1] is not prev:
        return prev
    pts = [(x, s) for x, s in line if x != v]
    if len(pts) != len(line) or len({x for x, _ in pts}) != len(pts):
        return prev
    while len(pts) >= 2 and sum(abs(x) for x in _weights(
            [x for x, _ in pts], float(v))) > _PREDICTOR_MAX_GAIN:
        pts.pop(0)
    return _extrapolate(pts, float(v)) if len(pts) >= 2 else prev


#: most points of the polynomial predictor in a sweep (4: cubic extrapolation; on the De
#: Zoysa sweep it takes 3 Newton steps per point where the secant takes 4)
PREDICTOR_POINTS = 4
#: largest sum of |Lagrange weights| of a prediction (uniform steps: 15 for the cubic,
#: 7 for the quadratic, 3 for the secant); beyond it (a long step after short ones) the
#: oldest points are dropped, and without a usable secant the previous solution is used
_PREDICTOR_MAX_GAIN = 16.0


def _weights(vs: list[float], v: float) -> list[float]:
    """Lagrange weights of the values at ``vs`` for extrapolation to ``v``."""
    return [math.prod((v - vs[j]) / (vs[i] - vs[j]) for j in range(len(vs)) if j != i)
            for i in range(len(vs))]


def _extrapolate(points: list[tuple[float, StaticsSolution]], v: float) -> StaticsSolution:
    """Lagrange extrapolation to ``v`` through (value, solution) points of one mesh, on
    the node arrays and, when one solver produced every point, on its unknowns (node by
    node: where the mesh points moved with the kinks between the points, the interval
    ends are extrapolated alike)."""
    weights = _weights([float(x) for x, _ in points], v)

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
            while len(pts) >= 2 and sum(abs(x) for x in _weights(
                    [float(x) for x, _ in pts], float(v))) > _PREDICTOR_MAX_GAIN:
                pts.pop(0)
            if len(pts) >= 2:
                start = _extrapolate(pts, v)
        known = {id(x) for x in cache.values()}
        sol = _solve_with_contact(sc, get, start, error_estimate)
        if start is not prev and not sol.converged:
            sol = _solve_with_contact(sc, get, prev, error_estimate)
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
