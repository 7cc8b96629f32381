"""The lumped-mass model (Huang (1992) ch. 5) driven by a dynamic scene.

* :func:`lumped_params`: a :class:`~cable_ocp.scene.dynamics.DynamicScene` ->
  :class:`~cable_ocp.dynamics.lumped_params.LumpedParams` (segments shared among the
  ``[[cable.segments]]`` by length, bodies at the joints, the unit, current, top motion);
* :func:`lumped_start`: the initial state (Huang (1992) 5.6.1): the statics solver's
  solution interpolated onto the nodes at their unstretched arc lengths, then the discrete
  model's own equilibrium F(x, 0, 0) = 0 by Newton from there, so that the run starts
  exactly at rest; or ``start = "unstrained"``: hanging straight down from end_b at its
  unstretched length, at rest (Huang's 5.7.1 start);
* :class:`LumpedSceneModel`: the scene's model as
  :class:`~cable_ocp.dynamics.model.CableModel` (static state, the step driven by the
  top, linearisation, modes, simulation), on which :func:`cable_ocp.dynamics.simulate`
  and :func:`cable_ocp.dynamics.modes` dispatch.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.checks import check_lumped, check_lumped_plant
from cable_ocp.dynamics.lumped import LumpedMassModel
from cable_ocp.dynamics.lumped_params import LumpedParams, PointBody, UnitParams
from cable_ocp.dynamics.lumped_run import LumpedRun, run
from cable_ocp.dynamics.model import DrivenStep
from cable_ocp.dynamics.result import (
    ModesResult,
    SimulationResult,
    coarse_step_warnings,
    slack_report,
    until_slack,
)
from cable_ocp.dynamics.snap import dropped_message, snap_report
from cable_ocp.dynamics.stepping import MAX_CHUNKS
from cable_ocp.errors import CableOCPError
from cable_ocp.physics.current import current_velocity
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.motion import top_offset_expr

__all__ = ["SLACK_MESSAGE", "LumpedSceneModel", "check_lumped_plant", "lumped_params",
           "lumped_start", "segment_counts"]

#: the slack message of the lumped-mass model (:func:`cable_ocp.dynamics.result.slack_report`)
SLACK_MESSAGE = ("slack: segment {segment} (s = {location:.4g} m from end_a) first went slack "
                 "at t = {t:.6g} s; Huang (1992) ch. 5 excludes slack cable: {action}")
#: runs with more segment-steps than this compile the whole step to C
#: (:func:`cable_ocp.dynamics.lumped_run.run`, ``compile="step"``)
COMPILE_STEP_ABOVE = 1_000_000


def segment_counts(lengths: list[float], total: int) -> list[int]:
    """Share ``total`` lumped segments among line segments of the given lengths (m):
    proportional to length, at least one each (largest remainders first).

    Parameters
    ----------
    lengths : list of float
        The line segments' lengths, m.
    total : int
        Lumped segments in all.
    """
    n = len(lengths)
    if total < n:
        raise CableOCPError(f"simulation.segments = {total}: the line has {n} segments "
                            f"([[cable.segments]]); give at least {n}")
    big_l = float(sum(lengths))
    raw = [total * v / big_l for v in lengths]
    out = [max(1, int(math.floor(r))) for r in raw]
    while sum(out) < total:
        k = max(range(n), key=lambda i: raw[i] - out[i])
        out[k] += 1
    while sum(out) > total:
        k = max((i for i in range(n) if out[i] > 1), key=lambda i: out[i] - raw[i])
        out[k] -= 1
    return out



def lumped_params(scene: DynamicScene, segments: int | None = None) -> LumpedParams:
    """Parameters of the lumped-mass model of a scene with ``segments`` lumped segments
    (default ``simulation.segments``), shared among ``[[cable.segments]]`` by length.

    Parameters
    ----------
    scene : DynamicScene
        A lumped3d scene.
    segments : int, optional
        Lumped segments (default ``simulation.segments``).
    """
    check_lumped(scene)
    st = scene.statics
    env = st.environment
    lines = st.lines
    n = scene.simulation.segments if segments is None else int(segments)
    counts = segment_counts([float(c.length) for c in lines], n)  # type: ignore[arg-type]
    cols: dict[str, list[float]] = {k: [] for k in (
        "segment_length", "axial_stiffness", "diameter", "mass_per_length", "weight_in_water",
        "normal_drag", "tangential_drag", "added_mass_coefficient",
        "tangential_added_mass_coefficient", "axial_damping", "bending_stiffness")}
    for c, dyn, k in zip(lines, scene.cable, counts, strict=True):
        vals = {"segment_length": float(c.length) / k, "axial_stiffness": c.axial_stiffness,  # type: ignore[arg-type]
                "diameter": c.diameter, "mass_per_length": dyn.mass_per_length,
                "weight_in_water": c.weight_in_water, "normal_drag": c.normal_drag,
                "tangential_drag": c.tangential_drag,
                "added_mass_coefficient": dyn.added_mass_coefficient,
                "tangential_added_mass_coefficient": dyn.tangential_added_mass_coefficient,
                "axial_damping": dyn.axial_damping, "bending_stiffness": c.bending_stiffness}
        for key, v in vals.items():
            cols[key] += [float(v)] * k
    joints = np.concatenate([[0], np.cumsum(counts)])
    bodies = []
    for sb, db in zip(st.bodies, scene.bodies, strict=True):
        bodies.append(PointBody(
            node=int(joints[sb.joint]), mass=db.mass, added_mass=db.added_mass,
            weight_in_water=sb.weight_in_water - sb.net_buoyancy, drag_area=sb.drag_area,
            drag_coefficient=sb.drag_coefficient, force=sb.thrust))
    unit = None
    end_a = None
    if scene.unit is not None:
        u = scene.unit
        unit = UnitParams(mass=u.mass, added_mass=u.added_mass,
                          weight_in_water=u.weight_in_water, drag_area=u.drag_area,
                          drag_coefficient=u.drag_coefficient,
                          drag_law="per_axis" if u.drag_per_axis else "vector")
    else:
        pa = [float(v) for v in st.end_a.position]  # type: ignore[arg-type]

        def end_a(t: Any, pa: list[float] = pa) -> Any:  # noqa: ARG001 - constant
            return ca.DM(pa)

    current = None
    if env.current is not None:
        cur = env.current

        def current(z: Any) -> Any:
            return current_velocity(cur, z)

    tm = scene.top_motion
    top0 = ca.DM([float(v) for v in scene.top_position])
    ts = ca.SX.sym("t")
    pos = top0 + top_offset_expr(tm, ts)
    top_fn = ca.Function("top_position", [ts], [pos])
    vel_fn = ca.Function("top_velocity", [ts], [ca.jacobian(pos, ts)])
    return LumpedParams(
        **{k: np.asarray(v) for k, v in cols.items()},
        top_position=lambda t: top_fn(t), top_velocity=lambda t: vel_fn(t),
        water_density=env.water_density, gravity=env.gravity, unit=unit,
        end_a_position=end_a, bodies=tuple(bodies), current=current,
        drag_law=st.cable.drag_law, smoothing=st.solver.smoothing,
        vertical_blend=st.solver.vertical_blend, tension_strain=st.cable.strain_table)


def lumped_start(scene: DynamicScene, model: LumpedMassModel
                 ) -> tuple[np.ndarray | None, dict[str, Any]]:
    """Initial free-node positions (m) of ``model`` for ``simulation.start``.

    ``"static"``: the statics solver's solution of the scene
    (:func:`cable_ocp.dynamics.static.static_state`) interpolated at the nodes' unstretched
    arc lengths (cubic in s per coordinate), then refined to the lumped-mass equilibrium
    by Newton. ``"unstrained"``: straight down from end_b, unstretched. ``"dropped"``:
    straight down and slack, every node raised by h (1 - s / L) (h =
    ``simulation.drop_height``).

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    model : LumpedMassModel
        Its model.

    Returns
    -------
    x : ndarray (3 n_free,) or None
        None when the start could not be computed (see ``info["message"]``).
    info : dict
        ``source``, ``statics_status``, ``converged``, ``relative_residual``,
        ``max_node_shift_m`` (largest move from the interpolated statics solution to the
        discrete equilibrium: the lumped model's discretisation error), ``message``.
    """
    p = model.params
    s_nodes = p.node_arc_length
    info: dict[str, Any] = {"source": scene.simulation.start}
    if scene.simulation.start in ("unstrained", "dropped"):
        top = np.asarray(scene.top_position, float)
        pos = np.tile(top, (p.segments + 1, 1))
        pos[:, 2] -= p.length - s_nodes
        pos[:, 2] += scene.simulation.drop_height * (1.0 - s_nodes / p.length)
        info.update(converged=True, message=dropped_message(scene.simulation))
        return pos[model.free_nodes].reshape(-1), info
    from scipy.interpolate import CubicSpline

    from cable_ocp.dynamics.static import static_state

    sol = static_state(scene)
    info["statics_status"] = sol.status
    if not sol.success:
        info.update(converged=False, message=f"the statics solve failed: {sol.message}")
        return None, info
    if sol.grounded_length > 0:
        info.update(converged=False, message="the static cable lies on the seabed; the "
                    "lumped-mass model has no seabed contact")
        return None, info
    s = np.asarray(sol.s, float)
    keep = np.concatenate([[True], np.diff(s) > 1e-12 * max(sol.length, 1.0)])
    spline = CubicSpline(s[keep], np.asarray(sol.position, float)[keep], axis=0)
    guess = spline(np.clip(s_nodes, s[keep][0], s[keep][-1]))
    x0 = guess[model.free_nodes].reshape(-1)
    x, newton = model.static_equilibrium(x0)
    shift = float(np.max(np.abs(x - x0))) if x0.size else 0.0
    info.update(converged=newton["converged"], iterations=newton["iterations"],
                relative_residual=newton["relative_residual"], max_node_shift_m=shift,
                statics_wall_time_s=sol.wall_time_s)
    if not newton["converged"]:
        why = ("; its Newton matrix is singular (segments with no tension carry no "
               "transverse stiffness: a slack or compressed line between fixed ends)"
               if newton.get("singular_jacobian") else "")
        info["message"] = (f"the lumped-mass equilibrium did not converge from the statics "
                           f"solution (relative residual {newton['relative_residual']:.3g})"
                           f"{why}; try another simulation.segments, or (a line with a "
                           "[unit]) start = \"unstrained\"")
        return None, info
    info["message"] = (f"statics solution refined to the discrete equilibrium (largest node "
                       f"shift {shift:.3g} m)")
    return x, info


def _failed_result(scene: DynamicScene, model: LumpedMassModel, message: str,
                   info: dict[str, Any]) -> SimulationResult:
    return SimulationResult.failed(model.params.segments, message, "lumped3d",
                                   scene.simulation.scheme, {"start": info})


def _result(scene: DynamicScene, model: LumpedMassModel, out: LumpedRun,
            info: dict[str, Any]) -> SimulationResult:
    sim = scene.simulation
    p = model.params
    ts = out.t
    status, message = out.status, out.message
    tens = out.tension
    top = np.linalg.norm(out.top_force, axis=1)
    s_mid = 0.5 * (p.node_arc_length[:-1] + p.node_arc_length[1:])
    t_slack, seg = out.slack if out.slack is not None else (None, None)
    keep = until_slack(ts, t_slack, sim.output_step, sim.on_slack)
    if keep is not None:
        ts, tens, top = ts[keep], tens[keep], top[keep]
    slack, status, message = slack_report(
        t_slack, seg, None if seg is None else float(s_mid[seg]), status=status,
        message=message, on_slack=sim.on_slack, template=SLACK_MESSAGE,
        continued="the run continued: a slack segment carries no tension (the smooth "
                  "no-compression law) and the line may fold there, which the model follows "
                  "only approximately")
    positions = out.positions[:ts.size]
    velocities = out.velocities[:ts.size] if out.velocities is not None else None
    tm = scene.top_motion
    warnings = coarse_step_warnings(sim.time_step, (
        ("heave_frequency", tm.heave_frequency),
        ("horizontal_frequency", tm.horizontal_frequency),
        ("circular_frequency", tm.circular_frequency)))
    sim_time = float(ts[-1] - ts[0]) if ts.size > 1 else 0.0
    diagnostics = {
        "build_time_s": out.build_time_s,
        "steps": out.steps,
        "segments": p.segments,
        "mean_newton_iterations": out.mean_iterations,
        "max_scaled_residual": float(np.max(out.residual)) if out.residual.size else None,
        "tolerance": sim.tolerance,
        "compiled": out.compiled,
        "start": info,
        "min_strain": out.min_strain,
        "wall_time_per_simulated_second": out.wall_time_s / sim_time if sim_time else None,
    }
    return SimulationResult.from_nodes(
        positions, t=ts, length=np.full(ts.size, p.length), top_tension=top,
        segment_tensions=tens, node_velocities=velocities,
        min_tension=float(np.min(tens)) if tens.size else math.nan, slack=slack,
        snap=snap_report(ts, tens, s_mid), status=status, message=message,
        warnings=warnings, wall_time_s=out.wall_time_s,
        model="lumped3d", scheme=sim.scheme, diagnostics=diagnostics)


class LumpedSceneModel:
    """The lumped-mass model of a dynamic scene, as :class:`cable_ocp.dynamics.model.CableModel`.

    Parameters
    ----------
    scene : DynamicScene
        A lumped3d scene (:func:`lumped_params` checks it).
    segments : int, optional
        Lumped segments (default ``simulation.segments``).

    Attributes
    ----------
    model : LumpedMassModel
        The model of :func:`lumped_params`; its state is the free nodes' positions (m) and
        velocities (m/s), node-major (x, y, z).
    free : list of int
        The free nodes (0..N-1 with a unit, 1..N-1 with an anchored end_a).
    """

    name = "lumped3d"

    def __init__(self, scene: DynamicScene, segments: int | None = None) -> None:
        self.scene = scene
        self.params = lumped_params(scene, segments)
        self.model = LumpedMassModel(self.params)
        self.n = self.params.segments
        self.free = [int(i) for i in self.model.free_nodes]
        self._static: tuple[np.ndarray | None, dict[str, Any]] | None = None

    def state_size(self) -> int:
        """Positions and velocities of the free nodes: ``6 n_free``."""
        return 6 * self.model.n_free

    def static_positions(self) -> tuple[np.ndarray | None, dict[str, Any]]:
        """The free nodes' positions at rest (m), :func:`lumped_start` (computed once)."""
        if self._static is None:
            self._static = lumped_start(self.scene, self.model)
        return self._static

    def static_state(self) -> tuple[np.ndarray | None, dict[str, Any]]:
        """The state at rest: :meth:`static_positions` and zero velocities."""
        x0, info = self.static_positions()
        return (None if x0 is None else np.concatenate([x0, np.zeros_like(x0)])), info

    def driven_step(self, dt: float | None = None) -> DrivenStep:
        """The midpoint step with the top's height and the top segment's length as inputs
        (:class:`~cable_ocp.dynamics.lumped_driven.DrivenLumpedStep`, in coordinates
        relative to the top; ``dt`` a symbol unless given, s). Needs a unit at end_a.

        Raises
        ------
        CableOCPError
            When end_a is anchored, or the static state failed.
        """
        from cable_ocp.dynamics.lumped_driven import DrivenLumpedStep

        step = DrivenLumpedStep(self.model, self.scene.length)
        x_abs, info = self.static_positions()
        if x_abs is None:
            raise CableOCPError(f"the lumped-mass line's static state failed: "
                                f"{info.get('message', '')}")
        e = step.expressions(self.model.force_scale(np.asarray(x_abs, dtype=float)))
        q = np.asarray(x_abs, dtype=float) - np.tile(step.top0, step.n)
        if dt is not None:
            e = dict(e)
            for key in ("res", "x1", "guess", "out"):
                e[key] = ca.substitute(e[key], e["dt"], ca.SX(float(dt)))
            e["dt"] = float(dt)
        return DrivenStep(unknown=e["y"], state=ca.vertcat(e["q0"], e["v0"]),
                          inputs=e["p"], dt=e["dt"], residual=e["res"],
                          next_state=e["x1"], guess=e["guess"], outputs=e["out"],
                          start=np.concatenate([q, np.zeros(q.size)]))

    def linearize(self) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness (N/m) and mass (kg) about the static positions
        (:meth:`~cable_ocp.dynamics.lumped.LumpedMassModel.linearize`).

        Raises
        ------
        CableOCPError
            When the static state failed.
        """
        x0, info = self.static_positions()
        if x0 is None:
            raise CableOCPError(info["message"])
        return self.model.linearize(x0)

    def simulate(self, progress: Callable[[int, int], None] | None = None
                 ) -> SimulationResult:
        """Time-domain simulation of the scene.

        ``simulation.scheme``: ``"midpoint"`` (default), ``"trapezoidal"``, ``"bdf2"``
        (:meth:`~cable_ocp.dynamics.lumped.LumpedMassModel.step_function`) or ``"thesis"``
        (Huang's (5.21), :mod:`cable_ocp.dynamics.lumped_thesis`). ``simulation.tolerance``
        is the Newton tolerance on the nodal force residual over the force scale (the
        largest of the total weight in water and the largest static tension). A pay-out
        (``[top_motion]`` varying the length) runs
        :func:`cable_ocp.dynamics.lumped_payout_run.simulate_payout` (nodes enter and
        leave at the winch; midpoint rule only).
        """
        if self.scene.top_motion.varying_length:
            from cable_ocp.dynamics.lumped_payout_run import simulate_payout

            return simulate_payout(self, progress)
        scene, model = self.scene, self.model
        sim = scene.simulation
        x0, info = self.static_positions()
        if x0 is None:
            return _failed_result(scene, model, info["message"], info)
        total = sim.steps

        def prog(t_done: float, duration: float) -> None:
            if progress is not None:
                progress(min(total, int(round(t_done / sim.time_step))), total)

        every = sim.output_every
        n_out = sim.steps // every
        if sim.scheme == "thesis":
            from cable_ocp.dynamics.lumped_thesis import run_thesis

            out = run_thesis(model, x0, None, sim.duration, sim.time_step, record_every=every,
                             progress=prog)
        else:
            # long runs: compile the whole step to C (a few seconds, cached) - about 3-5x
            # faster per step than the compiled kernel alone
            compile_mode = "step" if sim.steps * model.params.segments > COMPILE_STEP_ABOVE \
                else "kernel"
            out = run(model, x0, None, sim.duration, sim.time_step, scheme=sim.scheme,
                      record_every=every, chunk_records=max(1, math.ceil(n_out / MAX_CHUNKS)),
                      tol=sim.tolerance, max_iter=sim.max_iterations, compile=compile_mode,
                      progress=prog)
        return _result(scene, model, out, info)

    def modes(self, count: int) -> ModesResult:
        """Natural frequencies and mode shapes about the static state.

        K = -dF/dx of the tension, weight and body loads at the static state (the current
        shapes that state but its drag is left out of K), M with the direction-dependent
        added mass (5.2): K phi = omega^2 M phi. A fixed end_b (and an anchored end_a) has
        zero displacement in every shape.
        """
        model = self.model
        x0, info = self.static_positions()
        n = model.params.segments
        if x0 is None:
            return ModesResult(frequencies=np.zeros(0), shapes=np.zeros((0, n + 1, 3)),
                               node_positions=np.zeros((n + 1, 3)), length=model.params.length,
                               model="lumped3d", status="failed", message=info["message"],
                               diagnostics={"start": info})
        omega, shapes, lam = model.modes(x0, count)
        nodes = np.asarray(model.nodes(x0, 0.0)).T
        msg = f"{omega.size} modes, {n} segments"
        status = "solved"
        if np.any(lam < 0):
            status = "failed"
            msg = (f"the static state is unstable: {int(np.sum(lam < 0))} negative eigenvalues "
                   "of K (a compressed or slack line)")
        return ModesResult(frequencies=omega, shapes=shapes, node_positions=nodes,
                           length=model.params.length, model="lumped3d", status=status,
                           message=msg, diagnostics={"segments": n, "start": info,
                                                     "stiffness": "tension, weight and body "
                                                     "loads; drag neglected"})
