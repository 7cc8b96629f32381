"""The Gauss rules (cable_ocp.numerics.quadrature).

What is checked, and why each tolerance:

* Exactness: Gauss-Legendre with n points integrates x^k exactly for k <= 2n - 1, and the
  error of x^2n is Gauss' error constant; right Radau is exact for k <= 2n - 2 (its last
  point is the interval's end) and the error of x^(2n-1) is Radau's constant; on [-1, 1],
  [0, 1] and an arbitrary interval. The integrals are sums of O(1) terms, so 1e-13
  relative covers their rounding; the error constants to 1e-6 plus that rounding (where
  the error falls to rounding, as for n = 12 on [0, 1], the rounding term decides).
* The points the JSON depends on, bitwise: the collocation points are CasADi's tables, the
  FEM baseline's [0, 1] rule is numpy's leggauss mapped as it was, and the closed 3-point
  rule is the one the dynamics models write by hand (sqrt(0.6), 5/18, 8/18 after halving).
* The two sources of Legendre points agree to rounding (measured 4.4e-16 at most, bound
  1e-15) and so do CasADi's Radau points and the Radau rule's.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

from cable_ocp.numerics.quadrature import collocation_points, gauss_legendre, gauss_radau

INTERVALS = [(-1.0, 1.0), (0.0, 1.0), (-0.3, 2.2)]


def _moment(k: int, a: float, b: float) -> float:
    return (b ** (k + 1) - a ** (k + 1)) / (k + 1)


@pytest.mark.parametrize("interval", INTERVALS)
@pytest.mark.parametrize("n", range(1, 13))
def test_gauss_legendre_exact_to_degree_2n_minus_1(n: int, interval: tuple) -> None:
    a, b = interval
    x, w = gauss_legendre(n, interval)
    assert x.shape == w.shape == (n,) and np.all(np.diff(x) > 0) and a < x[0] and x[-1] < b
    for k in range(2 * n):
        assert np.sum(w * x**k) == pytest.approx(_moment(k, a, b), rel=1e-13, abs=1e-13)
    # the first inexact power: the error is Gauss' constant (b - a)^(2n+1) (n!)^4 /
    # ((2n + 1) ((2n)!)^2) (f^(2n) = (2n)! for x^2n)
    exact = _moment(2 * n, a, b)
    err = (b - a) ** (2 * n + 1) * math.factorial(n) ** 4 / (
        (2 * n + 1) * math.factorial(2 * n) ** 2)
    assert abs(exact - np.sum(w * x ** (2 * n)) - err) <= 1e-6 * err + 1e-13 * abs(exact)


@pytest.mark.parametrize("interval", INTERVALS)
@pytest.mark.parametrize("n", range(1, 10))
def test_gauss_radau_exact_to_degree_2n_minus_2(n: int, interval: tuple) -> None:
    a, b = interval
    x, w = gauss_radau(n, interval)
    assert x.shape == w.shape == (n,) and np.all(np.diff(x) > 0) and a < x[0]
    assert x[-1] == pytest.approx(b, abs=1e-15)
    for k in range(2 * n - 1):
        assert np.sum(w * x**k) == pytest.approx(_moment(k, a, b), rel=1e-13, abs=1e-13)
    # the first inexact power: the error is Radau's constant (Abramowitz and Stegun
    # 25.4.31) 2^(2n-1) n ((n-1)!)^4 / ((2n-1)!)^2 ((b - a)/2)^2n, with the sign of a
    # rule that includes its right end
    exact = _moment(2 * n - 1, a, b)
    err = -2 ** (2 * n - 1) * n * math.factorial(n - 1) ** 4 / math.factorial(
        2 * n - 1) ** 2 * ((b - a) / 2) ** (2 * n)
    assert abs(exact - np.sum(w * x ** (2 * n - 1)) - err) \
        <= 1e-6 * abs(err) + 1e-13 * abs(exact)


@pytest.mark.parametrize("degree", range(1, 10))
def test_collocation_points_are_casadis_and_the_rules_points(degree: int) -> None:
    for scheme in ("legendre", "radau"):
        tau = collocation_points(degree, scheme)
        assert tau == tuple(float(t) for t in ca.collocation_points(degree, scheme))
    legendre = np.asarray(collocation_points(degree, "legendre"))
    assert np.max(np.abs(legendre - gauss_legendre(degree, (0.0, 1.0))[0])) <= 1e-15
    radau = np.asarray(collocation_points(degree, "radau"))
    assert np.array_equal(radau, gauss_radau(degree)[0])


def test_the_rules_the_json_depends_on_are_bitwise_unchanged() -> None:
    """The FEM baseline's 4-point rule on [0, 1] is numpy's leggauss mapped as before;
    the closed 3-point rule halved is the dynamics models' hand-written mean rule."""
    x, w = np.polynomial.legendre.leggauss(4)
    x01, w01 = gauss_legendre(4, (0.0, 1.0))
    assert np.array_equal(x01, 0.5 * (x + 1.0)) and np.array_equal(w01, 0.5 * w)
    x3, w3 = gauss_legendre(3)
    assert tuple(x3) == (-math.sqrt(0.6), 0.0, math.sqrt(0.6))
    assert tuple(0.5 * w3) == (5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0)


def test_bad_arguments_raise() -> None:
    with pytest.raises(ValueError, match="at least one point"):
        gauss_legendre(0)
    with pytest.raises(ValueError, match="1..9"):
        gauss_radau(10)
    with pytest.raises(ValueError, match="scheme"):
        collocation_points(3, "lobatto")
