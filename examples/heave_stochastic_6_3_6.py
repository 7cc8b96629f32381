"""Reproduce 004 section 6.3.6: sigma 0.255 m, 2.96e-4 m, Fig. 6.21 fit, Fig. 6.25 study.

Run ``python examples/heave_stochastic_6_3_6.py [OUT.png]``.
"""

from __future__ import annotations

import sys

import numpy as np

from cable_ocp.heave import plant as pl
from cable_ocp.heave import sea
from cable_ocp.heave import stochastic as st
from cable_ocp.heave.thesis import A_636, B_636, HS_636, KV_636, WM_636, WV_636, ZETA_V_636

Q_636 = 553.6


def build(K: float = 1.0, filt: str = "thesis", order: int = 3) -> pl.HeavePlant:
    """The 11-state plant (6.28) for winch gain K."""
    spec = sea.SeaSpectrum("bretschneider", HS_636, WM_636)
    f = sea.make_shaping_filter(spec, filt, order).filter
    return pl.assemble_plant(A_636, B_636, pl.winch_first(K),
                             vessel=pl.vessel_block(WV_636, ZETA_V_636, KV_636), sea=f)


def main(out: str | None = None, K_values: tuple = (0.25, 0.5, 1, 2, 4, 8)) -> dict:
    """Compute the 6.3.6 numbers; save Fig. 6.21/6.25-like panels if ``out``."""
    p = build()
    cx = p.e("x")
    res = {"sigma_uncontrolled": np.sqrt(st.output_variance_lyapunov(p.A, p.B2, cx)),
           "sigma_uncontrolled_spectral": np.sqrt(st.output_variance_spectral(p.A, p.B2, cx))}
    d = st.stochastic_lqr(p.A, p.B1, p.B2, cx, Q_636)
    res["lqr"] = d
    res["q_99pct"] = st.weight_for_sigma(p.A, p.B1, p.B2, cx, 0.01 * d.sigma_uncontrolled)
    spec = sea.SeaSpectrum("bretschneider", HS_636, WM_636)
    res["fits"] = {"thesis": sea.thesis_fit(spec)}
    for n in (2, 3, 4):
        res["fits"][f"fit{n}"] = sea.fit_shaping_filter(spec, n)
    pb = {}
    for name, fit in res["fits"].items():
        pp = pl.assemble_plant(A_636, B_636, pl.winch_first(1.0),
                               vessel=pl.vessel_block(WV_636, ZETA_V_636, KV_636), sea=fit.filter)
        pb[name] = np.sqrt(st.output_variance_lyapunov(pp.A, pp.B2, pp.e("x")))
    res["sigma_by_filter"] = pb
    res["winch_study"] = st.winch_gain_study(build, K_values, 2.96e-4)
    if out:
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        w = np.linspace(0.05, 3.5, 500)
        ax[0].plot(w, spec(w), "k", label="Bretschneider (6.20)")
        for name, fit in res["fits"].items():
            ax[0].plot(w, sea.filter_spectrum(fit.filter, w),
                       label=f"{name}: L2 {fit.spectral_error:.3f}, var {fit.variance_error:+.3f}")
        ax[0].set(xlabel="omega (rad/s)", ylabel="S (m^2 s/rad)", title="Fig. 6.21")
        ax[0].legend(fontsize=7)
        ws = np.array(res["winch_study"])
        ax[1].plot(ws[:, 0], ws[:, 2], "o-")
        ax[1].set(xlabel="K (1/s)", ylabel="energy index sqrt(sum G^2)",
                  title="Fig. 6.25 (sigma = 2.96e-4 m)")
        fig.tight_layout()
        fig.savefig(out, dpi=110)
        plt.close(fig)
    return res


if __name__ == "__main__":
    r = main(sys.argv[1] if len(sys.argv) > 1 else None)
    print(f"sigma uncontrolled: Lyapunov {r['sigma_uncontrolled']:.6f} m, spectral "
          f"{r['sigma_uncontrolled_spectral']:.6f} m (thesis 0.255)")
    d = r["lqr"]
    print(f"LQR q = {Q_636}, r = 1: sigma = {d.sigma:.4e} m (thesis 2.96e-4), reduction "
          f"{d.reduction_pct:.2f} %, energy index {d.energy_index:.3f}")
    print(f"least q reaching 99 %: {r['q_99pct']:.2f}")
    for name, fit in r["fits"].items():
        print(f"filter {name:7s}: spectral error {fit.spectral_error:.4f}, variance error "
              f"{100 * fit.variance_error:+.3f} %, sigma_unit {r['sigma_by_filter'][name]:.4f} m")
    for K, q, e in r["winch_study"]:
        print(f"K = {K:5.2f} 1/s: q = {q:10.2f}, energy index {e:8.3f}")
