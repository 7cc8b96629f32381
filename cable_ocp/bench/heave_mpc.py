"""MPC timing benchmark (issue 4): solve time per step, median and p99, with the delay.

Problem: example 6.3.6 as in ``problems/heave/ex_6_3_6.toml`` (plant (6.28) with 11 states,
first-order winch, 0.2 s delay = 4 samples at 0.05 s, weights q, r, stroke/speed/command-rate
limits and the soft tension limit, all read from that file), closed loop on the exactly sampled
plant driven by the seeded sea. Each solver's problem is built once and warm-started; the timing
covers the whole ``step`` (gradient/bound assembly + solve). do-mpc (optional, never a test
dependency) is given the same problem when installed: the same sampled model and stage cost
(state, cross and input terms), DARE terminal cost, command bounds, stroke, speed and
command-rate limits and the soft tension limit (do-mpc's soft constraints have a linear penalty
only; ours add a quadratic one).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave import plant as pl
from cable_ocp.heave.discrete import discretize_noise
from cable_ocp.heave.simulate import build_models
from cable_ocp.scene.heave import HeaveScene, load_scene

SCENE = Path(__file__).resolve().parents[2] / "problems" / "heave" / "ex_6_3_6.toml"


def bench_scene() -> HeaveScene:
    """The 6.3.6 scene the benchmark runs (limits, weights, delay, sample time)."""
    return load_scene(SCENE)


def bench_settings(sc: HeaveScene, horizon: int, solver: str) -> mpc_mod.MPCSettings:
    """MPC settings from the scene's ``[controller]`` and ``[winch]`` tables."""
    c, w, u = sc.controller, sc.winch, sc.unit
    return mpc_mod.MPCSettings(
        horizon=horizon, sample_time=c.sample_time, q=c.q, r=c.r, solver=solver,
        stroke_max=w.stroke_max, speed_max=w.speed_max, command_rate_max=w.command_rate_max,
        accel_max=w.accel_max, tension_min=w.tension_min, unit_mass=u.mass,
        static_tension=u.static_tension, tension_penalty=c.tension_penalty)


@dataclass(frozen=True)
class BenchRow:
    """One timing row: solver, horizon, median and p99 step time (s), steps, failures."""

    solver: str
    horizon: int
    median_s: float
    p99_s: float
    steps: int
    failures: int
    note: str = ""


def bench_plant(sc: HeaveScene | None = None) -> pl.HeavePlant:
    """The 6.3.6 plant (6.28), built from the scene."""
    return build_models(sc or bench_scene()).plant


def _noise(p: pl.HeavePlant, h: float, steps: int, seed: int) -> np.ndarray:
    lam, V = np.linalg.eigh(discretize_noise(p.A, p.B2, np.pi, h))
    L = V * np.sqrt(np.clip(lam, 0, None))
    return np.random.default_rng(seed).standard_normal((steps, p.n)) @ L.T


def time_cas(solver: str, horizon: int, steps: int, seed: int = 0) -> BenchRow:
    """Closed-loop timing of :class:`cable_ocp.heave.mpc.LinearMPC` with ``solver``."""
    sc = bench_scene()
    p = bench_plant(sc)
    m = mpc_mod.LinearMPC(p, sc.winch.delay, bench_settings(sc, horizon, solver))
    w = _noise(p, sc.controller.sample_time, steps, seed)
    z = np.zeros(m.nz)
    up = 0.0
    ts, fails = [], 0
    for k in range(steps):
        r = m.step(z, up)
        ts.append(r.solve_time)
        fails += not r.success
        up = r.u0
        z = m.model.Ad @ z + m.model.Bd[:, 0] * r.u0
        z[: p.n] += w[k]
    ts = np.array(ts[1:])  # the first call includes one-off set-up
    return BenchRow(solver, horizon, float(np.median(ts)), float(np.percentile(ts, 99)),
                    steps, fails,
                    "condensed dense QP" if solver != "ipopt" else "multiple shooting NLP")


def time_do_mpc(horizon: int, steps: int, seed: int = 0) -> BenchRow:
    """The same problem in do-mpc (discrete model with the shift register, IPOPT)."""
    import casadi as cs
    import do_mpc  # optional benchmark dependency

    sc = bench_scene()
    p = bench_plant(sc)
    st = bench_settings(sc, horizon, "qpoases")
    ref = mpc_mod.LinearMPC(p, sc.winch.delay, st)  # sampled model, cost and terminal cost
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
    w = _noise(p, st.sample_time, steps, seed)
    x = np.zeros((nz, 1))
    ctl.x0 = x
    ctl.set_initial_guess()
    ts, fails = [], 0
    for k in range(steps):
        t0 = time.perf_counter()
        u0 = ctl.make_step(x)
        ts.append(time.perf_counter() - t0)
        fails += not bool(ctl.solver_stats.get("success", True))
        x = Ad @ x + Bd * float(u0[0, 0])
        x[:n, 0] += w[k]
    ts = np.array(ts[1:])
    return BenchRow("do-mpc (ipopt)", horizon, float(np.median(ts)),
                    float(np.percentile(ts, 99)), steps, fails,
                    f"do-mpc {do_mpc.__version__}, discrete model, same cost and limits "
                    "(tension: linear penalty)")


def run(horizons: list[int] | tuple = (20, 50, 100), steps: int = 300,
        solvers: list[str] | tuple = ("qpoases", "osqp", "qrqp", "ipopt"),
        with_do_mpc: bool = True) -> list[BenchRow]:
    """Timing rows for every solver and horizon (IPOPT and do-mpc with steps/5 steps)."""
    rows = []
    for N in horizons:
        for s in solvers:
            rows.append(time_cas(s, N, steps if s != "ipopt" else max(20, steps // 5)))
        if with_do_mpc:
            try:
                rows.append(time_do_mpc(N, max(20, steps // 5)))
            except ImportError:
                rows.append(BenchRow("do-mpc", N, float("nan"), float("nan"), 0, 0,
                                     "not installed (pip install do-mpc)"))
    return rows


def format_table(rows: list[BenchRow]) -> str:
    """Plain-text table of :func:`run`'s rows, with the speed-up over do-mpc per horizon."""
    lines = [f"{'solver':<16} {'N':>4} {'median ms':>10} {'p99 ms':>9} {'steps':>6} "
             f"{'fails':>6}  note"]
    dom = {r.horizon: r.median_s for r in rows if r.solver.startswith("do-mpc")}
    for r in rows:
        note = r.note
        if not r.solver.startswith("do-mpc") and np.isfinite(dom.get(r.horizon, np.nan)):
            ratio = dom[r.horizon] / r.median_s
            note += (f"; {ratio:.1f}x faster than do-mpc" if ratio >= 1
                     else f"; {1 / ratio:.1f}x slower than do-mpc")
        lines.append(f"{r.solver:<16} {r.horizon:>4} {1e3 * r.median_s:10.3f} "
                     f"{1e3 * r.p99_s:9.3f} {r.steps:>6} {r.failures:>6}  {note}")
    return "\n".join(lines)
