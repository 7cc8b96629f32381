"""MPC timing benchmark (issue 4): solve time per step, median and p99, with the delay.

Plant: example 6.3.6 (``problems/heave/ex_6_3_6.toml`` values: 11 states, first-order winch,
0.2 s delay = 4 samples at 0.05 s, stroke/speed/command-rate limits, soft tension), closed loop
on the exactly sampled plant driven by the seeded sea. Each solver's problem is built once and
warm-started; the timing covers the whole ``step`` (gradient/bound assembly + solve). do-mpc is
timed on the same plant when it is installed (optional; never a test dependency).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave import plant as pl
from cable_ocp.heave import sea
from cable_ocp.heave.discrete import discretize_noise
from cable_ocp.heave.thesis import A_636, B_636, HS_636, KV_636, WM_636, WV_636, ZETA_V_636

H = 0.05
TAU = 0.2
LIMITS = {"stroke_max": 2.0, "speed_max": 1.5, "command_rate_max": 0.1, "tension_min": 5000.0,
          "unit_mass": 125000.0, "static_tension": 50000.0}


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


def bench_plant() -> pl.HeavePlant:
    """The 6.3.6 plant (6.28)."""
    return pl.assemble_plant(A_636, B_636, pl.winch_first(1.0),
                             vessel=pl.vessel_block(WV_636, ZETA_V_636, KV_636),
                             sea=sea.thesis_shaping_filter(HS_636, WM_636))


def _noise(p: pl.HeavePlant, steps: int, seed: int) -> np.ndarray:
    lam, V = np.linalg.eigh(discretize_noise(p.A, p.B2, np.pi, H))
    L = V * np.sqrt(np.clip(lam, 0, None))
    return np.random.default_rng(seed).standard_normal((steps, p.n)) @ L.T


def time_cas(solver: str, horizon: int, steps: int, seed: int = 0) -> BenchRow:
    """Closed-loop timing of :class:`cable_ocp.heave.mpc.LinearMPC` with ``solver``."""
    p = bench_plant()
    m = mpc_mod.LinearMPC(p, TAU, mpc_mod.MPCSettings(horizon=horizon, sample_time=H,
                                                      solver=solver, **LIMITS))
    w = _noise(p, steps, seed)
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
    """Same plant, delay (shift states), limits and cost in do-mpc (discrete model)."""
    import casadi as cs
    import do_mpc  # optional benchmark dependency

    p = bench_plant()
    ref = mpc_mod.LinearMPC(p, TAU, mpc_mod.MPCSettings(horizon=1, sample_time=H, **LIMITS))
    Ad, Bd, nz, n = ref.model.Ad, ref.model.Bd, ref.nz, p.n
    model = do_mpc.model.Model("discrete")
    z = model.set_variable("_x", "z", shape=(nz, 1))
    u = model.set_variable("_u", "u0")
    model.set_rhs("z", cs.mtimes(cs.DM(Ad), z) + cs.DM(Bd) * u)
    c_str, _ = p.output_row("stretch")
    model.set_expression("stretch", cs.mtimes(cs.DM(c_str).T, z[:n]))
    iu = p.blocks["winch"].start
    model.set_expression("speed", p.K * (z[n] - z[iu]))
    model.setup()
    ctl = do_mpc.controller.MPC(model)
    ctl.settings.n_horizon = horizon
    ctl.settings.t_step = H
    ctl.settings.store_full_solution = False
    ctl.settings.nlpsol_opts = {"ipopt.print_level": 0, "print_time": 0, "ipopt.sb": "yes"}
    Qz = cs.DM(ref.Qz)
    lterm = cs.bilin(Qz, z, z)
    mterm = cs.bilin(cs.DM(ref.P), z, z)
    ctl.set_objective(lterm=lterm, mterm=mterm)
    ctl.set_rterm(u0=0.0)
    ctl.bounds["lower", "_u", "u0"] = -LIMITS["stroke_max"]
    ctl.bounds["upper", "_u", "u0"] = LIMITS["stroke_max"]
    ctl.set_nl_cons("speed_hi", model.aux["speed"], ub=LIMITS["speed_max"])
    ctl.set_nl_cons("speed_lo", -model.aux["speed"], ub=LIMITS["speed_max"])
    ctl.setup()
    w = _noise(p, steps, seed)
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
                    f"do-mpc {do_mpc.__version__}, collocation-free discrete model; "
                    "stroke as command bound, speed limit, no rate/tension limits")


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
            note += f"; {dom[r.horizon] / r.median_s:.1f}x faster than do-mpc"
        lines.append(f"{r.solver:<16} {r.horizon:>4} {1e3 * r.median_s:10.3f} "
                     f"{1e3 * r.p99_s:9.3f} {r.steps:>6} {r.failures:>6}  {note}")
    return "\n".join(lines)
