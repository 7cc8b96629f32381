"""Reproduce 004 section 6.2.6: printed gains, delay handling, Figs. 6.18-6.19.

Run ``python examples/heave_regulator_6_2_6.py [OUT.png]``. Prints the printed gains' closed-loop
poles and delay margins, the LQR gains of the three delay treatments, and saves the trade-off
curves J_d, J_v (6.16)-(6.17) versus the winch-speed energy J_w = int u'^2 dt on a seeded
Pierson-Moskowitz boom-tip record (Hs = 6 m, Tz = 14 s, Fig. 6.10). The thesis plots against
J_c = sum G_i^2 (6.18); that depends on the state realisation of a Pade design, J_w does not
(:func:`cable_ocp.heave.plots.tradeoff_data`).
"""

from __future__ import annotations

import sys

import numpy as np

from cable_ocp.heave import lqr, sea
from cable_ocp.heave import plant as pl
from cable_ocp.heave.simulate import wave_realisation
from cable_ocp.heave.thesis import A_626, B_626, G3_626, G5_626, HS_626, TAU_626, TZ_626


def boom_tip(duration: float = 200.0, seed: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Boom-tip record of Fig. 6.10 from the thesis filter scaled to the PM sea (0.01 s)."""
    wm = sea.modal_frequency_from_zero_crossing(TZ_626)
    p = pl.assemble_plant(A_626, B_626, pl.winch_first(1.0), vessel=pl.direct_vessel(),
                          sea=sea.thesis_shaping_filter(HS_626, wm))
    t, x0, _ = wave_realisation(p, duration, 0.01, seed)
    return t, x0


def main(out: str | None = None, duration: float = 200.0) -> dict:
    """Compute everything; save the figure if ``out``; return the numbers."""
    res = {}
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
    t, x0 = boom_tip(duration)
    from cable_ocp.heave.lqr import tradeoff_data

    res["tradeoff"] = tradeoff_data(A_626, B_626, 1.0, TAU_626, t, x0)
    if out:
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        for label, arr in res["tradeoff"].items():
            ax[0].loglog(arr[:, 0], arr[:, 1], "o-", label=label)
            ax[1].loglog(arr[:, 0], arr[:, 2], "o-", label=label)
        ax[0].set(xlabel="J_w = int u'^2 dt, m^2/s", ylabel="J_d (6.16), m^2 s", title="Fig. 6.18")
        ax[1].set(xlabel="J_w = int u'^2 dt, m^2/s", ylabel="J_v (6.17), m^2/s", title="Fig. 6.19")
        ax[0].legend()
        fig.tight_layout()
        fig.savefig(out, dpi=110)
        plt.close(fig)
    return res


if __name__ == "__main__":
    r = main(sys.argv[1] if len(sys.argv) > 1 else None)
    print("G3 = [93.944, 41.41, 5.166] closed-loop poles:", np.round(r["G3_poles"], 4))
    print(f"G3 delay margin (exact crossing): {r['G3_delay_margin']:.4f} s")
    print(f"G5 (Taylor, 0.2 s) stable for true delays in ({r['G5_interval'].lower:.3f}, "
          f"{r['G5_interval'].upper:.4f}) s")
    for m, (G, dm) in r["designs"].items():
        print(f"Q = diag(8825, 0, 0), tau = 0.2 s, {m:9s}: G = {np.round(G, 3)}, "
              f"delay margin {dm:.4f} s")
