"""Plant blocks and the assembled 11-state plant (Huang 1992, eqs. (6.1)-(6.28))."""

from __future__ import annotations

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import plant as pl
from cable_ocp.heave import sea
from cable_ocp.heave.thesis import A_636, B_636, HS_636, WM_636


def _resp(sys, s: complex) -> complex:
    """First output / first input of a frequency response (SISO systems return scalars)."""
    return complex(np.asarray(sys(s)).reshape(-1)[0])


def test_assembled_plant_equals_6_28_typed_by_hand(plant_636: pl.HeavePlant) -> None:
    # The block assembly must reproduce the block matrix printed in (6.28) exactly (pure
    # bookkeeping: 1e-14).
    a, b, K, wv, xv, kv = A_636, B_636, 1.0, 0.393, 0.6, 0.5
    w0 = 0.9538 * WM_636
    s0 = 1.25 / (4 * WM_636) * HS_636**2 * 1.8861
    Am = np.array([[0, 1, 0], [-1 / a, -b / a, 1 / a], [0, 0, -K]])
    Bm2 = np.array([[0], [1 / a], [0]])
    Ab = np.array([[0, 1], [-wv**2, -2 * xv * wv]])
    Bb = np.array([[0], [1]])
    Cb = np.array([[kv * wv**2, 0]])
    As = np.zeros((6, 6))
    for i in range(3):
        As[2 * i, 2 * i + 1] = 1
        As[2 * i + 1, 2 * i] = -(w0**2)
        As[2 * i + 1, 2 * i + 1] = -1.414 * w0
        if i < 2:
            As[2 * i + 1, 2 * i + 3] = w0**2
    Cs = np.zeros((1, 6))
    Cs[0, 0] = np.sqrt(s0)
    A = np.zeros((11, 11))
    A[:3, :3] = Am
    A[:3, 3:5] = Bm2 @ Cb
    A[3:5, 3:5] = Ab
    A[3:5, 5:] = Bb @ Cs
    A[5:, 5:] = As
    np.testing.assert_allclose(plant_636.A, A, atol=1e-14)
    B1 = np.zeros((11, 1))
    B1[2] = K
    B2 = np.zeros((11, 1))
    B2[10] = 1
    np.testing.assert_allclose(plant_636.B1, B1, atol=1e-14)
    np.testing.assert_allclose(plant_636.B2, B2, atol=1e-14)
    np.testing.assert_allclose(plant_636.e("x"), np.eye(11)[:1], atol=0)


def test_first_order_winch_sinusoid_6_1() -> None:
    # Huang (1992) section 6.2.2: |u/u0| = 1/sqrt(w^2/K^2 + 1), phase -atan(w/K).
    K, w = 1.5, 0.8
    g = _resp(pl.winch_first(K), 1j * w)
    assert abs(g) == pytest.approx(1 / np.sqrt(w**2 / K**2 + 1), rel=1e-12)
    assert np.angle(g) == pytest.approx(-np.arctan(w / K), rel=1e-12)


def test_taylor_delay_matches_exact_at_low_frequency() -> None:
    # (6.13) is 1/(1 + tau s + tau^2 s^2/2): the error to e^{-i w tau} is O((w tau)^3);
    # bound |err| <= (w tau)^3 (the leading term is (w tau)^3/6 plus higher orders).
    tau = 0.2
    blk = pl.delay_block("taylor", tau)
    for w in [0.01, 0.1, 0.5, 1.0]:
        g = _resp(blk, 1j * w)
        err = abs(g - np.exp(-1j * w * tau))
        assert err <= (w * tau) ** 3
    # ... and the error grows as (w tau)^3: ratio of errors at w and 10 w is ~1000 (+-5 %).
    e1 = abs(_resp(blk, 1j * 0.01) - np.exp(-1j * 0.01 * tau))
    e2 = abs(_resp(blk, 1j * 0.1) - np.exp(-1j * 0.1 * tau))
    assert e2 / e1 == pytest.approx(1000, rel=0.05)


def test_pade_better_than_taylor_at_wave_frequencies() -> None:
    # A second-order Pade is exact in phase to O((w tau)^5); at 1 rad/s it must beat Taylor.
    tau, w = 0.2, 1.0
    ex = np.exp(-1j * w * tau)
    et = abs(_resp(pl.delay_block("taylor", tau), 1j * w) - ex)
    ep = abs(_resp(pl.delay_block("pade", tau, 2), 1j * w) - ex)
    assert ep < et / 10


def test_second_order_winch_low_frequency_lag_matches_first_order() -> None:
    # Chosen values obey 2 zeta/omega = 1/K (problem files): same phase slope at w -> 0.
    w = 1e-4
    g1 = _resp(pl.winch_first(1.0), 1j * w)
    g2 = _resp(pl.winch_second(1.4, 0.7), 1j * w)
    assert np.angle(g2) == pytest.approx(np.angle(g1), rel=1e-6)


def test_regulator_plant_6_6_and_stretch_output() -> None:
    p = pl.assemble_plant(7.339769, 0.1906759, pl.winch_first(1.0))
    a, b = 7.339769, 0.1906759
    np.testing.assert_allclose(p.A, [[0, 1, 0], [-1 / a, -b / a, 1 / a], [0, 0, -1]], atol=1e-15)
    c, d = p.output_row("stretch")
    np.testing.assert_allclose(c, [-1, 0, 1])
    np.testing.assert_allclose(d, [0, 1])


def test_bad_block_parameters_raise() -> None:
    with pytest.raises(CableOCPError, match="gain"):
        pl.winch_first(0.0)
    with pytest.raises(CableOCPError, match="a = "):
        pl.unit_block(-1.0, 0.1)
    with pytest.raises(CableOCPError, match="both"):
        pl.assemble_plant(1, 0.1, pl.winch_first(1), sea=sea.thesis_shaping_filter(1, 1))
