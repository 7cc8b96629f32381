"""The cable models that can be the heave plant, and the one place that picks among them.

:func:`cable_plant` reads the cable scene's ``[simulation] model``:

* ``"axial"`` (default of a dynamic scene): :class:`cable_ocp.heave.cable_plant.AxialCablePlant`,
  the vertical line of Huang (1992), ch. 3;
* ``"planar"``: :class:`PlanarCablePlant`, the line in a vertical plane of Huang (1992),
  ch. 4 (:class:`cable_ocp.dynamics.planar.PlanarModel`): the same heave and pay-out at
  the top, and the line swings out of the vertical in a current along x (sway, and the
  vertical motion that the inclined line couples to it);
* ``"lumped3d"`` is refused: the lumped-mass model of Huang (1992), ch. 5
  (:class:`cable_ocp.dynamics.lumped.LumpedMassModel`) has fixed segment lengths (its
  unstretched lengths, node masses and weights are constants of its compiled residual) and a
  top motion that is a closed-form function of time, so the winch cannot pay cable in or
  out at the top. A plant on it needs the top segment's length and the top position as
  parameters of each step (a change to that model's step builder).

Both plants have the interface that the closed loop (:func:`cable_ocp.heave.cable_plant.run_loop`
through ``_CableLoopPlant``) and the identification experiment use: ``substeps``, ``dt``,
``length0``, ``z_top0``, ``tolerance``, ``model.n``, :meth:`initial_state`,
:meth:`static_unit_height`, :meth:`static_tensions`, :meth:`advance` and
:meth:`run_open_loop`.
"""

from __future__ import annotations

import copy
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.planar import PlanarModel
from cable_ocp.dynamics.scene import DynamicScene, dynamic_scene_from_dict
from cable_ocp.errors import CableOCPError
from cable_ocp.heave.cable_plant import (
    AxialCablePlant,
    SampledCablePlant,
    _compile,
    sampled_motion,
)

__all__ = ["HALVINGS", "PLANT_MODELS", "PlanarCablePlant", "axial_twin", "cable_plant"]

#: the cable scene's ``simulation.model`` values that can be the heave plant
PLANT_MODELS = ("axial", "planar")
#: times a planar step whose Newton iteration fails is halved (down to 1/8 of the step)
HALVINGS = 3


def cable_plant(scene: DynamicScene, sample_time: float) -> Any:
    """The heave plant of a cable scene, chosen by its ``[simulation] model``.

    Parameters
    ----------
    scene : DynamicScene
        The cable scene (``[unit] cable_scene`` of the heave file).
    sample_time : float
        Control sample, s (the scene's ``time_step`` must divide it).

    Returns
    -------
    AxialCablePlant or PlanarCablePlant

    Raises
    ------
    CableOCPError
        For ``model = "lumped3d"`` (module docstring) or a scene the model refuses.
    """
    model = scene.simulation.model
    if model == "axial":
        return AxialCablePlant(scene, sample_time)
    if model == "planar":
        return PlanarCablePlant(scene, sample_time)
    raise CableOCPError(
        f"simulation.model = {model!r} in the cable scene: the heave plant takes "
        f"{' or '.join(repr(m) for m in PLANT_MODELS)}; the lumped-mass model has fixed "
        "segment lengths, so the winch cannot pay cable in or out at its top")


def axial_twin(scene: DynamicScene) -> DynamicScene:
    """The same line as an axial scene: no current, no top motion, ``model = "axial"``
    (its first axial frequency is the identification's reference ``omega_1``)."""
    if scene.simulation.model == "axial":
        return scene
    raw = copy.deepcopy(scene.raw)
    raw.setdefault("simulation", {})["model"] = "axial"
    raw.pop("top_motion", None)
    if isinstance(raw.get("environment"), dict):
        raw["environment"].pop("current", None)
    return dynamic_scene_from_dict(raw)


