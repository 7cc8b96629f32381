"""Gauss quadrature rules: Gauss-Legendre and Gauss-Radau points and weights.

One home for the package's Gauss rules (the statics collocation, the FEM baseline's element
integrals; the dynamics models' 3-point mean of the tension is the rule of
``gauss_legendre(3)`` with halved weights):

* :func:`gauss_legendre`: n points, exact for polynomials of degree 2n - 1, on [-1, 1] or
  any interval. n = 1, 2, 3 in closed form (0; +-1/sqrt(3); 0, +-sqrt(3/5) with weights 2;
  1, 1; 5/9, 8/9, 5/9), n >= 4 from :func:`numpy.polynomial.legendre.leggauss`
  (Golub-Welsch, Newton-polished).
* :func:`gauss_radau`: the right Radau rule, n points including the interval's end b, exact
  for degree 2n - 2 (the collocation points of Radau IIA). Points from CasADi's tables
  (n = 1..9); weights w_n = 2/n^2 and w_i = (1 + x_i) / (n^2 P_{n-1}(x_i)^2) on [-1, 1]
  (Abramowitz and Stegun 25.4.31, mirrored to include +1).
* :func:`collocation_points`: the points of a collocation polynomial of degree d on
  [0, 1], Gauss-Legendre or Radau, as CasADi tabulates them (``casadi.collocation_points``;
  the statics transcription uses these, and its JSON depends on their last bits). They
  agree with ``gauss_legendre(d, (0, 1))`` and ``gauss_radau(d)`` to a few units of
  rounding (4.4e-16 at most for d <= 9; equal for d <= 2).

Nothing here knows about cables.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

__all__ = ["collocation_points", "gauss_legendre", "gauss_radau"]

#: the schemes of :func:`collocation_points`
SCHEMES = ("legendre", "radau")
#: the highest degree CasADi tabulates
MAX_DEGREE = 9


def collocation_points(degree: int, scheme: str) -> tuple[float, ...]:
    """Collocation points on [0, 1], CasADi's tables (``casadi.collocation_points``).

    Parameters
    ----------
    degree : int
        Degree d of the collocation polynomial, 1..9 (d points).
    scheme : {"legendre", "radau"}
        Gauss-Legendre (interior points, order 2d at the interval ends) or right
        Gauss-Radau (the last point is 1, order 2d - 1).

    Returns
    -------
    tuple of float
        The d points, increasing.
    """
    if scheme not in SCHEMES:
        raise ValueError(f"scheme = {scheme!r}: valid are {', '.join(SCHEMES)}")
    if not 1 <= degree <= MAX_DEGREE:
        raise ValueError(f"degree = {degree}: CasADi tabulates 1..{MAX_DEGREE}")
    return tuple(float(t) for t in ca.collocation_points(degree, scheme))


def _mapped(x: np.ndarray, w: np.ndarray, interval: tuple[float, float]
            ) -> tuple[np.ndarray, np.ndarray]:
    """A rule on [-1, 1] moved to ``interval`` (unchanged for (-1, 1))."""
    a, b = interval
    if (a, b) == (-1.0, 1.0):
        return x, w
    return 0.5 * (b - a) * (x + 1.0) + a, 0.5 * (b - a) * w


def gauss_legendre(n: int, interval: tuple[float, float] = (-1.0, 1.0)
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre points and weights: exact for polynomials of degree 2n - 1.

    Parameters
    ----------
    n : int
        Number of points, >= 1.
    interval : (float, float)
        The interval (a, b); the rule on [-1, 1] is mapped affinely, x -> (b - a)/2
        (x + 1) + a, w -> (b - a)/2 w.

    Returns
    -------
    points, weights : ndarray, shape (n,)
        Points increasing; the weights sum to b - a.
    """
    if n < 1:
        raise ValueError(f"n = {n}: a Gauss rule needs at least one point")
    if n == 1:
        x, w = np.array([0.0]), np.array([2.0])
    elif n == 2:
        r = 1.0 / math.sqrt(3.0)
        x, w = np.array([-r, r]), np.array([1.0, 1.0])
    elif n == 3:
        r = math.sqrt(0.6)
        x, w = np.array([-r, 0.0, r]), np.array([5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0])
    else:
        x, w = np.polynomial.legendre.leggauss(n)
    return _mapped(x, w, interval)


def gauss_radau(n: int, interval: tuple[float, float] = (0.0, 1.0)
                ) -> tuple[np.ndarray, np.ndarray]:
    """Right Gauss-Radau points and weights (the last point is the interval's end b):
    exact for polynomials of degree 2n - 2.

    Parameters
    ----------
    n : int
        Number of points, 1..9 (CasADi's tables).
    interval : (float, float)
        The interval (a, b); the points on [0, 1] are mapped affinely, t -> a + (b - a) t.

    Returns
    -------
    points, weights : ndarray, shape (n,)
        Points increasing, the last one b; the weights sum to b - a.
    """
    tau = np.array(collocation_points(n, "radau"))
    x = 2.0 * tau - 1.0  # on [-1, 1], the last point +1
    p = np.polynomial.legendre.legval(x[:-1], [0.0] * (n - 1) + [1.0])  # P_{n-1}(x_i)
    w = np.empty(n)
    w[:-1] = (1.0 + x[:-1]) / (n * n * p * p)
    w[-1] = 2.0 / (n * n)
    a, b = interval
    if (a, b) == (0.0, 1.0):
        return tau, 0.5 * w
    return a + (b - a) * tau, 0.5 * (b - a) * w
