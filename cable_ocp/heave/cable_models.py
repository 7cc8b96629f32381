"""The cable models that can be the heave plant, and the one place that picks among them.

:func:`cable_plant` reads the cable scene's ``[simulation] model``:

* ``"axial"`` (default of a dynamic scene): :class:`cable_ocp.heave.axial_plant.AxialCablePlant`,
  the vertical line of Huang (1992), ch. 3;
* ``"planar"``: :class:`PlanarCablePlant`, the line in a vertical plane of Huang (1992),
  ch. 4 (:class:`cable_ocp.dynamics.planar.PlanarModel`): the same heave and pay-out at
  the top, and the line swings out of the vertical in a current along x (sway, and the
  vertical motion that the inclined line couples to it);
* ``"lumped3d"``: :class:`LumpedCablePlant`, the three-dimensional lumped-mass line of
  Huang (1992), ch. 5 (:class:`cable_ocp.dynamics.lumped.LumpedMassModel`): the same heave
  and pay-out at the top, the winch paying cable in and out through the line's top
  segment (whose unstretched length must stay within :data:`TOP_SEGMENT_RANGE` of its
  nominal one: no re-meshing; a ``[deployment]`` runs on the pay-out plant of
  :mod:`cable_ocp.heave.lumped_deploy`); a current of any heading and profile swings the
  line out of the vertical in 3D.

The plants have the interface that the closed loop (:func:`cable_ocp.heave.closed_loop.run_loop`
through :class:`cable_ocp.heave.loop_plants.CableLine`) and the identification experiment
use: ``substeps``, ``dt``, ``length0``, ``z_top0``, ``tolerance``, ``model.n``,
:meth:`initial_state`, :meth:`static_unit_height`, :meth:`static_tensions`, :meth:`advance`
and :meth:`run_open_loop`.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.checks import check_axial, check_lumped_plant, check_planar
from cable_ocp.dynamics.lumped import LumpedMassModel
from cable_ocp.dynamics.model import model_for
from cable_ocp.errors import CableOCPError
from cable_ocp.heave.axial_plant import (
    AxialCablePlant,
    SampledCablePlant,
    compile_plant_functions,
)
from cable_ocp.scene.dynamics import DynamicScene, dynamic_scene_from_dict

__all__ = ["HALVINGS", "PLANT_MODELS", "TOP_SEGMENT_RANGE", "LumpedCablePlant",
           "check_plant_scene",
           "PlanarCablePlant", "axial_twin", "cable_plant", "lumped_axial_frequency",
           "still_scene"]

#: the cable scene's ``simulation.model`` values that can be the heave plant
PLANT_MODELS = ("axial", "planar", "lumped3d")
#: times a planar or lumped3d step whose Newton iteration fails is halved (down to 1/8 of
#: the step)
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
    AxialCablePlant, PlanarCablePlant or LumpedCablePlant

    Raises
    ------
    CableOCPError
        For a scene the model refuses (no unit, a time step that does not divide the
        sample, a static state that fails).
    """
    model = scene.simulation.model
    if model == "axial":
        return AxialCablePlant(scene, sample_time)
    if model == "planar":
        return PlanarCablePlant(scene, sample_time)
    if model == "lumped3d":
        return LumpedCablePlant(scene, sample_time)
    raise CableOCPError(
        f"simulation.model = {model!r} in the cable scene: the heave plant takes "
        f"{', '.join(repr(m) for m in PLANT_MODELS)}")


def check_plant_scene(path: str, scene: DynamicScene) -> None:
    """Refuse a cable scene that its model cannot run as the heave plant, before any work.

    The scene-level checks of ``[unit] cable_scene`` (readable, a dynamic scene with an
    axial, planar or lumped3d model and a unit, a time step dividing the sample) run when
    the heave scene is built (:func:`cable_ocp.scene.heave.check`); this one asks the model
    itself (:mod:`cable_ocp.dynamics.checks`), so it lives with the models.

    Parameters
    ----------
    path : str
        The heave file's ``unit.cable_scene`` (named in the message).
    scene : DynamicScene
        That cable scene.

    Raises
    ------
    CableOCPError
        Naming ``unit.cable_scene`` and the key the model refuses.
    """
    checks = {"axial": check_axial, "planar": check_planar, "lumped3d": check_lumped_plant}
    check = checks.get(scene.simulation.model)
    if check is None:  # the heave scene's own check refuses other models first
        return
    try:
        check(scene)
    except CableOCPError as exc:
        raise CableOCPError(f"unit.cable_scene = {path!r}: {exc}") from None


