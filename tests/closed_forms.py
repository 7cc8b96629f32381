"""Closed forms for the dynamics tests, written independently of the package.

``hanging_cable_frequencies``: the transverse natural frequencies of a cable hanging from a
fixed point with a tip mass (Bessel functions); tests/dynamics/test_lumped_modes.py checks
it against the hanging-chain and pendulum limits before the models are held to it.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import j0, j1, y0, y1


def hanging_cable_frequencies(length: float, w: float, mu_t: float, tip_weight: float,
                              tip_mass: float, count: int) -> np.ndarray:
    """First ``count`` transverse natural frequencies (rad/s) of a cable hanging from a
    fixed point with a tip mass, written independently of the code under test.

    mu_t y_tt = (T y_s)_s, T(s) = W + w s (s up from the tip), y(L) = 0 and
    M_t y_tt(0) = W y_s(0). With xi = s + W / w and kappa^2 = mu_t omega^2 / w the mode is
    Y = A J0(2 kappa sqrt(xi)) + B Y0(2 kappa sqrt(xi)); the two end conditions give a
    2x2 determinant whose roots are the frequencies.
    """
    a = tip_weight / w

    def det(om: float) -> float:
        k = om * math.sqrt(mu_t / w)
        za = 2.0 * k * math.sqrt(a)
        zl = 2.0 * k * math.sqrt(length + a)
        c1 = tip_mass * om**2 * j0(za) - w * k * math.sqrt(a) * j1(za)
        c2 = tip_mass * om**2 * y0(za) - w * k * math.sqrt(a) * y1(za)
        return c1 * y0(zl) - c2 * j0(zl)

    wmax = 4.0 * count * math.sqrt(w / (mu_t * length)) + 2.0 * math.sqrt(
        tip_weight / (tip_mass * length) if tip_mass > 0 else 0.0)
    grid = np.linspace(1e-6 * wmax, wmax, 40001)
    vals = np.array([det(g) for g in grid])
    roots = []
    for i in np.flatnonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0):
        roots.append(brentq(det, grid[i], grid[i + 1], xtol=1e-15, rtol=1e-14))
        if len(roots) == count:
            break
    assert len(roots) == count
    return np.array(roots)
