"""Reproduce Huang (1992), section 6.2.6: printed gains, delay handling, Figs. 6.18-6.19.

Prints the closed-loop poles and delay margins of the thesis' printed gains, the LQR gains
of the delay treatments, and draws the trade-off curves J_d, J_v (6.16)-(6.17) against the
winch-speed energy J_w = int u'^2 dt on a seeded Pierson-Moskowitz boom-tip record
(Hs = 6 m, Tz = 14 s, Fig. 6.10). The thesis plots against J_c = sum G_i^2 (6.18); that
depends on the state realisation of a Pade design, J_w does not
(:func:`cable_ocp.heave.lqr.tradeoff_data`). The printed gains simulated in closed loop (Figs.
6.14-6.17): ``examples/heave_printed_gains_6_2_6.py``.

Run:  python examples/heave_regulator_6_2_6.py [--out heave_regulator_6_2_6.png]
      [--duration 200] [--seed 2]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from cable_ocp.heave import lqr, sea
from cable_ocp.heave import plant as pl
from cable_ocp.heave.design_loop import wave_realisation
from cable_ocp.heave.thesis import A_626, B_626, G3_626, G5_626, HS_626, TAU_626, TZ_626


def boom_tip(duration: float = 200.0, seed: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Boom-tip record of Fig. 6.10 from the thesis filter scaled to the PM sea (0.01 s)."""
    wm = sea.modal_frequency_from_zero_crossing(TZ_626)
    p = pl.assemble_plant(A_626, B_626, pl.winch_first(1.0), vessel=pl.direct_vessel(),
                          sea=sea.thesis_shaping_filter(HS_626, wm))
    t, x0, _ = wave_realisation(p, duration, 0.01, seed)
    return t, x0


def compute(duration: float = 200.0, seed: int = 2) -> dict:
    """Every number and curve of the example (``duration``: boom-tip record, s)."""
    res: dict = {}
    d3 = lqr.design_from_gains(A_626, B_626, G3_626)
    res["G3_poles"] = np.linalg.eigvals(d3.Ap - d3.Bp @ d3.Gp)
    res["G3_delay_margin"] = lqr.delay_margin(d3)
    d5 = lqr.design_from_gains(A_626, B_626, G5_626, tau=TAU_626, method="taylor")
    res["G5_interval"] = lqr.delay_interval(d5)
    Q = np.diag([8825.0, 0.0, 0.0])
    res["designs"] = {}
    for m in ["none", "taylor", "pade", "discrete"]:
        des = lqr.design_lqr(A_626, B_626, Q, tau=TAU_626, method=m)
        res["designs"][m] = (des.G, lqr.delay_margin(des))
    t, x0 = boom_tip(duration, seed)
    res["tradeoff"] = lqr.tradeoff_data(A_626, B_626, 1.0, TAU_626, t, x0)
    res["duration"] = duration
    return res


def report(res: dict) -> str:
    """The printed results, one per line."""
    lines = [f"G3 = [93.944, 41.41, 5.166] closed-loop poles: {np.round(res['G3_poles'], 4)}",
             f"G3 delay margin (exact crossing): {res['G3_delay_margin']:.4f} s",
             f"G5 (Taylor, 0.2 s) stable for true delays in ({res['G5_interval'].lower:.3f}, "
             f"{res['G5_interval'].upper:.4f}) s"]
    for m, (G, dm) in res["designs"].items():
        lines.append(f"Q = diag(8825, 0, 0), tau = 0.2 s, {m:9s}: G = {np.round(G, 3)}, "
                     f"delay margin {dm:.4f} s")
    return "\n".join(lines)


def plot(res: dict, path: str | Path) -> Path:
    """The trade-off curves (cf. Figs. 6.18-6.19) to ``path`` (format by suffix)."""
    from cable_ocp.plots.common import legend_below, new_figure, plain_log_ticks, save

    fig = new_figure(11.5, 5.4)
    ax = fig.subplots(1, 2)
    handles = []
    for k, (label, arr) in enumerate(res["tradeoff"].items()):
        style = {"marker": "os^"[k % 3], "ms": 5, "color": f"C{k + 3}"}
        handles += ax[0].loglog(arr[:, 0], arr[:, 1], "-", label=f"LQR design, {label}",
                                **style)
        ax[1].loglog(arr[:, 0], arr[:, 2], "-", **style)
    xl = "winch-speed energy J_w = ∫ u'² dt (m²/s)"
    ax[0].set(xlabel=xl, ylabel="displacement index J_d = ∫ x² dt (m² s)")
    ax[1].set(xlabel=xl, ylabel="velocity index J_v = ∫ x'² dt (m²/s)")
    ax[0].set_title("Unit displacement against winch effort\n(cf. Huang 1992, Fig. 6.18)",
                    fontsize=10)
    ax[1].set_title("Unit velocity against winch effort\n(cf. Huang 1992, Fig. 6.19)",
                    fontsize=10)
    for a in ax:
        a.grid(True, which="both", alpha=0.25)
        plain_log_ticks(a, "x")
    fig.suptitle("Huang 1992, section 6.2.6: LQR with a 0.2 s winch delay, Q = diag(q, 0, 0), "
                 f"q = 10 to 1e5; {res['duration']:g} s PM boom-tip record, Hs 6 m, Tz 14 s",
                 fontsize=10.5)
    legend_below(fig, handles, ncols=3)
    path = Path(path)
    save(fig, path)
    return path


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(
        description="Reproduce Huang (1992), section 6.2.6: the printed gains' poles and "
                    "delay margins, LQR gains for the delay treatments (none, Taylor, Pade, "
                    "discrete), and the trade-off curves of Figs. 6.18-6.19 (written as a "
                    "figure).")
    ap.add_argument("--out", default="heave_regulator_6_2_6.png", metavar="PATH",
                    help="figure file; PNG, PDF or SVG by its suffix (default %(default)s)")
    ap.add_argument("--duration", type=float, default=200.0, metavar="S",
                    help="length of the boom-tip record for the trade-off curves, s "
                         "(default %(default)s)")
    ap.add_argument("--seed", type=int, default=2, metavar="N",
                    help="seed of the boom-tip record (default %(default)s)")
    args = ap.parse_args(argv)
    if args.duration <= 0:
        ap.error(f"--duration {args.duration}: must be > 0 (s)")
    res = compute(args.duration, args.seed)
    print(report(res))
    plot(res, args.out)
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