def axial_twin(scene: DynamicScene) -> DynamicScene:
    """The same line as an axial scene: no current, no top motion, ``model = "axial"``
    (its first axial frequency is the identification's reference ``omega_1``)."""
    if scene.simulation.model == "axial":
        return scene
    raw = copy.deepcopy(scene.raw)
    raw.setdefault("simulation", {})["model"] = "axial"
    raw["simulation"].pop("element_length", None)  # the lumped3d pay-out's key
    raw.pop("top_motion", None)
    if isinstance(raw.get("environment"), dict):
        raw["environment"].pop("current", None)
    return dynamic_scene_from_dict(raw)


def _newton_step(name: str, newton: ca.Function, resid: ca.Function, guess: ca.Function,
                 finish: Callable[[Any, Any], Any], nx: int, ny: int, tol: float,
                 max_iter: int) -> ca.Function:
    """One plant step ``(x, p) -> [x_next; residual; outputs]`` (``p`` = ``[L_a, L_b, z_a,
    z_b, dt]``) by Newton's method on the step's unknowns ``y`` (``ny``).

    ``guess(pv)``, ``newton(y, pv)`` (one iteration) and ``resid(y, pv)`` (the scaled
    residual) are functions of ``pv = [x; p]``; ``finish(y, pv)`` gives ``[x_next;
    outputs]``. Two iterations from the guess, then more (up to ``max_iter``) only while
    the residual exceeds ``tol``: a short-circuit switch, evaluated only when taken.
    """
    xa = ca.MX.sym("xa", nx)
    pm = ca.MX.sym("p", 5)
    pv = ca.vertcat(xa, pm)
    y1 = newton(newton(guess(pv), pv), pv)
    y = ca.vertcat(y1, resid(y1, pv))
    yb = ca.MX.sym("y", ny + 1)
    xb = newton(yb[:ny], pv)
    more = ca.Function("more", [yb, xa, pm], [ca.vertcat(xb, resid(xb, pv))])
    keep = ca.Function("keep", [yb, xa, pm], [yb])
    switch = ca.Function.conditional(f"{name}_more", [keep], more)
    for _ in range(max(0, max_iter - 2)):
        y = switch(y[ny] > tol, y, xa, pm)
    fin = finish(y[:ny], pv)
    return ca.Function(f"{name}_step", [xa, pm], [ca.vertcat(fin[:nx], y[ny], fin[nx:])])


