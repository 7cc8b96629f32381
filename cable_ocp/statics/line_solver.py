"""Build once, solve many: the statics solver of one discretised line.

A :class:`StaticsSolver` builds the collocated residual G(w, p) = 0 once, with its sparse
Jacobian and the Newton step assembled per collocation interval
(:mod:`cable_ocp.statics.newton`), and solves it by Newton's method with a backtracking
line search on |G| (one CasADi call per step, on preallocated buffers):

* warm start (a neighbouring solution, e.g. the previous point of a sweep, or a
  prediction from the last points): Newton; if it fails, IPOPT from the same start;
* cold start (the drag-free catenary or another guess): Newton; only if that fails, IPOPT
  (``nlpsol``, a square system with zero objective, built on first use,
  :mod:`cable_ocp.statics.ipopt`) from the same guess, then a ramp of the current from 0
  to its value (Huang (1992), section 2.5), and the diagnostics say which did it.

The built functions are kept on disk (:mod:`cable_ocp.statics.cache`) so that another
process solving a scene of the same structure loads them instead of building them.

Mesh points on the drag's kinks (``solver.mesh``, :mod:`cable_ocp.statics.kink_mesh`): the
interval widths are parameters of the built functions, so Newton moves the mesh onto the
kinks of its iterate as it converges, at no build cost (cold solves and starts from
another solver's solution; a warm start from this solver's own solution keeps its mesh
unless ``solver.mesh = "tracking"``).

Every solution is checked by evaluating the residual at the returned point; only a
residual within tolerance is reported as ``"solved"``
(:mod:`cable_ocp.statics.line_solution`).

The a-posteriori error estimate re-solves on N/2 and N/4 intervals (warm-started from the
fine solution) and applies Richardson's formula with the observed order
(:mod:`cable_ocp.statics.error_estimate`); the end stiffness comes from the solver's own
sensitivities (:mod:`cable_ocp.statics.stiffness`). Solving one scene with contact
switching and refinement, sweeps and sessions: :mod:`cable_ocp.statics.solver`.
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import replace
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt, sparse_lu
from cable_ocp.numerics.compile import compile_function, is_compiled
from cable_ocp.physics import seabed
from cable_ocp.scene import Scene, SolverOptions
from cable_ocp.statics import cache as disk_cache
from cable_ocp.statics.checks import check_physical
from cable_ocp.statics.collocation import Collocation
from cable_ocp.statics.error_estimate import apply_error_estimate
from cable_ocp.statics.formulation import P_CURRENT, Formulation, _structure_key
from cable_ocp.statics.initial_guess import (
    initial_guess,
    mean_cable_scene,
    touchdown_guess,
    towed_guess,
)
from cable_ocp.statics.ipopt import build_ipopt
from cable_ocp.statics.kink_mesh import KinkMesh
from cable_ocp.statics.line_solution import assemble_solution
from cable_ocp.statics.mesh import Mesh
from cable_ocp.statics.newton import (
    LINEAR_SOLVER,
    Kernel,
    NewtonResult,
    chord_newton,
    jacobian_functions,
    newton,
)
from cable_ocp.statics.shooting import MultipleShooting
from cable_ocp.statics.solution import StaticsSolution
from cable_ocp.statics.stiffness import EndStiffness

__all__ = ["COMPILE_FLAG", "NEWTON_MAX_STEPS", "StaticsSolver"]

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
        #: the kinks of the drag and the meshes fitted to them
        self.kinks = KinkMesh(self.coll, self.form, scene)
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
        self._stiffness: EndStiffness | None = None  # built on first use
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
                self._ipopt_fn = build_ipopt(self.coll.residual, self.coll.n_w,
                                             self.coll.n_p, self.tol, opts.max_iterations)
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
        widths (:meth:`Collocation.params`).

        Parameters
        ----------
        scene : Scene, optional
            A scene of this solver's structure.
        current_scale : float
            Multiplier on the current, 1 = as specified.
        mesh : Mesh, optional
            A mesh with this solver's numbers of intervals.
        """
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
        sol = self.solve_unchecked(scene, warm_start, error_estimate, current_scale)
        return check_physical(scene, sol)

    def solve_unchecked(self, scene: Scene, warm_start: StaticsSolution | None = None,
                        error_estimate: bool | None = None, current_scale: float = 1.0
                        ) -> StaticsSolution:
        """:meth:`solve` without the physical check (used for the coarse meshes of the
        error estimate too).

        Parameters
        ----------
        scene : Scene
            A scene with this solver's structure.
        warm_start : StaticsSolution, optional
            A neighbouring solution.
        error_estimate : bool, optional
            Compute the error estimate (default: ``scene.solver.error_estimate``).
        current_scale : float
            Multiplier on the current, 1 = as specified.
        """
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
            diag["mesh"]["kinks_s"] = self.kinks.arc_lengths(info.pop("found"), length, g_len)
            diag["mesh"]["moves"] = moves
            diag["mesh"].update(info)
        if self.fit_kinks and self.mesh.edges and np.all(np.isfinite(w)):
            _, _, length, g_len = self.coll.unpack(w, p)
            diag["mesh"]["points_s"] = self.kinks.arc_lengths(self.mesh.interval_edges(), length,
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
            apply_error_estimate(self, sol, scene, current_scale, w, p)
        return sol

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
        found = self.kinks.kinks_of(w, self.coll.mesh)
        for _ in range(2):
            target = self.kinks.fitted_mesh(found)
            if self.kinks.same_mesh(self.coll.mesh, target):
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
            found = self.kinks.kinks_of(w, self.coll.mesh)
        info["found"] = found
        return w, p, g_end, steps, info

    # -- internals ----------------------------------------------------------------------
    def _guess(self, scene: Scene) -> tuple[np.ndarray, str]:
        """The unknowns of a cold start on this mesh, and the name of the guess."""
        sig = self.mesh.sigma()
        if self.form.nx > 6 and not self.grounded:
            tow = towed_guess(scene, self.coll.node_s(sum(c.length for c in scene.segments)))
            if tow is not None:
                return self.coll.pack(*tow), "straight towed line"
        if scene.segments:
            scene = mean_cable_scene(scene)
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
            found = self.kinks.solution_kinks(sol, self.grounded)
            self.coll.set_mesh(self.kinks.fitted_mesh(found))
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
        found = self.kinks.kinks_of(trial, self.coll.mesh)
        target = self.kinks.fitted_mesh(found)
        self._checked = found
        if self.kinks.same_mesh(self.coll.mesh, target):
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

    def _ipopt_solve(self, w0: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, int, bool, str]:
        # a Ctrl-C: KeyboardInterrupt, never a failed solve to recover from
        res, st = interrupt.call_solver(self._ipopt, x0=np.clip(w0, self._lbx, self._ubx), p=p,
                                        lbx=self._lbx, ubx=self._ubx, lbg=0, ubg=0)
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

    def newton_correction(self, w: np.ndarray, p: np.ndarray) -> np.ndarray:
        """One Newton correction -J(w)^-1 G(w) at the unknowns ``w`` (scaled; zero at a
        converged iterate).

        Parameters
        ----------
        w : ndarray
            Scaled unknowns.
        p : ndarray
            The residual's parameter vector.
        """
        return self._kernel.step(w, p)[1]

    def _sensitivities(self) -> EndStiffness:
        """The end sensitivities of this solver's line (built on first use)."""
        if self._stiffness is None:
            self._stiffness = EndStiffness(self.scene, self.form, self.coll, self.grounded,
                                           self._gj)
        return self._stiffness

    def end_stiffness(self, w: np.ndarray, p: np.ndarray) -> dict[str, dict[str, Any]]:
        """The line's stiffness at each end whose position is fully fixed
        (:meth:`cable_ocp.statics.stiffness.EndStiffness.matrices`, built on first use).

        Parameters
        ----------
        w : ndarray
            Converged scaled unknowns of this solver.
        p : ndarray
            Parameter vector of the solve (:meth:`Formulation.params`).

        Returns
        -------
        dict
            ``{"a": {...}, "b": {...}}``, each with ``matrix`` (3x3, N/m, or None) and
            ``note``.
        """
        return self._sensitivities().matrices(w, p)

    def end_jacobian(self, w: np.ndarray, p: np.ndarray) -> np.ndarray:
        """The 6x6 dF/dx of both end forces in both end positions, both ends fixed
        (:meth:`cable_ocp.statics.stiffness.EndStiffness.end_jacobian`; N/m).

        Parameters
        ----------
        w : ndarray
            Converged scaled unknowns of this solver.
        p : ndarray
            Parameter vector of the solve (:meth:`Formulation.params`).
        """
        return self._sensitivities().end_jacobian(w, p)

    def length_sensitivity(self, w: np.ndarray, p: np.ndarray) -> dict[str, Any]:
        """The end forces' and the grounded length's sensitivities to the unstretched
        length and the end positions, both ends fixed
        (:meth:`cable_ocp.statics.stiffness.EndStiffness.length_sensitivity`).

        Parameters
        ----------
        w : ndarray
            Converged scaled unknowns of this solver.
        p : ndarray
            Parameter vector of the solve (:meth:`Formulation.params`).
        """
        return self._sensitivities().length_sensitivity(w, p)

    def on_intervals(self, intervals: int) -> StaticsSolver:
        """The solver of this scene on ``intervals`` intervals, with this one's degree,
        scheme and contact (built on first use, kept in the shared cache).

        Parameters
        ----------
        intervals : int
            Number of collocation intervals.
        """
        if (intervals, self.grounded) not in self._cache:
            StaticsSolver(self.scene, intervals=intervals, degree=self.mesh.degree,
                          scheme=self.mesh.scheme, cache=self._cache, grounded=self.grounded)
        return self._cache[(intervals, self.grounded)]

    def _make_solution(self, w: np.ndarray, p: np.ndarray, ok: bool, how: str, it: int,
                       wall: float, diag: dict[str, Any], g: np.ndarray | None = None
                       ) -> StaticsSolution:
        """The solution at the unknowns w (:func:`cable_ocp.statics.line_solution.
        assemble_solution`), with this solver's hooks: the end stiffness on first use
        and the unknowns for a warm start by this solver."""
        if g is None:  # else the residual at w, from the Newton iteration
            g = self._kernel.g(w, p)
        sol = assemble_solution(self, w, p, g, ok, how, it, wall, diag)
        if np.all(np.isfinite(w)):
            # the end stiffness, computed on first use (StaticsSolution.stiffness)
            sol._stiffness_source = functools.partial(self.end_stiffness, w.copy(), p.copy())
            if all(self.scene.end_a.fixed_mask) and all(self.scene.end_b.fixed_mask):
                sol._jacobian_source = functools.partial(self.end_jacobian, w.copy(), p.copy())
                sol._length_source = functools.partial(self.length_sensitivity, w.copy(),
                                                       p.copy())
            # the unknowns themselves and their mesh, for a warm start by this solver
            sol._unknowns = (self._token, w.copy(), self.coll.mesh)
        return sol
