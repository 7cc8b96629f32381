"""Wang, Cheong & Chucheepsakul (1993): shooting-optimization in z (Wang et al. 1993).

The paper's own method, reproduced as a baseline (``solver.method =
"wang_shooting_optimization"``). Source: Wang et al. (1993).

Formulation (Wang et al. 1993, eqs (1)-(12))
------------------------------
The height z is the independent variable. With H = z_b - z_a (the paper's water depth when
end_a is on the seabed and end_b at the surface) and a weight scale W (N/m, the seed's
W_c = |weight in water|), the nondimensional variables are (Wang et al. (1993), after eq. (6))

    zbar = (z - z_a)/H,  xbar = (x - x_a)/H,  ybar = (y - y_a)/H,  sbar = s/H,
    Tbar = T/(W H),  Vbar = V/sqrt(g H),  alpha = rho g D H / (2 W),

and the state is (Tbar, theta, phi, xbar, ybar, sbar): tension, the heading of the tangent
from +x towards +y, and its elevation above the horizontal. With the unit vectors
e_t = (cos phi cos theta, cos phi sin theta, sin phi), e_b = (-sin theta, cos theta, 0)
(= e_z x e_t / |e_z x e_t|) and e_n = e_t x e_b, and the nondimensional loads
Pbar_t, Pbar_b, Pbar_n (load / W) along them, eqs (7)-(12) read

    dTbar/dzbar  = wbar/eps - Pbar_t / sin phi                               (7)
    dtheta/dzbar = -Pbar_b / (Tbar cos phi sin phi)                          (8)
    dphi/dzbar   = (wbar/eps cos phi - Pbar_n) / (Tbar sin phi)              (9)
    dxbar/dzbar  = cot phi cos theta,   dybar/dzbar = cot phi sin theta      (10), (11)
    dsbar/dzbar  = 1 / (eps sin phi)                                         (12)

where wbar = weight_in_water / W (= 1 for a sinking cable, as in the paper) and eps = 1 + T/EA is
the stretch. For an inextensible cable (EA = inf, the paper's case) eps = 1 and these are exactly
Wang et al. (1993) (7)-(12). **Finite EA is supported**, consistently with the rest of the project
(docs/conventions.md "Drag"): the weight is per unstretched length (hence wbar/eps per stretched
length), the drag per stretched length, and s is the unstretched arc length.

Loads (Wang et al. 1993, eqs (4)-(6), with the modulus signs)
-----------------------------------------------
The paper takes x along the current, so that u = (V, 0, 0). Here the actual current vector
u(z) (any heading, any depth profile, interpolated as in :mod:`cable_ocp.physics.current`)
is projected on the frame: u_t = u.e_t, u_b = u.e_b, u_n = u.e_n, and

* ``drag_law = "componentwise"`` (Wang et al. 1993, eqs (4)-(6), Wilson's model)::

      Pbar_t = pi alpha C_t |ubar_t| ubar_t,  Pbar_b = alpha C_n |ubar_b| ubar_b,
      Pbar_n = alpha C_n |ubar_n| ubar_n;

  with u = (V, 0, 0) these are Wang et al. (1993) (4)-(6) exactly (u_b = -V sin theta,
  u_n = -V sin phi cos theta).
* ``drag_law = "vector"`` (independence principle, not in the paper): the load is
  1/2 rho D (C_n |U_N| U_N + pi C_t |u_t| u_t e_t) with U_N = u - u_t e_t, *projected on*
  e_t, e_b, e_n: Pbar_b = alpha C_n |ubar_N| ubar_b, Pbar_n = alpha C_n |ubar_N| ubar_n,
  |ubar_N| = sqrt(ubar_b^2 + ubar_n^2); Pbar_t as above.

The moduli are exact (no smoothing, unlike the collocation solver's ``solver.smoothing``),
and the frame (e_b, e_n) is defined by theta everywhere, so no vertical blend is needed; but
eq. (8) is singular where the cable is vertical (cos phi = 0) unless Pbar_b = 0 there.

Method (Wang et al. 1993, eqs (18)-(25))
--------------------------
Fixed-step classical RK4 in zbar from 0 to 1, h = 1/N with N = ``solver.intervals`` (Wang et al.
1993, eqs (18)-(23); sbar is integrated as a sixth state, as (12) allows), from the unknown initial
values zeta = (Tbar(0), theta(0), phi(0)). Nelder-Mead (scipy) minimises the L1 objective

    (24)  Phi = |xbar(1) - X| + |ybar(1) - Y| + |Tbar(1) - F|     (top tension F given)
    (25)  Phi = |xbar(1) - X| + |ybar(1) - Y| + |sbar(1) - Lbar|  (length given)

and, as an extension, Phi = |xbar(1) - X| + |ybar(1) - Y| over (theta(0), phi(0)) with
Tbar(0) known when the tension is given at the bottom end (end_a).

Planar scenes (no current, or a current parallel at every depth to the vertical plane
through both ends, as in Berteaux's problem): theta(0) is fixed to the chord's heading
and not optimised; theta stays constant and the |ybar(1) - Y| term of (24)/(25) is zero
to round-off. Deviation from the paper, whose (27) keeps |ybar(1)|: with theta(0) free,
a trial theta(0) != 0 makes (8) singular where the cable passes through vertical (about
16 m below Berteaux's buoy, cos phi = 0), and with fine steps (N = 80) Nelder-Mead then
settled on a spurious twisted discrete solution (top angle off by 0.02 deg). Nelder-Mead is run with
xatol = fatol = 1e-12 and restarted from its result, with a fresh simplex a few times the
size of the last run's progress, until a restart improves Phi by less than 1 % (at most
``MAX_RESTARTS`` runs). The first simplex is built around the drag-free catenary through
both ends (:func:`cable_ocp.statics.initial_guess.initial_guess`), or around a warm start.

The z-formulation's implicit constraint (Wang et al. (1993), before "Solutions"): the cable must
rise monotonically in z, 0 < phi < pi, with positive tension. A trial that leaves it is given the
objective ``PENALTY + (1 - zbar reached)`` (feasible trials have Phi < PENALTY), so the simplex is
pushed back. If the optimum lies on that boundary (a profile that would need to touch down or turn
back in z), Phi stays non-zero and the status is a failure.

Status
------
A Nelder-Mead result is converged when the physical end mismatch,
``constraint_violation`` = the largest of |x(L) - x_b| / chord, |y(L) - y_b| / chord and
|T - T_given| / T_given (or |L - L_given| / L_given), is below
``max(solver.tolerance, TOLERANCE)`` with ``TOLERANCE = 1e-8``; otherwise the status is
``"not_converged"`` (the mismatch is finite but too large) or ``"infeasible"`` (the best
trial leaves the z-monotone domain). A converged result then follows the accuracy contract
shared by every method (:func:`cable_ocp.baselines.common.refine_to_accuracy`): it is
``"solved"`` only when its error estimate is <= ``solver.accuracy``; otherwise N is
doubled (up to ``MAX_STEPS`` = 320, see :func:`solve`) and a result still above the
accuracy is ``"inaccurate"``, with the estimate, the accuracy and the limit in the
message.

``error_estimate`` (-) compares the solution with the roots of the 2N- and 4N-step
shooting problems (Newton from the converged initial values, :func:`_estimate`): the
larger of the end-force difference over the largest tension and the position and length
differences over the length, with the observed order (clipped to [1, 4]) in Richardson's
factor. It tracks the true error to within a few per cent where RK4 is in its asymptotic
range (true/estimate 0.96-1.00 on De Zoysa at 45-135 deg and Berteaux, 0.37-1.05 on the
extreme scenes; docs/baselines.md): 4.7e-5 for De Zoysa (psi0 = 90 deg) at h = 0.05, and
1e-7 for Berteaux.

Where the exact profile would touch down or dip below end_a (De Zoysa at psi0 >= 148 deg
with the componentwise law; the 5000 N top-tension variant at psi0 = 0), the discrete
shooting problem still has a root, but with phi(0) -> 0 as h -> 0: its first RK4 step
stands in for a horizontal run along the seabed, the mismatch with the finer roots stays
large and the estimate stays above 1e-2 (or does not exist, the finer integrations
leaving the domain) whatever h, so the result is ``"inaccurate"``: reporting such a root
as "solved" would be a wrong answer reported as success. This is how "phi hitting 0"
shows at a finite step. (Near but before touchdown, e.g. psi0 = 145 deg, the profile is
legitimate but so poorly resolved in z that it stays "inaccurate" up to the step limit.)

Representable scenes (else :class:`~cable_ocp.errors.CableOCPError`): end_a fully fixed
(position), end_b fully fixed strictly above it, and either the length or one end tension
given. The paper's own examples are of this kind (Wang et al. 1993, eqs (13)-(16), (28)).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
from scipy.optimize import minimize

from cable_ocp.baselines.common import (
    Estimate,
    compare,
    double_within,
    observed_order,
    refine_to_accuracy,
    rising_fixed_ends,
    unsupported,
)
from cable_ocp.errors import CableOCPError
from cable_ocp.physics.current import profile_components_np
from cable_ocp.physics.drag import drag_in_local_basis, line_drag_factors
from cable_ocp.scene import Scene
from cable_ocp.statics.initial_guess import initial_guess
from cable_ocp.statics.registry import register
from cable_ocp.statics.solution import StaticsSolution

METHOD = "wang_shooting_optimization"
TOLERANCE = 1e-8
MAX_STEPS = 320
PENALTY = 1.0e3
MAX_RESTARTS = 30
MAX_FEV_PER_RUN = 4000

__all__ = ["MAX_STEPS", "METHOD", "TOLERANCE", "WangProblem", "solve"]


def _fail(reason: str) -> CableOCPError:
    return unsupported(METHOD, reason)


class WangProblem:
    """The nondimensional z-formulation of a scene (Wang et al. 1993, eqs (7)-(12)) and its RK4
    shooting.

    Parameters
    ----------
    scene : Scene
        A scene with both ends fully fixed, end_b above end_a, and the length or one end
        tension given.

    Attributes
    ----------
    height : float
        H = z_b - z_a, m (the paper's water depth).
    weight_scale : float
        W, N/m: |weight in water|, or the drag scale for a neutrally buoyant cable.
    alpha : float
        rho g D H / (2 W) (-), Wang et al. (1993) after eq. (6).
    vbar : float
        Largest current speed / sqrt(g H) (-), Wang et al. (1993) eqs (26a), (30a).
    target : tuple of float
        (X, Y, third) with X, Y the nondimensional top-end offsets (Wang et al. 1993, eqs (13)-(14))
        and third = F (top tension, (15)), Lbar (length, (16)) or Tbar(0) (bottom tension).
    mode : str
        ``"top_tension"``, ``"length"`` or ``"bottom_tension"``.
    """

    def __init__(self, scene: Scene):
        env, cab = scene.environment, scene.cable
        ea, eb = scene.end_a, scene.end_b
        za, zb = rising_fixed_ends(
            scene, METHOD,
            "Wang et al. (1993) eqs (10)-(16) integrate from a fixed bottom end to a fixed top end")
        self.scene = scene
        self.origin = np.array(ea.position, dtype=float)
        self.height = h_ = zb - za
        d = np.array(eb.position, dtype=float) - self.origin
        self.chord = float(np.linalg.norm(d))
        rho, g = env.water_density, env.gravity
        w = cab.weight_in_water
        cur = env.current
        if w != 0.0:
            wscale = abs(w)
        elif cur is not None:
            wscale = line_drag_factors(rho, cab.diameter, cab.normal_drag,
                                       cab.tangential_drag)[0] * cur.max_speed**2
        else:
            raise _fail("a weightless cable in still water has no defined shape")
        self.weight_scale = wscale
        self.wbar = w / wscale
        self.alpha = rho * g * cab.diameter * h_ / (2.0 * wscale)
        self.sqrt_gh = math.sqrt(g * h_)
        self.vbar = (cur.max_speed / self.sqrt_gh) if cur is not None else 0.0
        self.ea_bar = (cab.axial_stiffness / (wscale * h_)) if cab.elastic else math.inf
        if ea.tension is not None:
            self.mode, third = "bottom_tension", ea.tension / (wscale * h_)
        elif eb.tension is not None:
            self.mode, third = "top_tension", eb.tension / (wscale * h_)
        else:
            self.mode, third = "length", float(cab.length) / h_  # type: ignore[arg-type]
        self.target = (float(d[0] / h_), float(d[1] / h_), float(third))
        # planar scene: current (every knot) parallel to the horizontal chord, or none
        self.plane_heading: float | None = None
        hx, hy = float(d[0]), float(d[1])
        hn = math.hypot(hx, hy)
        if hn > 1e-12 * self.chord:
            knots = list(zip(cur.ux, cur.uy, strict=True)) if cur is not None else []
            if all(abs(ux * hy - uy * hx) <= 1e-12 * hn * math.hypot(ux, uy)
                   for ux, uy in knots):
                self.plane_heading = math.atan2(hy, hx)
        self.rhs = self._make_rhs()

    # -- equations (Wang et al. 1993, (7)-(12)) ----------------------------------------------------
    def _make_rhs(self) -> Callable[..., tuple[float, ...]]:
        scene = self.scene
        cab, cur = scene.cable, scene.environment.current
        alpha, wbar, ea_bar = self.alpha, self.wbar, self.ea_bar
        kn = alpha * cab.normal_drag
        kt = math.pi * alpha * cab.tangential_drag
        law = cab.drag_law
        elastic = math.isfinite(ea_bar)
        sin, cos = math.sin, math.cos
        if cur is None:
            def vel(_z: float) -> tuple[float, float]:
                return 0.0, 0.0
        elif cur.uniform:
            u0 = (cur.ux[0] / self.sqrt_gh, cur.uy[0] / self.sqrt_gh)

            def vel(_z: float) -> tuple[float, float]:
                return u0
        else:
            kz = np.asarray(cur.z, dtype=float)
            kx = np.asarray(cur.ux, dtype=float) / self.sqrt_gh
            ky = np.asarray(cur.uy, dtype=float) / self.sqrt_gh
            z_a, h_ = float(self.origin[2]), self.height

            def vel(z: float) -> tuple[float, float]:
                ux_, uy_ = profile_components_np(z_a + h_ * z, kz, kx, ky)
                return float(ux_), float(uy_)

        def rhs(z: float, tb: float, th: float, ph: float) -> tuple[float, ...]:
            sp, cp, st, ct = sin(ph), cos(ph), sin(th), cos(th)
            ux, uy = vel(z)
            eps = 1.0 + tb / ea_bar if elastic else 1.0
            # projections of the current on e_t, e_b, e_n (Wang et al. 1993, (4)-(6)
            # for u = (V, 0, 0))
            uh = ux * ct + uy * st
            ut = cp * uh
            ub = -ux * st + uy * ct
            un = -sp * uh
            pt, pb, pn = drag_in_local_basis(law, ut, ub, un, kn, kt)
            we = wbar / eps
            cot = cp / sp
            return (we - pt / sp,                       # (7)
                    -pb / (tb * cp * sp),               # (8)
                    (we * cp - pn) / (tb * sp),         # (9)
                    cot * ct,                           # (10)
                    cot * st,                           # (11)
                    1.0 / (eps * sp))                   # (12)
        return rhs

    # -- RK4 (Wang et al. 1993, (18)-(23)) ---------------------------------------------------------
    def integrate(self, zeta: tuple[float, float, float], n: int, keep: bool = False
                  ) -> tuple[np.ndarray | None, float]:
        """Integrate from zbar = 0 to 1 in ``n`` RK4 steps (Wang et al. 1993, eqs (18)-(23)).

        Parameters
        ----------
        zeta : tuple of float
            (Tbar(0), theta(0) rad, phi(0) rad).
        n : int
            Number of steps, h = 1/n.
        keep : bool
            Return all nodes (shape (n+1, 6)) instead of the last one (shape (6,)).

        Returns
        -------
        states : ndarray or None
            (Tbar, theta, phi, xbar, ybar, sbar) at the nodes, or None when a stage left
            the domain 0 < phi < pi, Tbar > 0 (the cable would turn back in z or go slack).
        reached : float
            zbar reached before leaving the domain (1.0 on success).
        """
        f = self.rhs
        h = 1.0 / n
        tb, th, ph = (float(v) for v in zeta)
        x = y = s = 0.0
        out = [(tb, th, ph, x, y, s)] if keep else None
        pi = math.pi
        try:
            for k in range(n):
                z = k * h
                if not (0.0 < ph < pi and tb > 0.0):
                    return None, z
                a1 = f(z, tb, th, ph)
                t2, h2, p2 = tb + 0.5 * h * a1[0], th + 0.5 * h * a1[1], ph + 0.5 * h * a1[2]
                if not (0.0 < p2 < pi and t2 > 0.0):
                    return None, z
                a2 = f(z + 0.5 * h, t2, h2, p2)
                t3, h3, p3 = tb + 0.5 * h * a2[0], th + 0.5 * h * a2[1], ph + 0.5 * h * a2[2]
                if not (0.0 < p3 < pi and t3 > 0.0):
                    return None, z
                a3 = f(z + 0.5 * h, t3, h3, p3)
                t4, h4, p4 = tb + h * a3[0], th + h * a3[1], ph + h * a3[2]
                if not (0.0 < p4 < pi and t4 > 0.0):
                    return None, z
                a4 = f(z + h, t4, h4, p4)
                c = h / 6.0
                tb += c * (a1[0] + 2.0 * a2[0] + 2.0 * a3[0] + a4[0])
                th += c * (a1[1] + 2.0 * a2[1] + 2.0 * a3[1] + a4[1])
                ph += c * (a1[2] + 2.0 * a2[2] + 2.0 * a3[2] + a4[2])
                x += c * (a1[3] + 2.0 * a2[3] + 2.0 * a3[3] + a4[3])
                y += c * (a1[4] + 2.0 * a2[4] + 2.0 * a3[4] + a4[4])
                s += c * (a1[5] + 2.0 * a2[5] + 2.0 * a3[5] + a4[5])
                if out is not None:
                    out.append((tb, th, ph, x, y, s))
        except (ZeroDivisionError, OverflowError):
            return None, 0.0
        if not (0.0 < ph < pi and tb > 0.0 and math.isfinite(x + y + s + th)):
            return None, 1.0
        if out is not None:
            return np.array(out), 1.0
        return np.array([tb, th, ph, x, y, s]), 1.0

    # -- objective (Wang et al. 1993, (24), (25)) --------------------------------------------------
    def unknowns_to_zeta(self, v: np.ndarray) -> tuple[float, float, float]:
        """Optimisation variables -> (Tbar(0), theta(0), phi(0))."""
        vals = [float(a) for a in v]
        tb = self.target[2] if self.mode == "bottom_tension" else vals.pop(0)
        th = self.plane_heading if self.plane_heading is not None else vals.pop(0)
        return tb, th, vals[0]

    def zeta_to_unknowns(self, zeta: tuple[float, float, float]) -> np.ndarray:
        """(Tbar(0), theta(0), phi(0)) -> optimisation variables."""
        out = [] if self.mode == "bottom_tension" else [zeta[0]]
        if self.plane_heading is None:
            out.append(zeta[1])
        out.append(zeta[2])
        return np.array(out, dtype=float)

    def residuals(self, end: np.ndarray) -> tuple[float, float, float]:
        """End mismatches (xbar(1) - X, ybar(1) - Y, third) (Wang et al. 1993, (24)/(25))."""
        x_t, y_t, third = self.target
        if self.mode == "top_tension":
            r3 = end[0] - third
        elif self.mode == "length":
            r3 = end[5] - third
        else:
            r3 = 0.0
        return float(end[3] - x_t), float(end[4] - y_t), float(r3)

    def objective(self, v: np.ndarray, n: int) -> float:
        """L1 objective Phi (Wang et al. 1993, eq. (24) or (25)); PENALTY + (1 - zbar) when
        infeasible.

        Parameters
        ----------
        v : numpy.ndarray
            The optimisation variables (:meth:`unknowns_to_zeta`), in order: Tbar(0) =
            T(0) / (W H) (-; left out when the tension at end_a is given), theta(0) (rad,
            the tangent's heading from +x towards +y; left out on a planar scene, where it
            is the chord's heading) and phi(0) (rad, the tangent's elevation above the
            horizontal).
        n : int
            Number of RK4 steps over zbar in [0, 1] (h = 1/n).

        Returns
        -------
        float
            Phi (-), the sum of the absolute end mismatches of :meth:`residuals`; at least
            ``PENALTY`` when a stage leaves the domain 0 < phi < pi, Tbar > 0.
        """
        end, reached = self.integrate(self.unknowns_to_zeta(v), n)
        if end is None:
            return PENALTY + (1.0 - reached)
        r = self.residuals(end)
        return abs(r[0]) + abs(r[1]) + abs(r[2])

    def violation(self, end: np.ndarray) -> float:
        """Largest relative end mismatch (-): positions over the chord, tension/length over
        its prescribed value."""
        r = self.residuals(end)
        pos = max(abs(r[0]), abs(r[1])) * self.height / self.chord
        third = abs(r[2]) / abs(self.target[2]) if self.mode != "bottom_tension" else 0.0
        return float(max(pos, third))


def _start(problem: WangProblem, warm_start: StaticsSolution | None
           ) -> tuple[tuple[float, float, float], float]:
    """Initial (Tbar, theta, phi) at end_a and a relative simplex size."""
    if warm_start is not None and warm_start.tension_vector.shape[0] > 0:
        t0 = np.asarray(warm_start.tension_vector[0], dtype=float)
        size = 0.02
    else:
        sigma = np.linspace(0.0, 1.0, 3)
        _, t, _, _ = initial_guess(problem.scene, sigma, "catenary")
        t0 = np.asarray(t[0], dtype=float)
        size = 0.1
    tmag = float(np.linalg.norm(t0))
    th = math.atan2(t0[1], t0[0]) if math.hypot(t0[0], t0[1]) > 1e-12 * tmag else 0.0
    ph = math.atan2(t0[2], math.hypot(t0[0], t0[1]))
    ph = min(max(ph, 0.02), math.pi - 0.02)  # must start inside the z-monotone domain
    return (tmag / (problem.weight_scale * problem.height), th, ph), size


def _simplex(v0: np.ndarray, steps: np.ndarray) -> np.ndarray:
    simplex = np.tile(v0, (v0.size + 1, 1))
    for i in range(v0.size):
        simplex[i + 1, i] += steps[i]
    return simplex


def _minimise(problem: WangProblem, v0: np.ndarray, steps: np.ndarray, n: int
              ) -> tuple[np.ndarray, float, int, int, int]:
    """Nelder-Mead with restarts. Returns (v, Phi, iterations, evaluations, runs)."""
    opts = {"xatol": 1e-12, "fatol": 1e-12, "maxfev": MAX_FEV_PER_RUN,
            "maxiter": MAX_FEV_PER_RUN}
    v, fbest = v0.copy(), problem.objective(v0, n)
    nit = nfev = runs = 0
    for _ in range(MAX_RESTARTS):
        res = minimize(problem.objective, v, args=(n,), method="Nelder-Mead",
                       options={**opts, "initial_simplex": _simplex(v, steps)})
        runs += 1
        nit += int(res.nit)
        nfev += int(res.nfev)
        improved = float(res.fun) < fbest
        moved = np.abs(res.x - v) if improved else np.zeros_like(v)
        gain = (fbest - float(res.fun)) / fbest if (improved and fbest > 0) else 0.0
        if improved:
            v, fbest = np.asarray(res.x, dtype=float), float(res.fun)
        if fbest == 0.0 or gain < 0.01:
            break
        # fresh simplex a few times the last progress, never below round-off
        steps = np.maximum(4.0 * moved, 1e-9 * np.maximum(np.abs(v), 1.0))
    return v, fbest, nit, nfev, runs


def _square_residuals(problem: WangProblem, end: np.ndarray) -> np.ndarray:
    """As many end residuals as unknowns (planar: the in-plane horizontal offset)."""
    rx, ry, r3 = problem.residuals(end)
    out = []
    if problem.plane_heading is not None:
        out.append(rx * math.cos(problem.plane_heading) + ry * math.sin(problem.plane_heading))
    else:
        out += [rx, ry]
    if problem.mode != "bottom_tension":
        out.append(r3)
    return np.array(out)


def _newton_root(problem: WangProblem, zeta: tuple[float, float, float], n: int
                 ) -> tuple[float, float, float] | None:
    """Root of the n-step shooting problem near ``zeta``: Newton with a forward-difference
    Jacobian (at most 4 steps, to a relative end mismatch of 1e-13), or None when an
    integration leaves the z-monotone domain or the Jacobian is singular."""
    v = problem.zeta_to_unknowns(zeta)
    for _ in range(4):
        end, _ = problem.integrate(problem.unknowns_to_zeta(v), n)
        if end is None:
            return None
        r0 = _square_residuals(problem, end)
        if np.max(np.abs(r0)) <= 1e-13 * max(1.0, abs(problem.target[2])):
            break
        jac = np.empty((r0.size, v.size))
        for j in range(v.size):
            dv = np.zeros_like(v)
            dv[j] = 1e-7 * max(abs(v[j]), 1.0)
            e2, _ = problem.integrate(problem.unknowns_to_zeta(v + dv), n)
            if e2 is None:
                return None
            jac[:, j] = (_square_residuals(problem, e2) - r0) / dv[j]
        try:
            v = v - np.linalg.solve(jac, r0)
        except np.linalg.LinAlgError:
            return None
    return problem.unknowns_to_zeta(v)


def _profile(problem: WangProblem, states: np.ndarray, n: int
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """s (m), positions (m) and tension vectors (N) at the RK4 nodes."""
    zs = np.linspace(0.0, 1.0, n + 1) if states.shape[0] == n + 1 else np.array([0.0])
    h_, wsc = problem.height, problem.weight_scale
    tb, th, ph = states[:, 0], states[:, 1], states[:, 2]
    tang = np.stack([np.cos(ph) * np.cos(th), np.cos(ph) * np.sin(th), np.sin(ph)], axis=1)
    pos = problem.origin + h_ * np.stack([states[:, 3], states[:, 4], zs], axis=1)
    return h_ * states[:, 5], pos, (tb * wsc * h_)[:, None] * tang


def _as_solution(problem: WangProblem, zeta: tuple[float, float, float], n: int
                 ) -> StaticsSolution | None:
    """The n-step RK4 profile from ``zeta`` as a solution (for comparisons), or None."""
    states, _ = problem.integrate(zeta, n, keep=True)
    if states is None:
        return None
    s, pos, ten = _profile(problem, states, n)
    return StaticsSolution(status="solved", message="", s=s, position=pos, tension_vector=ten,
                           length=float(s[-1]))


def _estimate(problem: WangProblem, zeta: tuple[float, float, float], n: int,
              sol: StaticsSolution, roots: dict[int, tuple[float, float, float]]) -> Estimate:
    """Error estimate of the N-step solution from the roots of the 2N- and 4N-step shooting
    problems (Newton from the converged zeta; no Nelder-Mead): with d1 = |x_N - x_2N| and
    d2 = |x_2N - x_4N| (end forces over the largest tension, positions at the N nodes and
    the length over the length), the observed order q = log2(d1/d2) is clipped to [1, 4]
    (RK4's nominal 4) and the error of x_N is d1 2^q / (2^q - 1). ``inf`` when a finer
    integration leaves the z-monotone domain (a profile that z cannot resolve). The 2N root
    is kept in ``roots`` as the refinement's starting point."""
    z2 = _newton_root(problem, zeta, 2 * n)
    z4 = _newton_root(problem, z2, 4 * n) if z2 is not None else None
    s2 = _as_solution(problem, z2, 2 * n) if z2 is not None else None
    s4 = _as_solution(problem, z4, 4 * n) if z4 is not None else None
    if s2 is None or s4 is None:
        steps = 2 * n if s2 is None else 4 * n
        return Estimate(math.inf, {"note": f"the shooting problem on {steps} RK4 steps has no "
                                           "root near this one inside the z-monotone domain"})
    roots[2 * n] = z2
    f1, p1, tmax = compare(s2, sol, "z")
    f2, p2, _ = compare(s4, s2, "z")
    rel1 = max(f1 / tmax, p1 / sol.length)
    rel2 = max(f2 / tmax, p2 / sol.length)
    q = observed_order(rel2, rel1, 1.0, 4.0, 4.0)
    factor = 2.0**q / (2.0**q - 1.0)
    return Estimate(factor * rel1, {
        "method": f"Richardson, N = {n}/{2 * n}/{4 * n} RK4 steps (finer roots by Newton), "
                  f"observed order {q:.2f} (clipped to [1, 4])",
        "observed_order": q, "force_N": factor * f1, "position_m": factor * p1}, q)


def _solve_steps(problem: WangProblem, n: int, warm_start: StaticsSolution | None,
                 zeta_start: tuple[float, float, float] | None = None) -> StaticsSolution:
    """Nelder-Mead on the n-step shooting problem (Wang et al. 1993, eqs (24)/(25)); no estimate."""
    scene = problem.scene
    t_start = time.perf_counter()
    if zeta_start is not None and warm_start is not None:
        # refinement: start at the Newton root of this level from the previous level's
        # estimate, with a simplex a few times the distance between the two levels' roots
        v0 = problem.zeta_to_unknowns(zeta_start)
        vp = problem.zeta_to_unknowns(tuple(warm_start.diagnostics["zeta"]))
        steps = np.maximum(10.0 * np.abs(v0 - vp), 1e-7 * np.maximum(np.abs(v0), 1.0))
    else:
        zeta0, size = _start(problem, warm_start)
        v0 = problem.zeta_to_unknowns(zeta0)
        steps = np.full(v0.size, size)
        if problem.mode != "bottom_tension":
            steps[0] = size * v0[0]
    v, phi_obj, nit, nfev, runs = _minimise(problem, v0, steps, n)
    zeta = problem.unknowns_to_zeta(v)
    states, reached = problem.integrate(zeta, n, keep=True)
    wall = time.perf_counter() - t_start
    tol = max(scene.solver.tolerance, TOLERANCE)
    diag = {"method": METHOD, "objective": phi_obj, "alpha": problem.alpha,
            "vbar": problem.vbar, "h": 1.0 / n, "zeta": tuple(zeta), "mode": problem.mode,
            "function_evaluations": nfev, "restarts": runs - 1, "tolerance": tol}
    if states is None:
        states = np.array([[zeta[0], zeta[1], zeta[2], 0.0, 0.0, 0.0]])
        viol = math.inf
        status = "infeasible"
        message = (f"Nelder-Mead ended outside the z-monotone domain (zbar reached "
                   f"{reached:.3g}): the profile would need phi <= 0 or >= pi (touch down "
                   "or turn back in z) or a slack cable, which z as the independent "
                   "variable cannot represent")
    else:
        viol = problem.violation(states[-1])
        phmin = math.degrees(float(states[:, 2].min()))
        if viol > tol:
            status = "not_converged"
            message = (f"Nelder-Mead stopped at Phi = {phi_obj:.3g}, end mismatch {viol:.2e} "
                       f"> {tol:.0e}; min phi = {phmin:.3g} deg (a profile that touches down "
                       "or turns back in z has no exact representation)")
        else:
            status, message = "solved", (f"{METHOD}: Phi = {phi_obj:.3g}, end mismatch "
                                         f"{viol:.2e} <= {tol:.0e} on {n} RK4 steps; min phi "
                                         f"= {phmin:.3g} deg")
    s, pos, ten = _profile(problem, states, n)
    return StaticsSolution(
        status=status, message=message, s=s, position=pos, tension_vector=ten,
        length=float(s[-1]), iterations=nit, wall_time_s=wall, constraint_violation=viol,
        diagnostics=diag)


def solve(scene: Scene, warm_start: StaticsSolution | None = None) -> StaticsSolution:
    """Solve a scene with Wang et al.'s shooting-optimization (Wang et al. 1993, eqs (7)-(25)).

    Parameters
    ----------
    scene : Scene
        Both ends fully fixed, end_b above end_a; the length or one end tension given.
        ``solver.intervals`` = N RK4 steps (h = 1/N in zbar; the paper uses h = 0.05).
    warm_start : StaticsSolution, optional
        A nearby solution: its force at end_a seeds the simplex (smaller simplex).

    Returns
    -------
    StaticsSolution
        At the N + 1 RK4 nodes (N after refinement). ``diagnostics`` holds ``method``,
        ``objective`` (final Phi, -), ``alpha``, ``vbar``, ``h``, ``zeta`` (Tbar(0),
        theta(0), phi(0)), ``function_evaluations`` and ``restarts``; ``wall_time_s`` is
        the last level's Nelder-Mead time.

    Notes
    -----
    The accuracy contract (:func:`cable_ocp.baselines.common.refine_to_accuracy`): the
    error estimate (:func:`_estimate`: observed order from N, 2N and 4N steps) is compared
    with ``solver.accuracy``; while above it, N is doubled (Nelder-Mead again, started at
    the 2N root found for the estimate) up to ``min(solver.max_intervals, MAX_STEPS)`` =
    320 steps by default. The cap is this method's own limit: each level is a fresh
    Nelder-Mead run of a few hundred to a few thousand RK4 shootings in Python (seconds at
    320 steps), and RK4's fourth order has every resolvable benchmark scene below 1e-6
    well before 320 steps (De Zoysa 45-135 deg: ~1e-7 at 160). Refinement also stops
    when RK4's order 4 predicts that the cap cannot reach the accuracy. Profiles that
    z cannot resolve (touchdown, phi -> 0) keep a large or no estimate and end
    ``"inaccurate"``.

    Raises
    ------
    CableOCPError
        If the scene cannot be represented with z as the independent variable.
    """
    problem = WangProblem(scene)
    roots: dict[int, tuple[float, float, float]] = {}

    def solve_at(n: int, warm: StaticsSolution | None) -> StaticsSolution:
        return _solve_steps(problem, n, warm, roots.get(n) if warm is not None else None)

    def estimate(n: int, sol: StaticsSolution) -> Estimate:
        est = _estimate(problem, tuple(sol.diagnostics["zeta"]), n, sol, roots)
        # the estimate compares the finer roots with the Nelder-Mead iterate itself, so
        # its end mismatch (algebraic error) is inside d1
        est.detail["algebraic"] = float(sol.constraint_violation)
        return est

    def finer(n: int, est: Estimate) -> tuple[int | None, str]:
        lim = min(scene.solver.max_intervals, MAX_STEPS)
        text = (f"this method's limit of {MAX_STEPS} RK4 steps (Nelder-Mead cost)"
                if lim == MAX_STEPS else f"solver.max_intervals = {lim}")
        return double_within(n, est, scene.solver.accuracy, lim, text, 4.0, "RK4 steps")

    return refine_to_accuracy(scene, METHOD, scene.solver.intervals, solve_at, estimate, finer,
                              warm_start, label=lambda n: f"{n} RK4 steps")


register("wang_shooting_optimization", solve)
