"""MPC timing benchmark: solve time per step, median and p99, with the delay.

Problem: example 6.3.6 of Huang (1992) as in ``problems/heave/ex_6_3_6.toml`` (plant (6.28) with 11
states, first-order winch, 0.2 s delay = 4 samples at 0.05 s, weights q, r,
stroke/speed/command-rate limits and the soft tension limit, all read from that file), closed loop
on the exactly sampled plant driven by the seeded sea. Each solver's problem is built once and
warm-started; the timing covers the whole ``step`` (the state with the MPC's own delay buffer,
gradient/bound assembly + solve), the first step (one-off set-up) excluded. With the file's limits
and sea no limit is active after the first steps (not even under a 12x sea in the 15 s of a
300-step run); :data:`ACTIVE_LIMITS` with ``sea_scale = 3`` makes every limit active on many steps
(:func:`profile_daqp` counts the steps that change the working set). do-mpc (optional, never a test
dependency) is given the same problem when installed: the same sampled model and stage cost (state,
cross and input terms), DARE terminal cost, command bounds, stroke, speed and command-rate limits
and the soft tension limit (do-mpc's soft constraints have a linear penalty only; ours add a
quadratic one).
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave import plant as pl
from cable_ocp.heave.design_loop import build_models
from cable_ocp.heave.discrete import discretize_noise
from cable_ocp.numerics.text_table import table
from cable_ocp.scene.heave import HeaveScene, load_scene

SCENE = Path(__file__).resolve().parents[2] / "problems" / "heave" / "ex_6_3_6.toml"


def bench_scene() -> HeaveScene:
    """The 6.3.6 scene the benchmark runs (limits, weights, delay, sample time)."""
    return load_scene(SCENE)


def bench_settings(scene: HeaveScene, horizon: int, solver: str) -> mpc_mod.MPCSettings:
    """MPC settings from the scene's ``[controller]`` and ``[winch]`` tables.

    Parameters
    ----------
    scene : HeaveScene
        The heave scene: sample time, weights, winch limits, unit mass and static tension.
    horizon : int
        Prediction horizon, samples of the scene's sample time.
    solver : str
        The MPC's solver, one of :data:`cable_ocp.heave.mpc.SOLVERS` (``"daqp"``,
        ``"qpoases"``, ``"osqp"``, ``"qrqp"``, ``"ipopt"``).
    """
    c, w, u = scene.controller, scene.winch, scene.unit
    return mpc_mod.MPCSettings(
        horizon=horizon, sample_time=c.sample_time, q=c.q, r=c.r, solver=solver,
        stroke_max=w.stroke_max, speed_max=w.speed_max, command_rate_max=w.command_rate_max,
        accel_max=w.accel_max, tension_min=w.tension_min, unit_mass=u.mass,
        static_tension=u.static_tension, tension_penalty=c.tension_penalty)


@dataclass(frozen=True)
class BenchRow:
    """One timing row: solver, horizon, median and p99 step time (s), steps, failures.

    ``median_s``/``p99_s`` are wall time per step. ``cpu_median_s``/``cpu_p99_s`` are the
    CPU time of the calling thread over the same steps (the solvers run in it; the process
    CPU time would also count idle-spinning BLAS threads): on a shared machine a step that is
    preempted by another process keeps its CPU time while its wall time grows by a scheduler
    slice (milliseconds), so the CPU p99 shows the solver's own tail.
    """

    solver: str
    horizon: int
    median_s: float
    p99_s: float
    steps: int
    failures: int
    note: str = ""
    cpu_median_s: float = float("nan")
    cpu_p99_s: float = float("nan")


def bench_plant(scene: HeaveScene | None = None) -> pl.HeavePlant:
    """The 6.3.6 plant (6.28), built from the scene."""
    return build_models(scene or bench_scene()).plant


def _noise(p: pl.HeavePlant, h: float, steps: int, seed: int) -> np.ndarray:
    lam, V = np.linalg.eigh(discretize_noise(p.A, p.B2, np.pi, h))
    L = V * np.sqrt(np.clip(lam, 0, None))
    return np.random.default_rng(seed).standard_normal((steps, p.n)) @ L.T


def _closed_loop(solver: str, horizon: int, steps: int, seed: int, sea_scale: float,
                 overrides: dict | None
                 ) -> tuple[pl.HeavePlant, mpc_mod.LinearMPC, np.ndarray]:
    """The benchmark's plant, its MPC (``solver``, ``horizon``, the scene's settings with
    ``overrides``) and the sea's process noise of each of ``steps`` steps."""
    sc = bench_scene()
    p = bench_plant(sc)
    st = dataclasses.replace(bench_settings(sc, horizon, solver), **(overrides or {}))
    m = mpc_mod.LinearMPC(p, sc.winch.delay, st)
    w = sea_scale * _noise(p, sc.controller.sample_time, steps, seed)
    return p, m, w