def _sample_functions(name: str, step: ca.Function, nx: int, substeps: int, dt: float,
                      tol: float, halvings: int
                      ) -> tuple[ca.Function, ca.Function, ca.Function]:
    """``(sample, flat, step)`` from one plant step ``(x, p) -> [x_next; residual;
    z_unit, v_unit, t_unit, t_top, t_min]`` (:func:`_newton_step`).

    ``step`` with halving: where the residual exceeds the failure threshold ``1e3 tol``
    (a line going slack, where the no-compression law bends sharply), the step is taken
    again as two steps of half the size (``L`` and the top height halved linearly),
    recursively up to ``halvings`` times (only then evaluated). ``sample(X, P)``:
    ``substeps`` steps of ``dt`` with ``P`` (4 x substeps: ``L_a, L_b, z_a, z_b`` per
    step) -> ``(x_next, z_unit, v_unit, t_unit, t_top, t_min, residual)``; ``flat(X,
    Pf)``: the same with ``P`` as one column and the outputs stacked (one conversion per
    call in the closed loop).
    """
    xa = ca.MX.sym("xa", nx)
    pm = ca.MX.sym("p", 5)
    fail = max(1e3 * tol, 1e-6)  # the closed loop's failure threshold
    core = step
    for level in range(halvings):
        # the step, or (where it fails) two halves of it, each with the step before
        hm = ca.vertcat(0.5 * (pm[0] + pm[1]), 0.5 * (pm[2] + pm[3]))
        first = step(xa, ca.vertcat(pm[0], hm[0], pm[2], hm[1], 0.5 * pm[4]))
        second = step(first[:nx], ca.vertcat(hm[0], pm[1], hm[1], pm[3], 0.5 * pm[4]))
        halves = ca.Function("halves", [xa, pm], [ca.vertcat(
            second[:nx], ca.fmax(first[nx], second[nx]), second[nx + 1:])])
        whole = core(xa, pm)
        # a switch on functions that take the whole step as an argument: only the taken
        # branch runs (CasADi's if_else on expressions would build the "whole" branch as a
        # function of (xa, pm) and take the step again there)
        yw = ca.MX.sym("y", whole.shape[0])
        keep = ca.Function("keep", [yw, xa, pm], [yw])
        halve = ca.Function("halve", [yw, xa, pm], [halves(xa, pm)])
        pick = ca.Function.if_else(f"{name}_halving{level}_pick", halve, keep)
        step = ca.Function(f"{name}_halving{level}", [xa, pm], [
            pick(ca.logic_not(whole[nx] <= fail), whole, xa, pm)])
    X = ca.MX.sym("X", nx)
    P = ca.MX.sym("P", 4, substeps)
    xx = X
    cols, rmax = [], None
    for j in range(substeps):
        yj = step(xx, ca.vertcat(P[:, j], dt))
        xx = yj[:nx]
        rmax = yj[nx] if rmax is None else ca.fmax(rmax, yj[nx])
        cols.append(yj[nx + 1:])
    o = ca.horzcat(*cols)
    tmin = o[4, 0]
    for j in range(1, substeps):
        tmin = ca.fmin(tmin, o[4, j])
    sample = ca.Function(f"{name}_sample", [X, P],
                         [xx, o[0, :], o[1, :], o[2, :], o[3, :], tmin, rmax],
                         ["x", "P"], ["x_next", "z_unit", "v_unit", "t_unit", "t_top",
                                      "t_min", "residual"])
    Pf = ca.MX.sym("Pf", 4 * substeps)
    r = sample(X, ca.reshape(Pf, 4, substeps))
    flat = ca.Function(f"{name}_sample_flat", [X, Pf], [ca.vertcat(
        r[0], r[1].T, r[2].T, r[3].T, r[4].T, r[5], r[6])])
    return sample, flat, step


