"""Sea spectra and shaping filters (Huang 1992, eqs. (6.19)-(6.23))."""

from __future__ import annotations

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import sea
from cable_ocp.heave.stochastic import output_variance_lyapunov, output_variance_spectral


def test_bretschneider_m0_is_hs_squared_over_16() -> None:
    # Closed form of the omega_m^4 form of (6.20): m0 = Hs^2/16 exactly; quadrature to 1e-9.
    s = sea.SeaSpectrum("bretschneider", 3.048, 0.785)
    assert s.m0() == pytest.approx(3.048**2 / 16, rel=1e-9)


def test_bretschneider_peak_at_modal_frequency() -> None:
    # dS/dw = 0 at w = omega_m for the omega_m^4 form; grid spacing 1e-5 rad/s sets the tolerance.
    w = np.linspace(0.5, 1.2, 70001)
    s = sea.bretschneider(w, 3.0, 0.785)
    assert w[np.argmax(s)] == pytest.approx(0.785, abs=2e-5)


def test_pm_modal_frequency_from_tz_6_2_6() -> None:
    # Example 6.2.6: Tz = 14 s; (16 pi^3 / 1.25)^(1/4) / 14 = 0.31880 (docs/conventions.md: ~0.319).
    assert sea.modal_frequency_from_zero_crossing(14.0) == pytest.approx(0.3188, abs=1e-4)


def test_jonswap_gamma_one_is_bretschneider() -> None:
    w = np.linspace(0.1, 3, 50)
    np.testing.assert_allclose(sea.jonswap(w, 2.0, 0.7, 1.0), sea.bretschneider(w, 2.0, 0.7),
                               rtol=1e-14)


def test_thesis_filter_matches_6_21_closed_form() -> None:
    # |H(iw)|^2 of the state space (6.23) equals S0 r^4/(1+r^4)^3 (6.21) since 1.414^2 ~ 2;
    # 1.414 instead of sqrt(2) leaves a relative difference below 1e-3 at every frequency.
    hs, wm = 3.048, 0.785
    f = sea.thesis_shaping_filter(hs, wm)
    w = np.linspace(0.05, 4, 200)
    s0 = 1.25 / (4 * wm) * hs**2 * 1.8861
    r = w / (0.9538 * wm)
    np.testing.assert_allclose(sea.filter_spectrum(f, w), s0 * r**4 / (1 + r**4) ** 3, rtol=1e-3)


def test_filter_variance_lyapunov_equals_spectral() -> None:
    # pi*C P C^T and the one-sided integral of |H|^2 are the same number (closed form vs
    # quadrature); relative 1e-8 covers the quadrature tolerance.
    f = sea.thesis_shaping_filter(3.048, 0.785)
    v1 = output_variance_lyapunov(f.A, f.B, f.C)
    v2 = output_variance_spectral(f.A, f.B, f.C)
    assert v2 == pytest.approx(v1, rel=1e-8)


def test_fit_improves_on_thesis_filter() -> None:
    # The thesis says "further improvement is needed here" (6.3.6): a 3-section least-squares
    # fit must beat (6.22) in both spectral and variance error; errors are in [0, 1).
    spec = sea.SeaSpectrum("bretschneider", 3.048, 0.785)
    th = sea.thesis_fit(spec)
    fit = sea.fit_shaping_filter(spec, 3)
    assert fit.spectral_error < 0.5 * th.spectral_error
    assert abs(fit.variance_error) < abs(th.variance_error)
    # Errors shrink with order (more sections, more freedom) on this spectrum.
    f4 = sea.fit_shaping_filter(spec, 4)
    assert f4.spectral_error < fit.spectral_error


def test_invalid_filter_order_raises() -> None:
    with pytest.raises(CableOCPError, match="filter_order"):
        sea.fit_shaping_filter(sea.SeaSpectrum("jonswap", 2, 0.7), 9)