def _row(solver: str, horizon: int, ts: list[float], cpu: list[float], steps: int,
         fails: int, note: str) -> BenchRow:
    """A timing row from the wall and CPU times of every step, the first (one-off set-up)
    left out of the median and p99."""
    wall = np.array(ts[1:])
    return BenchRow(solver, horizon, float(np.median(wall)), float(np.percentile(wall, 99)),
                    steps, fails, note, float(np.median(cpu[1:])),
                    float(np.percentile(cpu[1:], 99)))


# Limits that the 3x sea makes active (stroke via the command bounds, speed, command rate and the
# soft tension limit), as in the equality test of the DAQP and qpOASES moves.
ACTIVE_LIMITS = {"stroke_max": 0.2, "speed_max": 0.15, "command_rate_max": 0.01,
                 "tension_min": 40000.0}

NOTES = {"daqp": "condensed dense QP, persistent DAQP workspace",
         "qpoases": "condensed dense QP via CasADi conic",
         "osqp": "condensed dense QP via CasADi conic",
         "qrqp": "condensed dense QP via CasADi conic",
         "ipopt": "multiple shooting NLP"}


def time_cas(solver: str, horizon: int, steps: int, seed: int = 0, sea_scale: float = 1.0,
             overrides: dict | None = None) -> BenchRow:
    """Closed-loop timing of :class:`cable_ocp.heave.mpc.LinearMPC` with ``solver``.

    ``steps`` closed-loop steps are run; the first (one-off set-up) is left out of the median
    and p99. ``sea_scale`` multiplies the sea's process noise (1: the scene's sea);
    ``overrides`` replaces MPC settings (e.g. :data:`ACTIVE_LIMITS`).

    Parameters
    ----------
    solver : str
        The MPC's solver, one of :data:`cable_ocp.heave.mpc.SOLVERS` (``"daqp"``,
        ``"qpoases"``, ``"osqp"``, ``"qrqp"``, ``"ipopt"``).
    horizon : int
        Prediction horizon, samples (of the scene's 0.05 s sample time).
    steps : int
        Closed-loop steps to run; the first (one-off set-up) is left out of the times.
    seed : int
        Seed of the sea's process noise (default 0).
    sea_scale : float
        Factor on the sea's process noise (-); default 1: the scene's sea.
    overrides : dict, optional
        :class:`~cable_ocp.heave.mpc.MPCSettings` fields to replace (e.g.
        :data:`ACTIVE_LIMITS`: stroke in m, speed in m/s, command rate in m per sample,
        tension in N). None (default): the scene's settings.
    """
    p, m, w = _closed_loop(solver, horizon, steps, seed, sea_scale, overrides)
    z = np.zeros(m.nz)
    up = 0.0
    ts, cpu, fails = [], [], 0
    for k in range(steps):
        c0 = time.thread_time()
        r = m.step(z[: p.n], up)  # the MPC keeps the delay buffer (equal to z's)
        cpu.append(time.thread_time() - c0)
        ts.append(r.solve_time)
        fails += not r.success
        up = r.u0
        z = m.model.Ad @ z + m.model.Bd[:, 0] * r.u0
        z[: p.n] += w[k]
    return _row(solver, horizon, ts, cpu, steps, fails, NOTES.get(solver, ""))


