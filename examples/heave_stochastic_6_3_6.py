"""Reproduce Huang (1992), section 6.3.6: sigma 0.255 m, 2.96e-4 m, Fig. 6.21, Fig. 6.25.

Prints the uncontrolled and controlled standard deviations of the unit's heave in sea state 5
(thesis: 0.255 m and 2.96e-4 m), the least weight that reaches a 99 % reduction, the quality
of the shaping filters, and the winch-gain study; draws the spectrum with its shaping
filters (cf. Fig. 6.21) and the control energy against the winch gain (cf. Fig. 6.25).

Run:  python examples/heave_stochastic_6_3_6.py [--out heave_stochastic_6_3_6.png]
      [--gains 0.25 0.5 1 2 4 8]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from cable_ocp.heave import plant as pl
from cable_ocp.heave import sea
from cable_ocp.heave import stochastic as st
from cable_ocp.heave.thesis import A_636, B_636, HS_636, KV_636, WM_636, WV_636, ZETA_V_636

Q_636 = 553.6  # 1/m^2: a calibration, fitted so that the LQR gives SIGMA_636 (no weights in 6.3.6)
SIGMA_636 = 2.96e-4  # m, the controlled sigma of Huang (1992), section 6.3.6 (Fig. 6.24)


def build(K: float = 1.0, filt: str = "thesis", order: int = 3) -> pl.HeavePlant:  # noqa: N803
    """The 11-state plant (6.28) for winch gain K."""
    spec = sea.SeaSpectrum("bretschneider", HS_636, WM_636)
    f = sea.make_shaping_filter(spec, filt, order).filter
    return pl.assemble_plant(A_636, B_636, pl.winch_first(K),
                             vessel=pl.vessel_block(WV_636, ZETA_V_636, KV_636), sea=f)


def compute(K_values: tuple = (0.25, 0.5, 1, 2, 4, 8)) -> dict:  # noqa: N803
    """Every number and curve of the example (``K_values``: winch gains, 1/s)."""
    p = build()
    cx = p.e("x")
    res = {"sigma_uncontrolled": np.sqrt(st.output_variance_lyapunov(p.A, p.B2, cx)),
           "sigma_uncontrolled_spectral": np.sqrt(st.output_variance_spectral(p.A, p.B2, cx))}
    d = st.stochastic_lqr(p.A, p.B1, p.B2, cx, Q_636)
    res["lqr"] = d
    res["q_99pct"] = st.weight_for_sigma(p.A, p.B1, p.B2, cx, 0.01 * d.sigma_uncontrolled)
    spec = sea.SeaSpectrum("bretschneider", HS_636, WM_636)
    res["spectrum"] = spec
    res["fits"] = {"thesis": sea.thesis_fit(spec)}
    for n in (2, 3, 4):
        res["fits"][f"fit{n}"] = sea.fit_shaping_filter(spec, n)
    pb = {}
    for name, fit in res["fits"].items():
        pp = pl.assemble_plant(A_636, B_636, pl.winch_first(1.0),
                               vessel=pl.vessel_block(WV_636, ZETA_V_636, KV_636), sea=fit.filter)
        pb[name] = np.sqrt(st.output_variance_lyapunov(pp.A, pp.B2, pp.e("x")))
    res["sigma_by_filter"] = pb
    res["winch_study"] = st.winch_gain_study(build, K_values, SIGMA_636)
    return res


def report(res: dict) -> str:
    """The printed results, one per line."""
    d = res["lqr"]
    lines = [f"sigma uncontrolled: Lyapunov {res['sigma_uncontrolled']:.6f} m, spectral "
             f"{res['sigma_uncontrolled_spectral']:.6f} m (thesis 0.255)",
             f"LQR q = {Q_636}, r = 1: sigma = {d.sigma:.4e} m (thesis 2.96e-4), reduction "
             f"{d.reduction_pct:.2f} %, energy index {d.energy_index:.3f}",
             f"least q reaching 99 %: {res['q_99pct']:.2f}"]
    for name, fit in res["fits"].items():
        lines.append(f"filter {name:7s}: spectral error {fit.spectral_error:.4f}, variance "
                     f"error {100 * fit.variance_error:+.3f} %, sigma_unit "
                     f"{res['sigma_by_filter'][name]:.4f} m")
    for K, q, e in res["winch_study"]:
        lines.append(f"K = {K:5.2f} 1/s: q = {q:10.2f}, energy index {e:8.3f}")
    return "\n".join(lines)


def plot(res: dict, path: str | Path) -> Path:
    """Spectrum and shaping filters (cf. Fig. 6.21), energy against winch gain (cf.
    Fig. 6.25), to ``path`` (format by suffix)."""
    from cable_ocp.plots.common import legend_below, new_figure, save

    fig = new_figure(11.5, 5.6)
    ax = fig.subplots(1, 2)
    spec = res["spectrum"]
    w = np.linspace(0.05, 3.5, 500)
    handles = ax[0].plot(w, spec(w), "k", lw=2.0, zorder=5,
                         label=f"Bretschneider spectrum (6.20), Hs = {spec.hs:g} m, "
                               f"omega_m = {spec.omega_m:g} rad/s")
    names = {"thesis": "thesis filter (6.21)-(6.23)", "fit2": "least-squares fit, order 2",
             "fit3": "least-squares fit, order 3", "fit4": "least-squares fit, order 4"}
    for k, (name, fit) in enumerate(res["fits"].items()):
        handles += ax[0].plot(w, sea.filter_spectrum(fit.filter, w), lw=1.3,
                              ls="--" if name == "thesis" else "-", color=f"C{k}",
                              label=f"{names.get(name, name)}: spectral error "
                                    f"{fit.spectral_error:.3f}, variance "
                                    f"{100 * fit.variance_error:+.1f} %")
    ax[0].set(xlabel="wave frequency omega (rad/s)",
              ylabel="spectral density S (m² s/rad)")
    ax[0].set_xlim(0.0, float(w[-1]))
    ax[0].set_ylim(bottom=0.0)
    ax[0].set_title("Sea spectrum and its shaping filters\n(cf. Huang 1992, Fig. 6.21)",
                    fontsize=10)
    ws = np.array(res["winch_study"])
    handles += ax[1].plot(ws[:, 0], ws[:, 2], "o-", color="C4",
                          label=f"LQR weighted for sigma = {SIGMA_636:g} m")
    ax[1].set_xscale("log")
    ax[1].set(xlabel="winch gain K (1/s)", ylabel="energy index sqrt(sum G_i²) (-)")
    ax[1].set_title(f"Control energy against winch gain at a unit heave sigma of "
                    f"{SIGMA_636:g} m\n(cf. Huang 1992, Fig. 6.25)", fontsize=10)
    ax[1].set_xticks(ws[:, 0], [f"{k:g}" for k in ws[:, 0]])
    ax[1].minorticks_off()
    for a in ax:
        a.grid(True, alpha=0.3)
    fig.suptitle("Huang 1992, section 6.3.6: stochastic heave compensation in sea state 5",
                 fontsize=11)
    legend_below(fig, handles, ncols=2)
    path = Path(path)
    save(fig, path)
    return path


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(
        description="Reproduce Huang (1992), section 6.3.6: the unit's heave sigma without "
                    "and with LQR control (thesis 0.255 m and 2.96e-4 m), the shaping "
                    "filters' quality (Fig. 6.21) and the winch-gain study (Fig. 6.25, "
                    "written as a figure).")
    ap.add_argument("--out", default="heave_stochastic_6_3_6.png", metavar="PATH",
                    help="figure file; PNG, PDF or SVG by its suffix (default %(default)s)")
    ap.add_argument("--gains", type=float, nargs="+", default=[0.25, 0.5, 1, 2, 4, 8],
                    metavar="K", help="winch gains K of the study, 1/s (default 0.25 0.5 1 "
                                      "2 4 8)")
    args = ap.parse_args(argv)
    if min(args.gains) <= 0:
        ap.error(f"--gains {args.gains}: every gain must be > 0 (1/s)")
    res = compute(tuple(args.gains))
    print(report(res))
    plot(res, args.out)
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
