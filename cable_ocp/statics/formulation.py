"""Static cable equations of a scene, as CasADi functions (no discretisation here).

State along the unstretched arc length s (docs/conventions.md: tension carried as a vector, so
vertical and horizontal cables are regular):

    x = (r, T),  r = position (m),  T = tension vector (N), the force the part of the
                 cable beyond s (towards end_b) exerts on the part before it.

Equilibrium of an element ds and Hooke's law (Wang, Cheong & Chucheepsakul (1993),
eqs (1)-(3) in vector form; Huang (1992), eqs (2.1)-(2.5), (2.18)-(2.24)):

    dr/ds = (1 + |T|/EA) T/|T|                       (EA = inf: no stretch term built)
    dT/ds = -f,  f = (0, 0, -w) + (1 + |T|/EA) f_drag(U(z) , T/|T|)

with w the weight in water per unstretched length (N/m) and f_drag the drag per
stretched length (:mod:`cable_ocp.physics.drag`); the (1 + |T|/EA) factor converts it to
per unstretched length (Huang (1992), eq. (2.46), uses the strained segment length;
docs/conventions.md, "Drag").
No current: no drag terms are built.

A cable with a tension-strain table (``[cable] tension_strain``; 004 (12.4), EA depending
on the tension) has the stretch 1 + e(|T|) in place of 1 + |T|/EA, e(T) the table's
monotone PCHIP in tension (:meth:`cable_ocp.scene.parts.Cable.strain_at`,
:class:`cable_ocp.physics.elasticity.TensionStrainTable`); a viscoelastic cable is at rest
here and has its static modulus (``axial_stiffness``).

The equations are solved in scaled form: sigma = s/L in [0, 1], r = ell * rho,
T = F * tau, with a length scale ell and a force scale F chosen from the scene, so that
every unknown and residual is O(1) for the solvers.

Bending stiffness (``bending_stiffness`` = EI > 0 on a segment; Bielański, eqs (4)-(7),
treats the towed object as a beam but prints only a first-approximation deflection): when any
segment asks for it, every node carries two more states, x = (r, T, theta, M), and only
the stiff segments get equations for them. A stiff segment is a planar beam-cable in the
x-z plane (Kirchhoff rod, inextensible in bending), theta the angle of the tangent
t = (cos theta, 0, sin theta) from +x towards +z, M = EI dtheta/ds the bending moment
(N m; the moment vector is -M e_y), T the whole internal force (tension and shear):

    dr/ds = (1 + T.t/EA) t,   dT/ds = -f(t),   dtheta/ds = M/EI,
    dM/ds = (1 + T.t/EA) (t_z T_x - t_x T_z)      (= -shear; moment balance m' + r' x n = 0)

so the tangent comes from theta, not from T (a free tail with T = 0 is regular). Out of
the plane, dy/ds = T_y / F (F the force scale) only pins T_y = 0 when y is fixed at both
ends; scenes that could leave the x-z plane are rejected by the scene validation. With
M = 0 the last equation forces T || t: the cable. On flexible segments theta and M are
dummies (d/ds = 0, both 0 at the segment start). Conditions: M = 0 at a free or pinned
end and where a stiff segment meets a flexible one or a body; theta and M continuous
between two stiff segments. The moment is scaled by M_ref = min(F ell, sqrt(EI F)), the
boundary-layer moment of a tensioned beam.

End conditions (Huang (1992), eqs (2.6)-(2.15); Wang, Cheong & Chucheepsakul (1993),
eqs (13)-(17)), per component i at each end:
a prescribed position r_i = p_i, or a prescribed external load F_i on the attachment,
which at equilibrium means T_i(0) = -F_i at end_a and T_i(L) = +F_i at end_b. A
prescribed tension magnitude adds |T|^2 = T0^2 at its end and makes L an unknown.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from cable_ocp.physics.current import profile_velocity
from cable_ocp.physics.drag import (
    drag_error_bound,
    drag_per_length,
    line_drag_factors,
    point_drag,
    point_drag_error_bound,
)
from cable_ocp.physics.seabed import friction_gradient, grounded_tension_integral, plane_normal
from cable_ocp.scene import Body, Cable, End, Scene

NX = 6

# layout of the numeric parameter vector p
P_LENGTH = 0  # scaled length lambda = L/ell (used when the length is fixed)
P_END_A = slice(1, 4)  # scaled prescribed values at end_a (position/ell or force/F)
P_END_B = slice(4, 7)
P_TENSION = 7  # scaled prescribed tension magnitude
P_CURRENT = 8  # current scale (homotopy parameter, 1 = as specified)
NP = 9


@dataclass(frozen=True)
class Scales:
    """Reference length (m) and force (N) used to scale unknowns and residuals."""

    length: float
    force: float


def _structure_key(scene: Scene) -> tuple:
    """Everything about a scene that changes the equations (not just parameter values)."""
    c = scene.cable
    return (
        scene.environment,
        c.length is None,
        c.diameter,
        c.weight_in_water,
        c.axial_stiffness,
        c.tension_strain,
        c.normal_drag,
        c.tangential_drag,
        c.drag_law,
        tuple(s.bending_stiffness for s in scene.segments),
        scene.end_a.fixed_mask,
        scene.end_b.fixed_mask,
        scene.end_a.tension is not None,
        scene.end_b.tension is not None,
        scene.solver,
        scene.segments,
        scene.segment_intervals,
        scene.bodies,
    )


def reference_length(scene: Scene) -> float:
    """Length scale, m: the given length, else the chord between fixed ends."""
    if scene.cable.length is not None:
        return scene.cable.length
    a, b = scene.end_a.position, scene.end_b.position
    return max(math.dist(a, b), 1.0)  # type: ignore[arg-type]


class Formulation:
    """The scene's ODE right-hand side and end conditions in scaled variables.

    Built once per scene *structure*; the numeric parameter vector (:meth:`params`)
    carries the end values, length, tension and current scale, so sweeps over those
    reuse the same CasADi functions.

    Attributes
    ----------
    scene : Scene
        The scene it was built from.
    scales : Scales
        Reference length and force.
    rhs : casadi.Function
        ``rhs(x[6], lam, cscale) -> dx/dsigma[6]`` in scaled variables.
    terms : tuple of str
        Which physical terms were built (for diagnostics and tests).
    """

    def __init__(self, scene: Scene):
        self.scene = scene
        self.key = _structure_key(scene)
        env = scene.environment
        self.lines = scene.lines
        self.segmented = bool(scene.segments)
        ell = reference_length(scene)
        fref = max(abs(c.weight_in_water) for c in self.lines) * ell
        for body in scene.bodies:
            fref = max([fref, *(abs(f) for f in body.static_load)])
        for end in (scene.end_a, scene.end_b):
            fref = max([fref, *(abs(f) for f in end.force if f is not None)])
            if end.tension is not None:
                fref = max(fref, end.tension)
        cur = env.current
        if cur is not None:
            fref = max(fref, max(line_drag_factors(env.water_density, c.diameter,
                                                   c.normal_drag, c.tangential_drag)[0]
                                 * cur.max_speed**2 * ell for c in self.lines))
        if fref == 0.0:
            fref = 1.0
        self.scales = Scales(length=ell, force=fref)
        #: True for the segments with bending stiffness (EI > 0)
        self.stiff = tuple(c.bending_stiffness > 0.0 for c in self.lines)
        #: states per node: 6, or 8 (theta, M) when a segment has bending stiffness
        self.nx = NX + 2 if any(self.stiff) else NX
        ei_max = max((c.bending_stiffness for c in self.lines), default=0.0)
        #: moment scale M_ref, N m (1 without bending stiffness)
        self.moment_scale = min(fref * ell, math.sqrt(ei_max * fref)) if any(self.stiff) \
            else 1.0
        self.terms = self._build_terms()

        total = sum(c.length for c in self.lines) if self.segmented else 1.0
        #: share L_k / L of each segment in the unstretched length (-)
        self.fractions = (tuple(c.length / total for c in self.lines)  # type: ignore[operator]
                          if self.segmented else (1.0,))

    # the CasADi functions are built on first use: a solver whose collocated functions
    # come from the on-disk cache never needs them
    @functools.cached_property
    def rhs_list(self) -> tuple[ca.Function, ...]:
        """``rhs(x, lam, cscale) -> dx/dsigma`` of each segment (scaled)."""
        x = ca.SX.sym("x", self.nx)
        lam = ca.SX.sym("lam")
        cs = ca.SX.sym("cscale")
        return tuple(
            ca.Function("rhs", [x, lam, cs], [self._segment_rhs(x, lam, cs, c)],
                        ["x", "lam", "cscale"], ["dx"]) for c in self.lines)

    @property
    def rhs(self) -> ca.Function:
        """The first (or only) segment's right-hand side."""
        return self.rhs_list[0]

    @functools.cached_property
    def body_loads(self) -> tuple[ca.Function, ...]:
        """``load(x[6], cscale) -> P / F`` (scaled external load) of each body."""
        x, cs = ca.SX.sym("x", NX), ca.SX.sym("cscale")
        return tuple(
            ca.Function(f"body_load_{i}", [x, cs], [self._body_load_expr(b, x, cs)],
                        ["x", "cscale"], ["load"]) for i, b in enumerate(self.scene.bodies))

    @functools.cached_property
    def joint_loads(self) -> tuple[ca.Function, ...]:
        """The summed scaled load of the bodies at each joint k = 1 .. (x the joint state)."""
        x, cs = ca.SX.sym("x", NX), ca.SX.sym("cscale")
        return tuple(
            ca.Function(f"joint_load_{k}", [x, cs], [sum(
                (self.body_loads[i](x, cs) for i, b in enumerate(self.scene.bodies)
                 if b.joint == k), ca.SX.zeros(3))], ["x", "cscale"], ["load"])
            for k in range(1, len(self.lines)))

    # -- physics ------------------------------------------------------------------------
    def _build_terms(self) -> tuple[str, ...]:
        terms = ["weight"]
        if self.scene.environment.current is not None:
            terms.append(f"drag:{self.scene.cable.drag_law}")
        if any(c.elastic for c in self.lines):
            terms.append("stretch")
        if self.segmented:
            terms.append(f"segments:{len(self.lines)}")
        terms.extend(f"bending:{k}" for k, st in enumerate(self.stiff) if st)
        terms.extend(f"body:{b.kind}@{b.joint}" for b in self.scene.bodies)
        return tuple(terms)

    def _body_load_expr(self, body: Body, x: ca.SX, cscale: ca.SX) -> ca.SX:
        """Scaled external load P / F of one body at the joint state x (its height sets the
        current): weight, buoyancy, thrust and drag 0.5 rho C_d A |U| U (smooth modulus)."""
        env, sc = self.scene.environment, self.scales
        load = ca.DM(body.static_load)
        if body.has_drag and env.current is not None:
            cur = env.current
            u = profile_velocity(sc.length * x[2], cur.z, cur.ux, cur.uy, cscale)
            load = load + point_drag(u, (body.drag_coefficient * body.drag_area,) * 3,
                                     rho=env.water_density, delta=self.scene.solver.smoothing)
        return load / sc.force

    def body_load(self, index: int, position: np.ndarray, current_scale: float = 1.0
                  ) -> np.ndarray:
        """External load of ``scene.bodies[index]`` at ``position`` (m), N.

        Parameters
        ----------
        index : int
            Index of the body in ``scene.bodies``.
        position : array_like, shape (3,)
            The body's position (its joint), m; only its height z sets the current, and
            hence the drag.
        current_scale : float, default 1.0
            Factor on the current velocities (-), the homotopy parameter
            (``P_CURRENT``); 1 is the current as specified, 0 none.
        """
        x = np.concatenate([np.asarray(position, float) / self.scales.length, np.ones(3)])
        return np.asarray(self.body_loads[index](x, current_scale)).reshape(-1) \
            * self.scales.force

    def _segment_rhs(self, x: ca.SX, lam: ca.SX, cscale: ca.SX, cab: Cable) -> ca.SX:
        """Right-hand side of one segment with ``self.nx`` states (see module docstring)."""
        if self.nx == NX:
            return self._rhs_expr(x, lam, cscale, cab)
        if cab.bending_stiffness <= 0.0:
            return ca.vertcat(self._rhs_expr(x[0:NX], lam, cscale, cab), 0, 0)
        return self._beam_rhs(x, lam, cscale, cab)

    def _beam_rhs(self, x: ca.SX, lam: ca.SX, cscale: ca.SX, cab: Cable) -> ca.SX:
        """Planar beam-cable (x-z plane): x = (rho, tau, theta, m), scaled; d/dsigma."""
        sc, env = self.scales, self.scene.environment
        tau, theta, m = x[3:6], x[6], x[7]
        t = ca.vertcat(ca.cos(theta), 0, ca.sin(theta))
        stretch = 1.0
        if cab.elastic:
            stretch = 1.0 + cab.strain_at(sc.force * ca.dot(tau, t))
        f = ca.vertcat(0, 0, -cab.weight_in_water)
        if env.current is not None:
            cur = env.current
            u = profile_velocity(sc.length * x[2], cur.z, cur.ux, cur.uy, cscale)
            opts = self.scene.solver
            f = f + stretch * drag_per_length(
                cab.drag_law, u, t, rho=env.water_density, diameter=cab.diameter,
                normal_drag=cab.normal_drag, tangential_drag=cab.tangential_drag,
                delta=opts.smoothing, blend=opts.vertical_blend)
        mref = self.moment_scale
        # out of plane: dy/dsigma = lam tau_y keeps the system regular when y is fixed at
        # both ends (it pins T_y); the validated planar scenes have T_y = 0, y = const
        drho = lam * stretch * t + ca.vertcat(0, lam * tau[1], 0)
        dtau = -lam * (sc.length / sc.force) * f
        dtheta = lam * sc.length * mref / cab.bending_stiffness * m
        dm = lam * sc.length * sc.force / mref * stretch * (t[2] * tau[0] - t[0] * tau[2])
        return ca.vertcat(drho, dtau, dtheta, dm)

    def bending_joint_residual(self, k: int, x_prev: ca.MX | None, x_start: ca.MX,
                               x_end: ca.MX) -> list[ca.MX]:
        """Conditions on (theta, m) of segment k (scaled), given its first and last node
        and the last node of segment k - 1 (None for k = 0): a flexible segment's dummies
        are 0 at its start; a stiff one has M = 0 where it meets a flexible segment, a body
        or an end, and continuous theta, M after a stiff segment without a body between.

        Parameters
        ----------
        k : int
            Index of the segment (0 at end_a).
        x_prev : casadi.MX or None
            Scaled state (``nx`` values) of the last node of segment k - 1; None (not
            read) for k = 0.
        x_start, x_end : casadi.MX
            Scaled states (``nx`` values) of the first and last node of segment k; theta
            (index 6) in rad, M / M_ref (index 7) with M_ref = :attr:`moment_scale`.
        """
        if self.nx == NX:
            return []
        if not self.stiff[k]:
            return [x_start[6], x_start[7]]
        res = []
        joined = (k > 0 and self.stiff[k - 1]
                  and not any(b.joint == k for b in self.scene.bodies))
        if joined:
            res += [x_start[6] - x_prev[6], x_start[7] - x_prev[7]]
        else:
            res.append(x_start[7])
        last = k == len(self.lines) - 1
        nxt_joined = (not last and self.stiff[k + 1]
                      and not any(b.joint == k + 1 for b in self.scene.bodies))
        if not nxt_joined:
            res.append(x_end[7])
        return res

    def _rhs_expr(self, x: ca.SX, lam: ca.SX, cscale: ca.SX, cab: Cable | None = None
                  ) -> ca.SX:
        sc, env = self.scales, self.scene.environment
        cab = self.scene.cable if cab is None else cab
        rho_, tau = x[0:3], x[3:6]
        tmag = ca.sqrt(ca.dot(tau, tau))
        t = tau / tmag
        stretch = 1.0
        if cab.elastic:
            stretch = 1.0 + cab.strain_at(sc.force * tmag)
        # loads per unstretched length, N/m
        f = ca.vertcat(0, 0, -cab.weight_in_water)
        if env.current is not None:
            cur = env.current
            u = profile_velocity(sc.length * rho_[2], cur.z, cur.ux, cur.uy, cscale)
            opts = self.scene.solver
            fd = drag_per_length(
                cab.drag_law, u, t, rho=env.water_density, diameter=cab.diameter,
                normal_drag=cab.normal_drag, tangential_drag=cab.tangential_drag,
                delta=opts.smoothing, blend=opts.vertical_blend,
            )
            f = f + stretch * fd
        drho = lam * stretch * t
        dtau = -lam * (sc.length / sc.force) * f
        return ca.vertcat(drho, dtau)

    # -- end conditions -----------------------------------------------------------------
    def end_residual(self, end: End, x: ca.SX, values: ca.SX, at_a: bool) -> list[ca.SX]:
        """Residuals of the end conditions at one end (scaled).

        Parameters
        ----------
        end : End
            The end; its ``fixed_mask`` says per component whether the position (residual
            r_i - p_i) or the external load (residual T_i + F_i at end_a, T_i - F_i at
            end_b) is prescribed.
        x : casadi.SX
            Scaled state at that end, (rho, tau) = (r / ell, T / F) first.
        values : casadi.SX, shape (3,)
            Scaled prescribed values per component, position / ell or load / F (the
            ``P_END_A`` or ``P_END_B`` part of the parameters).
        at_a : bool
            True at end_a (s = 0), where the cable's tension is minus the external load;
            False at end_b (s = L), where it equals it.
        """
        res = []
        sign = -1.0 if at_a else 1.0
        for i, fixed in enumerate(end.fixed_mask):
            if fixed:
                res.append(x[i] - values[i])
            else:
                res.append(x[3 + i] - sign * values[i])
        return res

    def touchdown_residual(self, x0: ca.MX, g: ca.MX, anchor: ca.MX) -> list[ca.MX]:
        """End conditions at end_a when its cable lies on the seabed for a length g
        (scaled): the touchdown point is where the anchor's straight grounded line ends
        (stretched), and the cable is tangent to the seabed there (T . n = 0).
        See :mod:`cable_ocp.physics.seabed`.

        Parameters
        ----------
        x0 : casadi.MX
            Scaled state at the touchdown point, the first node of the suspended part:
            (r / ell, T / F) first.
        g : casadi.MX
            Scaled grounded (unstretched) length, g / ell, from end_a to the touchdown.
        anchor : casadi.MX, shape (3,)
            Scaled position of end_a, r_a / ell (the ``P_END_A`` parameters).
        """
        sb = self.scene.environment.seabed
        cab, sc = self.scene.cable, self.scales
        n = plane_normal(sb.slope_deg, sb.slope_heading_deg)
        tau = x0[3:6]
        tmag = ca.sqrt(ca.dot(tau, tau))
        e = tau / tmag
        k = friction_gradient(cab.weight_in_water, e, sb.friction, float(n[2])) \
            * sc.length / sc.force
        dist = g
        if cab.elastic:
            dist = g + sc.force / cab.axial_stiffness * grounded_tension_integral(tmag, k, g)
        res = [x0[i] - (anchor[i] + e[i] * dist) for i in range(3)]
        res.append(ca.dot(tau, ca.DM(n)))
        return res

    def tension_residual(self, x: ca.SX, tension: ca.SX) -> ca.SX:
        """|tau|^2 - tau0^2 (scaled).

        Parameters
        ----------
        x : casadi.SX
            Scaled state at the end whose tension is prescribed; tau = T / F is
            ``x[3:6]``.
        tension : casadi.SX
            Scaled prescribed tension magnitude tau0 = T0 / F (the ``P_TENSION``
            parameter).
        """
        return ca.dot(x[3:6], x[3:6]) - tension * tension

    # -- parameters ---------------------------------------------------------------------
    def params(self, scene: Scene | None = None, current_scale: float = 1.0) -> np.ndarray:
        """Numeric parameter vector for ``scene`` (which must share this structure).

        Parameters
        ----------
        scene : Scene, optional
            The scene whose values to take (the length, the end values, the prescribed
            tension); it must have this formulation's structure, else ValueError.
            Default: the scene the formulation was built from.
        current_scale : float, default 1.0
            Factor on the current velocities (-), the homotopy parameter stored at
            ``P_CURRENT``; 1 is the current as specified.

        Returns
        -------
        numpy.ndarray, shape (NP,)
            Scaled parameters: L / ell (1 when the length is free), the end values
            (position / ell or load / F), T0 / F (0 when no tension is prescribed) and
            the current scale.
        """
        scene = self.scene if scene is None else scene
        if scene is not self.scene and _structure_key(scene) != self.key:
            raise ValueError("scene structure differs from the one this formulation was built for")
        sc = self.scales
        p = np.zeros(NP)
        p[P_LENGTH] = (scene.cable.length or sc.length) / sc.length
        for sl, end in ((P_END_A, scene.end_a), (P_END_B, scene.end_b)):
            p[sl] = [v / (sc.length if fixed else sc.force)
                     for v, fixed in zip(end.values, end.fixed_mask, strict=True)]
        tension = scene.end_a.tension or scene.end_b.tension
        p[P_TENSION] = (tension or 0.0) / sc.force
        p[P_CURRENT] = current_scale
        return p

    def smoothing_force_bound(self, length: float, max_tension: float) -> float:
        """Bound (N) on the total drag error from the smooth modulus over the cable.

        Parameters
        ----------
        length : float
            Unstretched length of the cable, m. Not used on a multi-segment line, where
            each segment's own length is taken (and each body's point-drag bound added).
        max_tension : float
            Largest tension magnitude along the cable, N; it bounds the stretch factor
            (1 + T/EA) that converts the drag to per unstretched length.
        """
        env, cab = self.scene.environment, self.scene.cable
        if env.current is None:
            return 0.0
        if self.segmented:
            total = 0.0
            for c in self.lines:
                per_len = drag_error_bound(
                    c.drag_law, rho=env.water_density, diameter=c.diameter,
                    normal_drag=c.normal_drag, tangential_drag=c.tangential_drag,
                    delta=self.scene.solver.smoothing)
                total += per_len * c.length * (
                    1.0 + (float(c.strain_at(max_tension)) if c.elastic else 0.0))
            delta = self.scene.solver.smoothing
            for b in self.scene.bodies:
                if b.has_drag:  # |sqrt(u^2 + d^2) u - |u| u| <= d^2 / 2
                    total += point_drag_error_bound((b.drag_coefficient * b.drag_area,),
                                                    rho=env.water_density, delta=delta)
            return total
        per_len = drag_error_bound(
            cab.drag_law, rho=env.water_density, diameter=cab.diameter,
            normal_drag=cab.normal_drag, tangential_drag=cab.tangential_drag,
            delta=self.scene.solver.smoothing,
        )
        stretch = 1.0 + (float(cab.strain_at(max_tension)) if cab.elastic else 0.0)
        return per_len * length * stretch