class _SteppedPlanar(PlanarModel):
    """The planar model with the top height and the unstretched length as parameters.

    As the axial plant's: over one step of ``dt`` both are linear in time between their
    values at the start and the end of the step, ``p = [L_a, L_b, z_a, z_b]`` (m); the top
    stays at its static x. Time ``t`` runs from 0 to ``dt`` within the step; ``dt`` (s) is
    a parameter too (:attr:`motion_params` = ``[p; dt]``).
    """

    def __init__(self, scene: DynamicScene) -> None:
        super().__init__(scene)
        #: the step, s: a symbol, so that one compiled step serves every step size (the
        #: halving of a step whose Newton iteration does not converge)
        self.dt = dt = ca.SX.sym("dt")
        p = ca.SX.sym("p", 4)
        self.motion_params = ca.vertcat(p, dt)
        self.motion = sampled_motion(scene.top_position, p, dt)


class PlanarCablePlant(SampledCablePlant):
    """The planar cable model (Huang (1992), ch. 4) advanced one control sample per call.

    The boom-tip heave moves the top (end_b) vertically, the winch output ``u`` pays cable
    in there (``L = L_dep - u``), as :class:`cable_ocp.heave.cable_plant.AxialCablePlant`;
    the top keeps its static x. A current along x (``[environment.current]`` of the cable
    scene) inclines the line and drags on the unit and the cable as they move. Each
    sub-step is the planar model's own implicit-midpoint step with its discrete-gradient
    tension (:meth:`cable_ocp.dynamics.planar.PlanarModel._step_expressions`), with ``L``,
    the top height and the step size as parameters, solved by Newton's method (compiled;
    a step that does not converge is halved, :meth:`_build`).

    Outputs per sub-step: the unit's height and vertical velocity, the tension at the unit
    (the magnitude of the force that the cable exerts on it: element 0's tension less the
    half element that the unit's node carries, its inertia at the step's mean
    acceleration), the top tension
    (the top node's balance without its acceleration: ``L`` and the top height are linear
    within a step, as in the axial plant) and the smallest element tension.

    Parameters
    ----------
    scene : DynamicScene
        A planar scene with a unit (``[simulation] model = "planar"``): ``segments``,
        ``time_step`` (must divide ``sample_time``), ``tolerance``, ``max_iterations``.
        Its ``[top_motion]`` is not used.
    sample_time : float
        Control sample ``h``, s.
    """

    _chunk_name = "planar_chunk"

    #: the cable scene's ``simulation.model`` of this plant
    model_name = "planar"

    def __init__(self, scene: DynamicScene, sample_time: float) -> None:
        sim = scene.simulation
        if sim.model != "planar":
            raise CableOCPError(f"PlanarCablePlant: simulation.model = {sim.model!r}; "
                                'expected "planar"')
        if scene.unit is None:
            raise CableOCPError('simulation.model = "planar" as the heave plant: the cable '
                                "scene needs a [unit] at end_a (the unit the winch lifts)")
        ratio = sample_time / sim.time_step
        m = int(round(ratio))
        if m < 1 or abs(ratio - m) > 1e-9 * max(1.0, ratio):
            raise CableOCPError(f"cable scene: [simulation] time_step = {sim.time_step} s must "
                                f"divide the control sample time {sample_time} s")
        self.scene = scene
        self.h = float(sample_time)
        self.substeps = m
        self.dt = self.h / m
        self.length0 = scene.length
        self.z_top0 = float(scene.top_position[2])
        self.tolerance = sim.tolerance
        # the static state: the statics solution refined to the discrete equilibrium, by
        # the model with the scene's own (time) motion at t = 0 (the static top, L0)
        base = PlanarModel(scene if sim.start == "static"
                           else scene.with_overrides({"simulation.start": "static"}))
        x0, info = base.initial_state()
        if x0 is None:
            raise CableOCPError(f"cable scene: the planar line's static state failed: "
                                f"{info.get('message', '')}")
        self._x0 = np.asarray(x0, dtype=float)
        self.model = _SteppedPlanar(scene)
        self.model.force_scale = base.force_scale
        self.nf = self.model.nf
        self._sample = self._build(sim.tolerance, sim.max_iterations, HALVINGS)
        self._chunks: dict[int, ca.Function] = {}
        p_static = np.array([self.length0, self.length0, self.z_top0, self.z_top0, self.dt])
        r = self._outputs_at(self._x0, p_static)
        self._z_static = float(r[0])
        self._t_static = (float(r[2]), float(r[3]))

    def _build(self, tol: float, max_iter: int, halvings: int) -> ca.Function:
        """The sample function ``(x, P) -> (x_next, z_unit, v_unit, t_unit, t_top, t_min,
        residual)`` over ``substeps`` midpoint steps (as the axial plant's).

        Each step is Newton's method on the planar model's midpoint residual in the new
        offsets, from the model's explicit predictor: two iterations, then more (up to
        ``max_iterations``) only while the scaled residual exceeds the tolerance (a
        short-circuit switch, as the axial plant). The Newton matrix (block banded: the
        pay-out terms reach two nodes each way) is solved by CasADi's sparse QR, which,
        unlike the ``rootfinder``, generates C: the functions are compiled as the axial
        plant's (:func:`cable_ocp.heave.cable_plant._compile`). Where a step does not
        converge (the residual above the failure threshold ``1e3 tolerance``: a line going
        slack, where the no-compression law bends sharply), it is taken again as two steps
        of half the size, recursively up to ``halvings`` times (only then evaluated).
        """
        md = self.model
        nf2 = 2 * self.nf
        p = md.motion_params  # [L_a, L_b, z_a, z_b, dt]
        dt = md.dt
        q1, q0, v0, t0, res, v1, _, pred = md._step_expressions(dt)
        res, v1, pred = ca.substitute([res, v1, pred], [t0], [ca.SX(0.0)])
        pars = ca.vertcat(q0, v0, p)
        fj = ca.Function("planar_fj", [q1, pars], [res, ca.jacobian(res, q1)])
        xs = ca.MX.sym("q1", nf2)
        ps = ca.MX.sym("pars", pars.shape[0])
        rk, jk = fj(xs, ps)
        newton = ca.Function("planar_newton", [xs, ps], [xs - ca.solve(jk, rk, "qr")])
        resid = ca.Function("planar_resid", [q1, pars], [ca.norm_inf(res)])
        guess = ca.Function("planar_guess", [pars], [pred])
        post = ca.Function("planar_post", [q1, pars], [v1])
        # outputs at the end of the step (t = dt)
        outf = md.output_function()
        qs = ca.SX.sym("q", nf2)
        vs = ca.SX.sym("v", nf2)
        va = ca.SX.sym("va", nf2)  # velocities at the start of the step
        rs, tens, top, _, vel, _ = outf(dt, qs, vs, p)
        # the pull on the unit: element 0's tension along its chord, less the half element
        # that node 0 carries (weight in water, drag, inertia at the step's mean
        # acceleration), as the axial plant's
        h_el = p[1] / md.n
        d0 = rs[:, 1] - rs[:, 0]
        urel = (md._current(0.5 * (rs[1, 0] + rs[1, 1]))
                - 0.5 * (vel[:, 0] + vel[:, 1]))
        drag_half = 0.5 * md._element_drag(d0, urel)
        l2 = ca.dot(d0, d0)
        txx, txz, tzz = d0[0] ** 2 / l2, d0[0] * d0[1] / l2, d0[1] ** 2 / l2
        half = 0.5 * h_el
        mxx = half * (md.mu + md.man * (1.0 - txx) + md.mat * txx)
        mxz = half * (md.mat - md.man) * txz
        mzz = half * (md.mu + md.man * (1.0 - tzz) + md.mat * tzz)
        acc = (vs[0:2] - va[0:2]) / dt
        pull = (tens[0] * d0 / ca.norm_2(d0) + drag_half
                - ca.vertcat(mxx * acc[0] + mxz * acc[1],
                             mxz * acc[0] + mzz * acc[1] + 0.5 * md.w * h_el))
        out = ca.Function("planar_out", [qs, vs, va, p],
                          [ca.vertcat(rs[1, 0], vel[1, 0], ca.norm_2(pull), top,
                                      ca.mmin(tens))])
        newton, resid, guess, post, out = _compile([newton, resid, guess, post, out])
        self._out = out

        # one step: two iterations, then more while the residual exceeds tol
        xa = ca.MX.sym("xa", 2 * nf2)
        pm = ca.MX.sym("p", 5)
        pv = ca.vertcat(xa, pm)
        x2 = newton(newton(guess(pv), pv), pv)
        y = ca.vertcat(x2, resid(x2, pv))
        yb = ca.MX.sym("y", nf2 + 1)
        xb = newton(yb[:nf2], pv)
        more = ca.Function("more", [yb, xa, pm], [ca.vertcat(xb, resid(xb, pv))])
        keep = ca.Function("keep", [yb, xa, pm], [yb])
        switch = ca.Function.conditional("planar_more", [keep], more)
        for _ in range(max(0, max_iter - 2)):
            y = switch(y[nf2] > tol, y, xa, pm)
        qn = y[:nf2]
        vn = post(qn, pv)
        step = ca.Function("planar_step", [xa, pm],
                           [ca.vertcat(qn, vn, y[nf2], out(qn, vn, xa[nf2:], pm))])
        fail = max(1e3 * tol, 1e-6)  # the closed loop's failure threshold
        core = step
        for level in range(halvings):
            # the step, or (where it fails) two halves of it, each with the step before
            hm = ca.vertcat(0.5 * (pm[0] + pm[1]), 0.5 * (pm[2] + pm[3]))
            first = step(xa, ca.vertcat(pm[0], hm[0], pm[2], hm[1], 0.5 * pm[4]))
            second = step(first[:2 * nf2], ca.vertcat(hm[0], pm[1], hm[1], pm[3],
                                                      0.5 * pm[4]))
            halves = ca.Function("halves", [xa, pm], [ca.vertcat(
                second[:2 * nf2], ca.fmax(first[2 * nf2], second[2 * nf2]),
                second[2 * nf2 + 1:])])
            whole = core(xa, pm)
            r = whole[2 * nf2]
            step = ca.Function(f"planar_halving{level}", [xa, pm], [ca.if_else(
                ca.logic_not(r <= fail), halves(xa, pm), whole, True)])
        self._step = step
        X = ca.MX.sym("X", 2 * nf2)
        P = ca.MX.sym("P", 4, self.substeps)
        xx = X
        cols, rmax = [], None
        for j in range(self.substeps):
            yj = step(xx, ca.vertcat(P[:, j], self.dt))
            xx = yj[:2 * nf2]
            rmax = yj[2 * nf2] if rmax is None else ca.fmax(rmax, yj[2 * nf2])
            cols.append(yj[2 * nf2 + 1:])
        o = ca.horzcat(*cols)
        tmin = o[4, 0]
        for j in range(1, self.substeps):
            tmin = ca.fmin(tmin, o[4, j])
        sample = ca.Function("planar_sample", [X, P],
                             [xx, o[0, :], o[1, :], o[2, :], o[3, :], tmin, rmax],
                             ["x", "P"], ["x_next", "z_unit", "v_unit", "t_unit", "t_top",
                                          "t_min", "residual"])
        m = self.substeps
        Pf = ca.MX.sym("Pf", 4 * m)
        r = sample(X, ca.reshape(Pf, 4, m))
        self._flat = ca.Function("planar_sample_flat", [X, Pf], [ca.vertcat(
            r[0], r[1].T, r[2].T, r[3].T, r[4].T, r[5], r[6])])
        return sample

    def _outputs_at(self, x: np.ndarray, p: np.ndarray) -> np.ndarray:
        nf2 = 2 * self.nf
        return np.asarray(self._out(x[:nf2], x[nf2:], x[nf2:], p)).ravel()

    # ------------------------------------------------------------------------------------
    def initial_state(self) -> np.ndarray:
        """The static state at the scene's length, at rest: offsets ``q`` from the
        unstretched line hanging from the top and material velocities ``V`` (zero) of the
        free nodes (relative to the top, so a displaced top carries it along)."""
        return self._x0.copy()

    def static_unit_height(self, length: float | np.ndarray) -> np.ndarray:
        """Static height of the unit (m) at the scene's length (the discrete equilibrium in
        the current). Known at that length only: a deployment (another length) needs the
        axial plant."""
        length = np.asarray(length, dtype=float)
        if np.any(np.abs(length - self.length0) > 1e-9 * self.length0):
            raise CableOCPError('the planar heave plant knows the static depth at the cable '
                                f'scene\'s length ({self.length0} m) only: a [deployment] '
                                'needs simulation.model = "axial"')
        return np.full(length.shape, self._z_static) if length.shape else np.asarray(
            self._z_static)

    def static_tensions(self, length: float | None = None) -> tuple[float, float]:
        """(tension at the unit, at the top) of the static line, N (the scene's length;
        with a current the unit's includes its drag)."""
        if length is not None and abs(length - self.length0) > 1e-9 * self.length0:
            self.static_unit_height(length)  # raises
        return self._t_static