def profile_daqp(horizon: int = 50, steps: int = 300, seed: int = 0, sea_scale: float = 1.0,
                 overrides: dict | None = None) -> dict:
    """Where the time of a ``"daqp"`` step goes (medians over the closed loop, s).

    Two runs of the same closed loop (same states: the moves agree to round-off). The first
    times the real :meth:`LinearMPC.step` (``step``, ``step_p99``, as :func:`time_cas`). The
    second repeats the phases of a step one by one, as ``step`` does them, and times each:
    ``assembly`` (the one matrix-vector product with the precomputed parametric maps that gives
    the gradient and the row offsets), then for the QP without the tension rows ``bounds`` (its
    row bounds), ``update`` (DAQP's update of the gradient and bounds in its factored problem),
    ``solve`` (DAQP's iterations from the previous working set) and ``check`` (the tension rows
    at that solution); ``full`` is the whole QP with the slacks (bounds, update and solve),
    timed over the ``full_steps`` steps that need it (a tension row binds). ``phases`` is the
    median of the per-step sum of the phases and ``other`` = ``step`` - ``phases`` (argument
    handling, the plan copy, the result object). Also: DAQP iterations of the reduced QP per
    step (median, max) and the steps that changed its working set (more than one iteration).

    Parameters
    ----------
    horizon : int
        Prediction horizon, samples of the scene's 0.05 s sample time (default 50).
    steps : int
        Closed-loop steps to run (default 300); the first (one-off set-up) is left out of
        the times.
    seed : int
        Seed of the sea's process noise (default 0).
    sea_scale : float
        Factor on the sea's process noise (-); default 1: the scene's sea.
    overrides : dict, optional
        :class:`~cable_ocp.heave.mpc.MPCSettings` fields to replace (e.g.
        :data:`ACTIVE_LIMITS`: stroke in m, speed in m/s, command rate in m per sample,
        tension in N). None (default): the scene's settings.
    """
    ref = time_cas("daqp", horizon, steps, seed, sea_scale, overrides)
    p, m, w = _closed_loop("daqp", horizon, steps, seed, sea_scale, overrides)
    qp = m._daqp
    assert qp is not None
    two_stage = qp.reduced is not None
    red = qp.reduced if two_stage else qp.full
    nv, N = m._nv, m.N
    mh = qp.mh if two_stage else m.Ac.shape[0]
    nr = red.nv
    z = np.zeros(m.nz)
    up = 0.0
    keys = ("assembly", "bounds", "update", "solve", "check", "full", "phases")
    rec: dict[str, list[float]] = {k: [] for k in keys}
    its = []
    binding = False
    pc = time.perf_counter
    for k in range(steps):
        t0 = pc()
        v = m._Pz @ z
        v += m._p0
        v += up * m._Pu
        g, c = v[:nv], v[nv:]
        t1 = pc()
        times = {"assembly": t1 - t0}
        need_full = binding
        if not binding:
            np.subtract(red.ub0, c[:mh], out=red.bu[nr:])
            np.subtract(red.lb0, c[:mh], out=red.bl[nr:])
            t2 = pc()
            red.model.update(f=g[:nr], bupper=red.bu, blower=red.bl)
            t3 = pc()
            x, _, _, info = red.model.solve()
            t4 = pc()
            if two_stage:
                tt = qp.A_soft @ x[:N]
                tt += c[mh:]
                need_full = not (tt >= qp.lb_soft).all()
            t5 = pc()
            times.update(bounds=t2 - t1, update=t3 - t2, solve=t4 - t3, check=t5 - t4)
            its.append(int(info["iterations"]))
        if need_full:
            t5 = pc()
            x, _ = qp.full.solve(g, c)
            times["full"] = pc() - t5
            binding = float(np.max(x[N:])) > qp.tol
        if k > 0:
            for key, dt in times.items():
                rec[key].append(dt)
            rec["phases"].append(sum(times.values()))
        up = float(x[0])
        z = m.model.Ad @ z + m.model.Bd[:, 0] * up
        z[: p.n] += w[k]
    out = {key: float(np.median(v)) if v else 0.0 for key, v in rec.items()}
    out["full_steps"] = len(rec["full"])
    out["step"], out["step_p99"] = ref.median_s, ref.p99_s
    out["other"] = out["step"] - out["phases"]
    out["iterations_median"] = float(np.median(its[1:]))
    out["iterations_max"] = int(np.max(its[1:]))
    out["working_set_changes"] = int(np.sum(np.array(its[1:]) > 1))
    out["n_variables"], out["n_rows"] = int(nv), int(m.Ac.shape[0])
    out["n_variables_reduced"], out["n_rows_reduced"] = int(nr), int(mh)
    return out