class _OneLengthPlant(SampledCablePlant):
    """A plant that steps its model through the model's step with the top motion and the
    length as inputs (:meth:`cable_ocp.dynamics.model.CableModel.driven_step`) and knows
    its static state at the cable scene's length only (the planar and lumped-mass plants:
    their static start is the discrete equilibrium at that length), from ``_z_static`` and
    ``_t_static``."""

    model_name: str
    #: the prefix of the plant's CasADi functions
    _name: str

    def _drive(self, scene: DynamicScene, sample_time: float) -> None:
        """Set the sampling attributes, build the scene's model at rest under its static
        top (:func:`still_scene`) and its driven step, and the sample function."""
        self._setup(scene, sample_time)
        self.model = model_for(still_scene(scene))
        try:
            self.step = self.model.driven_step()
        except CableOCPError as exc:
            raise CableOCPError(f"cable scene: {exc}") from None
        self._x0 = np.asarray(self.step.start, dtype=float)
        self._compile_sample()

    def _build(self, tol: float, max_iter: int, halvings: int) -> ca.Function:
        """The sample function ``(x, P) -> (x_next, z_unit, v_unit, t_unit, t_top, t_min,
        residual)`` over ``substeps`` steps of the model's driven step (as the axial
        plant's).

        Each step is Newton's method on the step's (scaled) residual from the model's
        predictor: two iterations, then more (up to ``max_iterations``) only while the
        scaled residual exceeds the tolerance (a short-circuit switch, as the axial plant).
        The Newton matrix (the exact Jacobian, block banded) is solved by CasADi's sparse
        QR, which, unlike the ``rootfinder``, generates C: the functions are compiled as
        the axial plant's (:func:`cable_ocp.heave.axial_plant.compile_plant_functions`).
        Where a step does not converge (the residual above the failure threshold ``1e3
        tolerance``: a line going slack, where the no-compression law bends sharply), it
        is taken again as two steps of half the size, recursively up to ``halvings`` times
        (only then evaluated).
        """
        st, name = self.step, self._name
        y = st.unknown
        ny, nx = y.shape[0], st.state.shape[0]
        pars = ca.vertcat(st.state, st.inputs, st.dt)
        fj = ca.Function(f"{name}_fj", [y, pars], [st.residual, ca.jacobian(st.residual, y)])
        ys = ca.MX.sym("y", ny)
        ps = ca.MX.sym("pars", pars.shape[0])
        rk, jk = fj(ys, ps)
        newton = ca.Function(f"{name}_newton", [ys, ps], [ys - ca.solve(jk, rk, "qr")])
        resid = ca.Function(f"{name}_resid", [y, pars], [ca.norm_inf(st.residual)])
        guess = ca.Function(f"{name}_guess", [pars], [st.guess])
        fin = ca.Function(f"{name}_finish", [y, pars], [ca.vertcat(st.next_state,
                                                                   st.outputs)])
        newton, resid, guess, fin = compile_plant_functions([newton, resid, guess, fin])
        self._guess, self._fin = guess, fin
        step = _newton_step(name, newton, resid, guess, fin, nx, ny, tol, max_iter)
        sample, self._flat, self._step = _sample_functions(name, step, nx, self.substeps,
                                                           self.dt, tol, halvings)
        return sample

    def _outputs_at(self, x: np.ndarray, p: np.ndarray) -> np.ndarray:
        """``[z_unit, v_unit, t_unit, t_top, t_min]`` of the state ``x`` at rest over a
        step of ``p`` (the static outputs: the predictor of a state at rest with the top
        and the length still is no motion)."""
        pv = np.concatenate([x, p])
        r = np.asarray(self._fin(self._guess(pv), pv)).ravel()
        return r[x.size:]

    def initial_state(self) -> np.ndarray:
        """The static state at the scene's length, at rest, in the model's driven layout
        (relative to the top, so a displaced top carries the line with it)."""
        return self._x0.copy()

    def _compile_sample(self) -> None:
        """Build the sample function (the subclass's ``_build``, with the scene's Newton
        settings and :data:`HALVINGS`) and the static outputs at the start state
        ``_x0``: the unit's height and the tensions at the unit and the top."""
        sim = self.scene.simulation
        self._sample = self._build(sim.tolerance, sim.max_iterations, HALVINGS)
        self._chunks: dict[int, ca.Function] = {}
        r = self._outputs_at(self._x0, np.array([self.length0, self.length0, self.z_top0,
                                                 self.z_top0, self.dt]))
        self._z_static = float(r[0])
        self._t_static = (float(r[2]), float(r[3]))

    def static_unit_height(self, length: float | np.ndarray) -> np.ndarray:
        """Static height of the unit (m) at the scene's length (the discrete equilibrium,
        in the current if any). Known at that length only."""
        length = np.asarray(length, dtype=float)
        if np.any(np.abs(length - self.length0) > 1e-9 * self.length0):
            raise CableOCPError(f'the {self.model_name} heave plant knows the static depth at '
                                f'the cable scene\'s length ({self.length0} m) only (a '
                                '[deployment] runs on the axial or the lumped3d pay-out '
                                'plant)')
        return np.full(length.shape, self._z_static) if length.shape else np.asarray(
            self._z_static)

    def static_tensions(self, length: float | None = None) -> tuple[float, float]:
        """(tension at the unit, at the top) of the static line, N (the scene's length;
        with a current the unit's includes its drag)."""
        if length is not None and abs(length - self.length0) > 1e-9 * self.length0:
            self.static_unit_height(length)  # raises
        return self._t_static


