"""Huang (1992), section 6.2.6 with the thesis' own gains: G3 and G5 in the closed loop.

G3 = [93.944, 41.41, 5.166] on the undelayed regulator plant (6.6) (Figs. 6.14-6.16) and
G5 = [296.97, 132.73, 15.95, 2.306, 0.164] with the Taylor delay model (6.14) on the plant with
a true 0.2 s winch delay (Fig. 6.17), K = 1 1/s (6.2.6 states no K), each through the project's
one closed loop on a seeded boom-tip record of the Fig. 6.10 sea (Pierson-Moskowitz, Hs = 6 m,
Tz = 14 s). Prints the closed-loop poles, the decay of a displaced start against the slowest
pole, and the numbers behind what the text says of Figs. 6.14-6.17 (the figures themselves are
lost from the thesis' text: only their captions remain); draws the four responses.
(:mod:`cable_ocp.heave.regulator`.)

Run:  python examples/heave_printed_gains_6_2_6.py [--out heave_printed_gains_6_2_6.png]
      [--duration 300] [--seed 2]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from cable_ocp.heave import regulator as rg


def compute(duration: float = 300.0, seed: int = 2) -> dict:
    """Every number and curve of the example (``duration`` of the sea record, s)."""
    res: dict = {"duration": duration, "poles": {}, "true_poles": {}, "decay": {}}
    for g in ("G3", "G5"):
        res["poles"][g] = rg.design_poles(g)
        res["true_poles"][g] = rg.true_loop_poles(g, 0.01)
        tr = rg.free_response(g, 1.0, duration=30.0)
        res["decay"][g] = rg.decay_rate(tr.t, tr.x, 5.0)
    res["run"] = rg.simulate_printed(duration=duration, seed=seed,
                                     warmup=min(30.0, duration / 3))
    res["numbers"] = rg.stated_numbers(res["run"])
    return res


def report(res: dict) -> str:
    """The printed results, one per line."""
    lines = []
    for g in ("G3", "G5"):
        lines.append(f"{g} design poles (A - B G): {np.round(res['poles'][g], 4)}")
        lines.append(f"{g} poles of the loop with the true delay, sampled at 10 ms: "
                     f"{np.round(res['true_poles'][g][-4:], 4)} (the four slowest)")
        lines.append(f"{g} free response from x = 1 m: decay {res['decay'][g]:.5f} 1/s")
    n = res["numbers"]
    lines.append(f"uncontrolled heave RMS: {n['uncontrolled']['heave_rms']:.3f} m")
    for g in ("G3", "G5"):
        r = n[g]
        lines.append(f"{g}: heave RMS {r['heave_rms']:.4f} m ({r['reduction_pct']:.2f} % "
                     f"reduction), corr(u, x0) = {r['opposition']:.4f}, rms(x0 + u) / rms(x0)"
                     f" = {r['residual_ratio']:.4f}, J_c = {r['J_c']:.0f}, "
                     f"J_w = {r['J_w']:.2f} m^2/s")
    return "\n".join(lines)


def plot(res: dict, path: str | Path) -> Path:
    """The responses (cf. Figs. 6.14-6.17) to ``path`` (format by suffix)."""
    from cable_ocp.plots.common import legend_below, new_figure, save

    run = res["run"]
    t = run.t
    fig = new_figure(11.5, 8.0)
    ax = fig.subplots(4, 1, sharex=True)
    h = ax[0].plot(t, run.x0, color="C0", lw=0.8, label="boom tip x0")
    ax[0].set(ylabel="x0 (m)", title="Boom-tip motion (cf. Fig. 6.14)")
    unc = run.traces["uncontrolled"]
    h += ax[1].plot(t, unc.x, color="0.6", lw=0.8, label="unit, uncontrolled")
    h += ax[1].plot(t, run.traces["G3"].x, color="C3", lw=0.9, label="unit, G3")
    ax[1].set(ylabel="x (m)", title="Unit heave, G3 = [93.944, 41.41, 5.166], no delay "
              "(cf. Fig. 6.15)")
    h += ax[2].plot(t, run.traces["G3"].u, color="C2", lw=0.9, label="winch output u, G3")
    ax[2].plot(t, -run.x0, color="C0", lw=0.6, ls="--")
    ax[2].set(ylabel="u (m)", title="Winch output against -x0 (dashed), G3 (cf. Fig. 6.16)")
    ax[3].plot(t, unc.x, color="0.6", lw=0.8)
    h += ax[3].plot(t, run.traces["G5"].x, color="C4", lw=0.9, label="unit, G5 (0.2 s delay)")
    ax[3].set(ylabel="x (m)", xlabel="t (s)",
              title="Unit heave, delay 0.2 s, G5 = [296.97, 132.73, 15.95, 2.306, 0.164] "
                    "(cf. Fig. 6.17)")
    for a in ax:
        a.grid(True, alpha=0.25)
        a.title.set_fontsize(9.5)
    fig.suptitle("Huang 1992, 6.2.6: the printed gains in closed loop (K = 1 1/s), PM sea "
                 f"Hs 6 m, Tz 14 s, {res['duration']:g} s", fontsize=10.5)
    legend_below(fig, h, ncols=3)
    path = Path(path)
    save(fig, path)
    return path


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(
        description="Huang (1992), section 6.2.6 with the thesis' printed gains G3 and G5 in "
                    "the closed loop: poles, decay of a displaced start, and the responses "
                    "of Figs. 6.14-6.17 on a seeded Pierson-Moskowitz boom-tip record "
                    "(written as a figure).")
    ap.add_argument("--out", default="heave_printed_gains_6_2_6.png", metavar="PATH",
                    help="figure file; PNG, PDF or SVG by its suffix (default %(default)s)")
    ap.add_argument("--duration", type=float, default=300.0, metavar="S",
                    help="length of the boom-tip record, s (default %(default)s)")
    ap.add_argument("--seed", type=int, default=2, metavar="N",
                    help="seed of the boom-tip record (default %(default)s)")
    args = ap.parse_args(argv)
    if args.duration <= 30:
        ap.error(f"--duration {args.duration}: must be > 30 (s)")
    res = compute(args.duration, args.seed)
    print(report(res))
    plot(res, args.out)
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