def time_do_mpc(horizon: int, steps: int, seed: int = 0) -> BenchRow:
    """The same problem in do-mpc (discrete model with the shift register, IPOPT).

    do-mpc's own warnings (optional features not installed, CasADi's notice about numpy
    functions on CasADi values inside do-mpc) are silenced: they are not about this problem.

    Parameters
    ----------
    horizon : int
        Prediction horizon, samples (of the scene's 0.05 s sample time).
    steps : int
        Closed-loop steps to run; the first (one-off set-up) is left out of the times.
    seed : int
        Seed of the sea's process noise (default 0).

    Raises
    ------
    ImportError
        When do-mpc is not installed.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return _time_do_mpc(horizon, steps, seed)


def _time_do_mpc(horizon: int, steps: int, seed: int) -> BenchRow:
    import casadi as cs
    import do_mpc  # optional benchmark dependency

    # the sampled model, cost and terminal cost of our MPC, and the same sea
    p, ref, w = _closed_loop("daqp", horizon, steps, seed, 1.0, None)
    st = ref.settings
    Ad, Bd, nz, n, d = ref.model.Ad, ref.model.Bd, ref.nz, p.n, ref.model.d
    model = do_mpc.model.Model("discrete")
    z = model.set_variable("_x", "z", shape=(nz, 1))
    u = model.set_variable("_u", "u0")
    model.set_rhs("z", cs.mtimes(cs.DM(Ad), z) + cs.DM(Bd) * u)
    iu = p.blocks["winch"].start
    applied = z[n] if d > 0 else u
    model.set_expression("speed", p.K * (applied - z[iu]))
    c_str, _ = p.output_row("stretch")
    model.set_expression("stretch", cs.mtimes(cs.DM(c_str).reshape((1, n)), z[:n]))
    if d > 0:
        model.set_expression("rate", u - z[nz - 1])  # newest buffered command = u0_{k-1}
    model.setup()
    ctl = do_mpc.controller.MPC(model)
    ctl.settings.n_horizon = horizon
    ctl.settings.t_step = st.sample_time
    ctl.settings.store_full_solution = False
    ctl.settings.nlpsol_opts = {"ipopt.print_level": 0, "print_time": 0, "ipopt.sb": "yes"}
    lterm = (cs.bilin(cs.DM(ref.Qz), z, z) + 2 * cs.mtimes([z.T, cs.DM(ref.Nz), u])
             + float(ref.Rz[0, 0]) * u**2)
    ctl.set_objective(lterm=lterm, mterm=cs.bilin(cs.DM(ref.P), z, z))
    ctl.set_rterm(u0=0.0)
    ctl.bounds["lower", "_u", "u0"] = -st.stroke_max
    ctl.bounds["upper", "_u", "u0"] = st.stroke_max
    lo = np.full((nz, 1), -np.inf)
    hi = np.full((nz, 1), np.inf)
    lo[iu], hi[iu] = -st.stroke_max, st.stroke_max
    ctl.bounds["lower", "_x", "z"] = lo
    ctl.bounds["upper", "_x", "z"] = hi
    ctl.set_nl_cons("speed_hi", model.aux["speed"], ub=st.speed_max)
    ctl.set_nl_cons("speed_lo", -model.aux["speed"], ub=st.speed_max)
    if d > 0:
        ctl.set_nl_cons("rate_hi", model.aux["rate"], ub=st.command_rate_max)
        ctl.set_nl_cons("rate_lo", -model.aux["rate"], ub=st.command_rate_max)
    ctl.set_nl_cons("tension", -model.aux["stretch"], ub=-ref.stretch_min, soft_constraint=True,
                    penalty_term_cons=float(ref.g_slack[-1]))
    ctl.setup()
    x = np.zeros((nz, 1))
    ctl.x0 = x
    ctl.set_initial_guess()
    ts, cpu, fails = [], [], 0
    for k in range(steps):
        c0 = time.thread_time()
        t0 = time.perf_counter()
        u0 = ctl.make_step(x)
        ts.append(time.perf_counter() - t0)
        cpu.append(time.thread_time() - c0)
        fails += not bool(ctl.solver_stats.get("success", True))
        x = Ad @ x + Bd * float(u0[0, 0])
        x[:n, 0] += w[k]
    return _row("do-mpc (ipopt)", horizon, ts, cpu, steps, fails,
                f"do-mpc {do_mpc.__version__}, discrete model, same cost and limits "
                "(tension: linear penalty)")


def run(horizons: list[int] | tuple = (20, 50, 100), steps: int = 300,
        solvers: list[str] | tuple = mpc_mod.SOLVERS,
        with_do_mpc: bool = True, sea_scale: float = 1.0,
        overrides: dict | None = None,
        progress: Callable[[int, int, BenchRow], None] | None = None) -> list[BenchRow]:
    """Timing rows for every solver and horizon (IPOPT and do-mpc with steps/5 steps).

    do-mpc's row has ``steps = 0`` and NaN times when it is not installed; it runs only on the
    scene as it is (``sea_scale = 1``, no ``overrides``). ``progress(done, total, row)`` is
    called after each row.

    Parameters
    ----------
    horizons : list or tuple of int
        Prediction horizons, samples of 0.05 s (default (20, 50, 100)).
    steps : int
        Closed-loop steps per row (default 300; IPOPT and do-mpc run ``max(20, steps // 5)``).
    solvers : list or tuple of str
        Solvers to time (default all of :data:`cable_ocp.heave.mpc.SOLVERS`).
    with_do_mpc : bool
        Add a do-mpc row per horizon (default True; only with the scene's own sea and
        settings).
    sea_scale : float
        Factor on the sea's process noise (-); default 1: the scene's sea.
    overrides : dict, optional
        :class:`~cable_ocp.heave.mpc.MPCSettings` fields to replace (e.g.
        :data:`ACTIVE_LIMITS`: stroke in m, speed in m/s, command rate in m per sample,
        tension in N). None (default): the scene's settings.
    progress : callable, optional
        ``progress(done, total, row)``, called after each row; None (default): none.
    """
    rows: list[BenchRow] = []
    dompc = with_do_mpc and sea_scale == 1.0 and not overrides
    total = len(horizons) * (len(solvers) + int(dompc))

    def add(row: BenchRow) -> None:
        rows.append(row)
        if progress is not None:
            progress(len(rows), total, row)

    for N in horizons:
        for s in solvers:
            add(time_cas(s, N, steps if s != "ipopt" else max(20, steps // 5),
                         sea_scale=sea_scale, overrides=overrides))
        if dompc:
            try:
                add(time_do_mpc(N, max(20, steps // 5)))
            except ImportError:
                add(BenchRow("do-mpc", N, float("nan"), float("nan"), 0, 0,
                             "not installed (pip install do-mpc)"))
    return rows


def format_table(rows: list[BenchRow]) -> str:
    """Plain-text table of :func:`run`'s rows (:func:`cable_ocp.numerics.text_table.table`),
    with the speed-up over do-mpc per horizon in the note."""
    dom = {r.horizon: r.median_s for r in rows if r.solver.startswith("do-mpc")}
    cells: list[list] = []
    notes: list[str] = []
    for r in rows:
        note = r.note
        if not r.solver.startswith("do-mpc") and np.isfinite(dom.get(r.horizon, np.nan)):
            ratio = dom[r.horizon] / r.median_s
            note += (f"; {ratio:.1f}x faster than do-mpc" if ratio >= 1
                     else f"; {1 / ratio:.1f}x slower than do-mpc")
        cells.append([r.solver, r.horizon] + [
            "-" if not np.isfinite(v) else f"{1e3 * v:.3f}"
            for v in (r.median_s, r.p99_s, r.cpu_median_s, r.cpu_p99_s)]
            + [r.steps, r.failures])
        if note.lstrip("; "):
            notes.append(f"{r.solver}, N = {r.horizon}: {note.lstrip('; ')}")
    return "\n".join([
        table(["solver", "N", "median", "p99", "CPU median", "CPU p99", "steps", "fails"],
              cells, ["", "", "[ms]", "[ms]", "[ms]", "[ms]", "", ""], left=1),
        *notes,
        "(ms per closed-loop step: wall time, and CPU time of the calling thread, which a",
        "preemption by another process does not inflate)"])


def json_data(rows: list[BenchRow]) -> dict:
    """``{"rows": [{"solver", "horizon", "median_ms", "p99_ms", "steps", "failures"}]}``.

    ``steps`` is the number of closed-loop steps run (the first, with the one-off set-up, is
    not in the median and p99); times in ms. do-mpc is included when it is installed (its
    placeholder row without steps is left out).
    """
    return {"rows": [{"solver": r.solver, "horizon": r.horizon,
                      "median_ms": 1e3 * r.median_s, "p99_ms": 1e3 * r.p99_s,
                      "steps": r.steps, "failures": r.failures}
                     for r in rows if r.steps > 0]}


def bench_json(horizons: list[int] | tuple = (20, 50, 100), steps: int = 300,
               solvers: list[str] | tuple = mpc_mod.SOLVERS, with_do_mpc: bool = True) -> dict:
    """Run the benchmark (:func:`run`) and return :func:`json_data` of its rows.

    Parameters
    ----------
    horizons : list or tuple of int
        Prediction horizons, samples of 0.05 s (default (20, 50, 100)).
    steps : int
        Closed-loop steps per row (default 300; IPOPT and do-mpc run ``max(20, steps // 5)``).
    solvers : list or tuple of str
        Solvers to time (default all of :data:`cable_ocp.heave.mpc.SOLVERS`).
    with_do_mpc : bool
        Add a do-mpc row per horizon when it is installed (default True).
    """
    return json_data(run(horizons, steps, solvers, with_do_mpc))