class PlanarCablePlant(_OneLengthPlant):
    """The planar cable model (Huang (1992), ch. 4) advanced one control sample per call.

    The boom-tip heave moves the top (end_b) vertically, the winch output ``u`` pays cable
    in there (``L = L_dep - u``), as :class:`cable_ocp.heave.axial_plant.AxialCablePlant`;
    the top keeps its static x. A current along x (``[environment.current]`` of the cable
    scene) inclines the line and drags on the unit and the cable as they move. Each
    sub-step is the planar model's own implicit-midpoint step with its discrete-gradient
    tension with ``L``, the top height and the step size as inputs
    (:meth:`cable_ocp.dynamics.planar.PlanarModel.driven_step`), solved by Newton's method
    (compiled; a step that does not converge is halved, :meth:`_OneLengthPlant._build`).

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
    _name = "planar"

    #: the cable scene's ``simulation.model`` of this plant
    model_name = "planar"

    def __init__(self, scene: DynamicScene, sample_time: float) -> None:
        self._drive(scene, sample_time)


# ------------------------------------------------------------------------------------------
# The three-dimensional lumped-mass line (Huang (1992), ch. 5) as the plant
# ------------------------------------------------------------------------------------------

#: the top segment's unstretched length must stay within these multiples of its nominal
#: length (the winch pays cable in and out through it; it is not re-meshed)
TOP_SEGMENT_RANGE = (0.3, 2.0)


def still_scene(scene: DynamicScene) -> DynamicScene:
    """The cable scene without its ``[top_motion]`` and with the static start: the line
    at rest under its static top (the heave plant moves the top itself)."""
    raw = copy.deepcopy(scene.raw)
    raw.pop("top_motion", None)
    raw.setdefault("simulation", {})["start"] = "static"
    return dynamic_scene_from_dict(raw)


def lumped_axial_frequency(scene: DynamicScene) -> float:
    """First axial natural frequency (rad/s) of a lumped3d scene's line hanging vertically
    without the current: the lowest mode of the lumped-mass model about its static state
    whose shape is vertical (more than 99 % of its squared displacements along z; the
    vertical line's axial and transverse modes are uncoupled)."""
    from cable_ocp.dynamics.lumped_scene import lumped_params, lumped_start

    raw = copy.deepcopy(still_scene(scene).raw)
    if isinstance(raw.get("environment"), dict):
        raw["environment"].pop("current", None)
    twin = dynamic_scene_from_dict(raw)
    model = LumpedMassModel(lumped_params(twin))
    x0, info = lumped_start(twin, model)
    if x0 is None:
        raise CableOCPError(f"cable scene: the vertical lumped-mass line's static state "
                            f"failed: {info.get('message', '')}")
    omega, shapes, _ = model.modes(x0)
    share = np.sum(shapes[:, :, 2] ** 2, axis=1) / np.sum(shapes**2, axis=(1, 2))
    return float(omega[np.flatnonzero(share > 0.99)[0]])

class LumpedCablePlant(_OneLengthPlant):
    """The three-dimensional lumped-mass line (Huang (1992), ch. 5) advanced one control
    sample per call.

    The boom-tip heave moves the top (end_b) vertically (its x and y stay at the static
    position), the winch output ``u`` pays cable in there (``L = L_dep - u``), as
    :class:`cable_ocp.heave.axial_plant.AxialCablePlant`. The winch pays cable in and out
    through the top segment: its unstretched length is ``l_top0 + (L - L0)``; the other
    segments keep theirs. Its length must stay within :data:`TOP_SEGMENT_RANGE` times its
    nominal length: the plant is not re-meshed, and :meth:`advance` stops the run (a
    ``"failed"`` status with the reason) where the winch would leave that range. A
    current (any heading) swings the line out of the vertical and drags on the unit and
    the cable as they move; without a current the vertical line is the axial one.

    Each sub-step is the lumped-mass model's implicit-midpoint step with its
    discrete-gradient tension with ``L``, the top height and the step as inputs
    (:meth:`cable_ocp.dynamics.lumped_scene.LumpedSceneModel.driven_step`: the model's own
    equations of motion), solved by Newton's method with the exact Jacobian
    (block tridiagonal; CasADi's sparse QR, compiled), a step that does not converge
    halved as the planar plant's. The static start is the model's own equilibrium
    (:func:`cable_ocp.dynamics.lumped_scene.lumped_start`).

    Outputs per sub-step: the unit's height and vertical velocity, the tension at the unit
    (the magnitude of the cable's pull on it: segment 0's tension less the half segment
    that the unit's node carries, its inertia at the step's mean acceleration), the top
    tension (the top node's balance without its acceleration) and the smallest segment
    tension, the Hooke tension ``EA eps`` with the material damping: ``<= 0`` exactly where
    a segment is slack (``eps <= 0``, the lumped-mass model's slack), where the model's
    smooth no-compression law carries almost nothing.

    Parameters
    ----------
    scene : DynamicScene
        A lumped3d scene with a unit (``[simulation] model = "lumped3d"``): ``segments``,
        ``time_step`` (must divide ``sample_time``), ``tolerance``, ``max_iterations``.
        Its ``[top_motion]`` and ``start`` are not used.
    sample_time : float
        Control sample ``h``, s.
    """

    _chunk_name = "lumped_chunk"
    _name = "lumped"

    #: the cable scene's ``simulation.model`` of this plant
    model_name = "lumped3d"

    def __init__(self, scene: DynamicScene, sample_time: float) -> None:
        self._drive(scene, sample_time)
        self.l_top0 = float(self.model.params.segment_length[-1])
        self.top_range = (TOP_SEGMENT_RANGE[0] * self.l_top0,
                          TOP_SEGMENT_RANGE[1] * self.l_top0)

    def _out_of_range(self, lengths: np.ndarray) -> str | None:
        """Why ``lengths`` (m) would take the top segment out of its range, or None."""
        lt = self.l_top0 + (np.asarray(lengths, dtype=float) - self.length0)
        lo, hi = self.top_range
        bad = np.flatnonzero((lt < lo) | (lt > hi))
        if not bad.size:
            return None
        k = int(bad[0])
        return (f"the winch would take the lumped3d plant's top segment to {lt[k]:.4g} m "
                f"(unstretched line {lengths[k]:.6g} m against the cable scene's "
                f"{self.length0:.6g} m), outside {TOP_SEGMENT_RANGE[0]:g} to "
                f"{TOP_SEGMENT_RANGE[1]:g} times its nominal {self.l_top0:.4g} m: the plant "
                "pays cable in and out through its top segment and is not re-meshed (fewer "
                "simulation.segments in the cable scene lengthen that segment; "
                "winch.stroke_max limits the winch; simulation.model = \"axial\" has no such "
                "limit)")

    # ------------------------------------------------------------------------------------
    def advance(self, x: np.ndarray, lengths: np.ndarray, tops: np.ndarray
                ) -> tuple[np.ndarray, dict[str, Any]]:
        """:meth:`SampledCablePlant.advance`; where the winch would take the top segment
        out of its range, nothing is stepped: the state is returned unchanged, the
        outputs are NaN, the residual infinite and ``out["stop"]`` says why.

        Parameters
        ----------
        x : numpy.ndarray
            State.
        lengths, tops : numpy.ndarray, shape (substeps + 1,)
            Unstretched length and top height at the sub-step points, m.
        """
        why = self._out_of_range(lengths)
        if why is None:
            return super().advance(x, lengths, tops)
        nan = np.full(self.substeps, np.nan)
        return x.copy(), {"z_unit": nan, "v_unit": nan.copy(), "t_unit": nan.copy(),
                          "t_top": nan.copy(), "t_min": math.nan, "residual": math.inf,
                          "stop": why}

    def run_open_loop(self, lengths: np.ndarray, tops: np.ndarray,
                      chunk: int = 200) -> dict[str, np.ndarray]:
        """:meth:`SampledCablePlant.run_open_loop`; raises :class:`CableOCPError` where
        ``lengths`` would take the top segment out of its range.

        Parameters
        ----------
        lengths, tops : numpy.ndarray
            On the sub-step grid, m (:meth:`SampledCablePlant.run_open_loop`).
        chunk : int
            Samples per mapaccum call.
        """
        why = self._out_of_range(lengths)
        if why is not None:
            raise CableOCPError(why)
        return super().run_open_loop(lengths, tops, chunk)
