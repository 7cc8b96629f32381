"""A time-domain run of the lumped-mass model: :func:`run` and its result :class:`LumpedRun`.

The steps of :meth:`cable_ocp.dynamics.lumped.LumpedMassModel.step_function` are chained
with ``mapaccum`` in chunks (no Python per time step); the records are turned into node
positions, velocities, tensions and the top force by the model's functions.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.lumped import LumpedMassModel
from cable_ocp.dynamics.lumped_kernel import segment_kernel
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.numerics.compile import compile_function

__all__ = ["LumpedRun", "run", "step_grid"]


@dataclass
class LumpedRun:
    """A time-domain run of the lumped-mass model (recorded every ``record_every`` steps).

    Attributes
    ----------
    status : str
        ``"solved"``, ``"failed"`` (a Newton step did not converge: the run stops there) or
        ``"interrupted"``.
    message : str
        Detail of the status.
    t : ndarray (n,)
        Record times, s.
    x, v : ndarray (n, 3 n_free)
        Free-node positions (m) and velocities (m/s).
    positions : ndarray (n, N + 1, 3)
        All node positions from end_a to end_b, m.
    velocities : ndarray (n, N + 1, 3) or None
        All node velocities, m/s.
    tension : ndarray (n, N)
        Segment tensions, N.
    top_force : ndarray (n, 3)
        Force of end_b's attachment on the cable, N (:attr:`LumpedMassModel.top_force`);
        its norm is the top tension.
    strain : ndarray (n, N)
        Segment strains (-); <= 0 means slack.
    residual : ndarray (n,)
        Largest scaled Newton residual over the steps since the previous record, m/s^2.
    scheme : str
    time_step : float
        s.
    steps : int
        Time steps taken.
    wall_time_s : float
        Wall time of the stepping, s (excludes building the CasADi functions).
    build_time_s : float
        Time to build the step and chunk functions, s.
    mean_iterations : float
        Newton iterations per step, on average (NaN for the ``rootfinder`` solver).
    compiled : str
        What ran as compiled C: ``"step"``, ``"kernel"`` or ``"none"``.
    min_strain : float
        Smallest segment strain over every step (-); <= 0 means a segment went slack.
    slack : tuple (time, segment) or None
        End time of the first step with a slack segment (s) and that segment's index from
        end_a (the one with the smallest strain), or None.
    """

    status: str
    message: str
    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray | None
    tension: np.ndarray
    strain: np.ndarray
    top_force: np.ndarray
    residual: np.ndarray
    scheme: str
    time_step: float
    steps: int
    wall_time_s: float
    build_time_s: float
    mean_iterations: float = math.nan
    compiled: str = "none"
    min_strain: float = math.nan
    slack: tuple[float, int] | None = None

    @property
    def success(self) -> bool:
        """True when every step converged."""
        return self.status == "solved"


def step_grid(duration: float, time_step: float, record_every: int) -> tuple[int, int, float]:
    """``(k, n_steps, dt)`` of a run over ``duration``: k = ``record_every`` (at least 1) and
    the fewest steps, a multiple of k, of at most ``time_step`` (to 1e-9 of a step) that
    fill it exactly.

    Parameters
    ----------
    duration : float
        Simulated time, s (> 0, else :class:`CableOCPError`).
    time_step : float
        The largest step, s.
    record_every : int
        Steps per record.
    """
    if not duration > 0:
        raise CableOCPError(f"duration = {duration}: must be > 0")
    k = max(1, int(record_every))
    n_steps = max(1, int(math.ceil(duration / time_step - 1e-9)))
    n_steps = int(math.ceil(n_steps / k) * k)
    return k, n_steps, duration / n_steps


def run(model: LumpedMassModel, x0: np.ndarray, v0: np.ndarray | None, duration: float,
        time_step: float, *, scheme: str = "midpoint", record_every: int = 1,
        chunk_records: int | None = None, t0: float = 0.0, tol: float = 1e-10,
        max_iter: int = 20, solver: str = "newton", compile: str | bool = "kernel",
        progress: Callable[[float, float], Any] | None = None) -> LumpedRun:
    """Integrate the lumped-mass model from (x0, v0) at t0 over ``duration`` seconds.

    Steps are chained with ``mapaccum`` in chunks: no Python runs per time step. After each
    chunk ``progress(t_done, duration)`` is called (s, s) if given. A step whose scaled
    Newton residual stays above max(1000 tol, 1e-6) (or is NaN) stops the run with status
    ``"failed"`` at the last good record.

    Parameters
    ----------
    model : LumpedMassModel
    x0, v0 : ndarray (3 n_free,)
        Initial free-node positions (m) and velocities (m/s; None = at rest).
    duration : float
        Simulated time, s.
    time_step : float
        s; reduced if needed so that a whole number of steps (and of records) fills
        ``duration``.
    scheme : {"midpoint", "trapezoidal", "bdf2"}
        See :meth:`LumpedMassModel.step_function`.
    record_every : int
        Keep every k-th step.
    chunk_records : int, optional
        Records per chunk (default: about 20 chunks).
    t0 : float
        Start time, s.
    tol : float
        Newton tolerance on the residual scaled by the force scale (-; the largest of the
        total weight in water and the largest tension at the start).
    max_iter : int
        Newton iterations per step.
    solver : {"newton", "rootfinder"}
        See :meth:`LumpedMassModel.step_function`.
    compile : {"kernel", "step", False}
        ``"kernel"`` (default): the per-segment kernel is compiled to C once per machine
        (cached; needs a C compiler, else interpreted); ``"step"``: the whole chunk of
        steps (Newton iterations, linear solves) is generated as C and compiled, cached by
        the hash of its code (a few seconds per new scene and time step; fastest);
        False: everything interpreted by CasADi's virtual machine. All give the same
        numbers up to rounding.
    progress : callable, optional
        ``progress(t_done, duration)`` after each chunk (s, s).
    """
    import time

    if compile not in ("kernel", "step", False):
        raise CableOCPError(f"compile = {compile!r}: valid are 'kernel', 'step', False")

    k, n_steps, dt = step_grid(duration, time_step, record_every)
    n_rec = n_steps // k
    c = chunk_records or max(1, int(math.ceil(n_rec / 20)))
    c = min(c, n_rec)
    tb = time.perf_counter()
    x0 = np.asarray(x0, float).reshape(-1)
    fscale = model.force_scale(x0, t0)
    step = model.step_function(dt, scheme, tol=tol, max_iter=max_iter, solver=solver,
                               compile_kernel=compile == "kernel", force_scale=fscale)
    zs = ca.MX.sym("z", step.size1_in(0))
    ts = ca.MX.sym("t")
    # a record = k steps: last state, largest residual, iterations, smallest strain, the
    # first step (0..k-1) that ends slack (k: none) and its slack segment
    acc = step.mapaccum("acc", k)
    zk, rk, ik, ek, sk = acc(zs, ts + dt * ca.DM(np.arange(k).reshape(1, -1)))
    first = ca.find((ek <= 0.0).T)
    seg_first = ca.dot(sk.T, ca.DM(np.arange(k)) == first)
    rec = ca.Function("rec", [zs, ts], [zk[:, -1], ca.mmax(rk), ca.sum2(ik), ca.mmin(ek),
                                        first, seg_first])
    # one chunk function; the last chunk is padded beyond the end and cut
    chunk = rec.mapaccum("chunk", c)
    compiled = "none"
    if compile == "kernel" and solver == "newton" and segment_kernel(
            model.params.drag_law, True, model.params.tension_strain,
            model.params.viscoelastic is not None).class_name() == "External":
        compiled = "kernel"
    if compile == "step":
        cc = compile_function(chunk, "-O1")  # -O2: 4x the compile time, the same speed here
        compiled = "step" if cc is not chunk else "none"
        chunk = cc
    build = time.perf_counter() - tb
    z = model.initial_state(x0, v0, scheme, t0)
    nf3 = 3 * model.n_free
    zs_out = [z[None, :]]
    res_out = [np.zeros(1)]
    times = [np.array([t0])]
    iterations = 0.0
    slack: tuple[float, int] | None = None
    min_strain = math.inf
    status, message = "solved", f"{n_steps} steps of {dt:.6g} s ({scheme})"
    tw = time.perf_counter()
    done = 0
    tol_fail = max(1e3 * tol, 1e-6)
    try:
        while done < n_rec:
            m = min(c, n_rec - done)
            tstart = t0 + dt * k * (done + np.arange(c))
            zc, rc, ic, ec, fc, sc = chunk(z, tstart[None, :])
            zc = np.asarray(zc).T[:m]
            rc = np.asarray(rc).reshape(-1)[:m]
            tstart = tstart[:m]
            ic = np.asarray(ic).reshape(-1)[:m]
            ec = np.asarray(ec).reshape(-1)[:m]
            fc = np.asarray(fc).reshape(-1)[:m]
            sc = np.asarray(sc).reshape(-1)[:m]
            found = (fc >= 0) & (fc < k)  # casadi.find returns k when nothing is found
            if slack is None and np.any(found):
                j = int(np.flatnonzero(found)[0])
                slack = (float(tstart[j] + dt * (fc[j] + 1)), int(round(sc[j])))
            min_strain = min(min_strain, float(np.min(ec)))
            bad = np.flatnonzero(~np.isfinite(rc) | (rc > tol_fail)
                                 | ~np.all(np.isfinite(zc), axis=1))
            iterations += float(np.nansum(ic[:bad[0]] if bad.size else ic))
            if bad.size:
                b = int(bad[0])
                zs_out.append(zc[:b])
                res_out.append(rc[:b])
                times.append(tstart[:b] + dt * k)
                status = "failed"
                message = (f"Newton did not converge in a step ending by t = "
                           f"{tstart[b] + dt * k:.6g} s (scaled residual {rc[b]:.3g} > "
                           f"{tol_fail:.3g}); the history stops at the last good record: a "
                           "smaller time step may help")
                break
            zs_out.append(zc)
            res_out.append(rc)
            times.append(tstart + dt * k)
            z = zc[-1]
            done += m
            if progress is not None:
                progress(min(done * k * dt, duration), duration)
    except (KeyboardInterrupt, Exception) as exc:  # a Ctrl-C: keep the records finished
        if not interrupt.is_interruption(exc):
            raise
        n_ok = min(len(zs_out), len(res_out), len(times))  # the signal may fall between them
        del zs_out[n_ok:], res_out[n_ok:], times[n_ok:]
        status = "interrupted"
        message = (f"interrupted after {float(times[-1][-1]) - t0:.6g} s of simulated time; "
                   "the history stops at the last record finished")
    wall = time.perf_counter() - tw
    zall = np.concatenate(zs_out)
    tall = np.concatenate(times)
    xs, vs = zall[:, :nf3], zall[:, nf3:2 * nf3]
    n = len(tall)
    pos = np.asarray(model.nodes.map(n)(xs.T, tall[None, :]))
    positions = pos.reshape(3, n, model.params.segments + 1).transpose(1, 2, 0)
    vel = np.asarray(model.node_velocities.map(n)(vs.T, tall[None, :]))
    velocities = vel.reshape(3, n, model.params.segments + 1).transpose(1, 2, 0)
    strain = model.tensions.map(n)(xs.T, tall[None, :])[1]
    # the viscoelastic law's tensions need the dashpot strains (the state's last N)
    evs = [zall[:, 3 * nf3:].T] if model.solid is not None else []
    tens = model.segment_tension.map(n)(xs.T, vs.T, tall[None, :], *evs)
    ftop = np.asarray(model.top_force.map(n)(xs.T, vs.T, tall[None, :], *evs)).T
    steps = (len(tall) - 1) * k
    return LumpedRun(
        status=status, message=message, t=tall, x=xs, v=vs, positions=positions,
        velocities=velocities,
        tension=np.asarray(tens).T, strain=np.asarray(strain).T, top_force=ftop,
        residual=np.concatenate(res_out), scheme=scheme, time_step=dt,
        steps=steps, wall_time_s=wall, build_time_s=build,
        mean_iterations=iterations / max(steps, 1), compiled=compiled,
        min_strain=min_strain, slack=slack)
