"""Axial tension of a cable element: the material law, in one place.

The law of every dynamic model (Huang (1992) (5.3): T = EA e, e = l_stretched / l - 1),
with two additions that the models share:

* **no compression** (a cable buckles rather than push): Hooke's tension is replaced by the
  smooth, convex, increasing

      T(e) = (EA e + sqrt((EA e)^2 + delta_T^2)) / 2,

  which is > 0 everywhere and tends to EA e when taut and to 0 when slack. Its bound:

      0 < T(e) - max(EA e, 0) <= delta_T / 2,   equality at e = 0

  (:func:`no_compression_bound`); the models use delta_T = 0.01 N. Its derivative is
  EA times the smooth switch

      s(e) = (1 + EA e / sqrt((EA e)^2 + delta_T^2)) / 2   in (0, 1)

  (:func:`taut_switch`: 1 taut, 0 slack);
* **material damping** c de/dt (c in N s), switched off with the tension when slack:
  c (de/dt) s(e) (:func:`material_damping`).

These functions take numbers (floats, numpy arrays or CasADi expressions) and no model
object. A material is an object with the :class:`AxialMaterial` interface;
:class:`LinearElastic` is the one the models use. A nonlinear material (a tension-strain
table, interpolated with the same no-compression switch) or a viscoelastic one (a
Kelvin-Voigt or standard-solid law whose internal strain is a state) is another class with
the same methods: a model that asks its material for ``tension``, ``stiffness`` and
``taut`` needs no change. Not implemented here.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

import casadi as ca
import numpy as np

#: force scale of the smooth no-compression law of the dynamic models, N
SLACK_SMOOTHING = 0.01


def _sqrt(x: Any) -> Any:
    if isinstance(x, (ca.SX, ca.MX, ca.DM)):
        return ca.sqrt(x)
    return np.sqrt(x)


def _asinh(x: Any) -> Any:
    if isinstance(x, (ca.SX, ca.MX, ca.DM)):
        return ca.asinh(x)
    return np.arcsinh(x)


def hooke_tension(strain: Any, axial_stiffness: Any) -> Any:
    """Linear tension EA e, N (negative in compression).

    Parameters
    ----------
    strain : float, array or casadi expression
        Axial strain e (-).
    axial_stiffness : float
        EA, N.
    """
    return axial_stiffness * strain


def kelvin_voigt_tension(strain: Any, strain_rate: Any, axial_stiffness: Any,
                         damping: Any) -> Any:
    """EA e + c de/dt, N: the linear law without the no-compression switch.

    The axial models use it as printed in Huang (1992) (3.2)-(3.3) and report a slack
    element (a tension <= 0) instead of smoothing it away.

    Parameters
    ----------
    strain : float, array or casadi expression
        Axial strain e (-).
    strain_rate : float, array or casadi expression
        de/dt, 1/s.
    axial_stiffness : float
        EA, N.
    damping : float
        c, N s.
    """
    return axial_stiffness * strain + damping * strain_rate


def smooth_tension(strain: Any, axial_stiffness: Any, slack_smoothing: Any) -> Any:
    """Smooth no-compression tension (EA e + sqrt((EA e)^2 + delta_T^2)) / 2, N.

    Parameters
    ----------
    strain : float, array or casadi expression
        Axial strain e (-).
    axial_stiffness : float
        EA, N.
    slack_smoothing : float
        delta_T, N (> 0): the bound of :func:`no_compression_bound` is delta_T / 2.
    """
    u = axial_stiffness * strain
    return 0.5 * (u + _sqrt(u * u + slack_smoothing * slack_smoothing))


def taut_switch(strain: Any, axial_stiffness: Any, slack_smoothing: Any) -> Any:
    """Smooth switch s(e) = (1 + EA e / sqrt((EA e)^2 + delta_T^2)) / 2, 0 slack .. 1 taut.

    dT/de of :func:`smooth_tension` is EA s(e).

    Parameters
    ----------
    strain : float, array or casadi expression
        Axial strain e (-).
    axial_stiffness : float
        EA, N.
    slack_smoothing : float
        delta_T, N.
    """
    u = axial_stiffness * strain
    return 0.5 * (1.0 + u / _sqrt(u * u + slack_smoothing * slack_smoothing))


def material_damping(strain_rate: Any, strain: Any, damping: Any, axial_stiffness: Any,
                     slack_smoothing: Any) -> Any:
    """Damping tension c (de/dt) s(e), N: off with the tension when slack.

    Parameters
    ----------
    strain_rate : float, array or casadi expression
        de/dt, 1/s.
    strain : float, array or casadi expression
        The strain at which the switch is taken (-).
    damping : float
        c, N s.
    axial_stiffness : float
        EA, N.
    slack_smoothing : float
        delta_T, N.
    """
    return damping * strain_rate * taut_switch(strain, axial_stiffness, slack_smoothing)


def smooth_strain_energy(strain: Any, axial_stiffness: Any, slack_smoothing: Any) -> Any:
    """Stored energy per unstretched length of :func:`smooth_tension`, J/m.

    The integral of T over [0, e]: with x = EA e and d = delta_T,
    EA e^2 / 4 + (x sqrt(x^2 + d^2) + d^2 asinh(x / d)) / (4 EA) (0 at e = 0; its
    derivative in e is the tension).

    Parameters
    ----------
    strain : float, array or casadi expression
        Axial strain e (-).
    axial_stiffness : float
        EA, N.
    slack_smoothing : float
        delta_T, N.
    """
    u = axial_stiffness * strain
    dd = slack_smoothing
    return (axial_stiffness * strain**2 / 4.0
            + (u * _sqrt(u * u + dd * dd) + dd * dd * _asinh(u / dd)) / (4.0 * axial_stiffness))


def no_compression_bound(slack_smoothing: float) -> float:
    """sup_e (smooth_tension(e) - max(EA e, 0)) = delta_T / 2, N (attained at e = 0).

    With x = EA e: (x + sqrt(x^2 + d^2)) / 2 - max(x, 0) = (sqrt(x^2 + d^2) - |x|) / 2
    = d^2 / (2 (sqrt(x^2 + d^2) + |x|)), largest (d / 2) at x = 0, decreasing in |x|.

    Parameters
    ----------
    slack_smoothing : float
        delta_T, N.
    """
    return 0.5 * slack_smoothing


class AxialMaterial(Protocol):
    """The interface a model asks of a cable material (per element).

    ``tension(strain, strain_rate)`` (N), ``stiffness(strain)`` = dT/de (N) at zero strain
    rate, ``taut(strain)`` in [0, 1] (the share of the tension law in force: 0 slack),
    ``energy(strain)`` (J/m, for energy checks) and ``bound`` (N): how far ``tension`` may
    lie above the material's non-smooth law.
    """

    @property
    def bound(self) -> float:
        """Smoothing bound, N."""
        ...

    def tension(self, strain: Any, strain_rate: Any = None) -> Any:
        """Axial tension, N.

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain (-).
        strain_rate : float, array, casadi expression or None
            Strain rate, 1/s (None: no rate-dependent part).
        """
        ...

    def stiffness(self, strain: Any) -> Any:
        """dT/de, N."""
        ...

    def taut(self, strain: Any) -> Any:
        """0 (slack) .. 1 (taut), -."""
        ...

    def energy(self, strain: Any) -> Any:
        """Stored energy per unstretched length, J/m (0 at zero strain)."""
        ...


@dataclass(frozen=True)
class LinearElastic:
    """Linear EA with material damping and the smooth no-compression switch.

    Attributes
    ----------
    axial_stiffness : float
        EA, N.
    damping : float
        Material damping c, N s (tension c de/dt, 0 = none).
    slack_smoothing : float
        delta_T, N (default :data:`SLACK_SMOOTHING`).
    """

    axial_stiffness: float
    damping: float = 0.0
    slack_smoothing: float = SLACK_SMOOTHING

    @property
    def bound(self) -> float:
        """:func:`no_compression_bound`, N."""
        return no_compression_bound(self.slack_smoothing)

    def tension(self, strain: Any, strain_rate: Any = None) -> Any:
        """Smooth tension plus c (de/dt) s(e) when a strain rate is given, N.

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain (-).
        strain_rate : float, array, casadi expression or None
            Strain rate, 1/s (None: no damping term).
        """
        out = smooth_tension(strain, self.axial_stiffness, self.slack_smoothing)
        if strain_rate is not None and self.damping != 0.0:
            out = out + material_damping(strain_rate, strain, self.damping,
                                         self.axial_stiffness, self.slack_smoothing)
        return out

    def stiffness(self, strain: Any) -> Any:
        """EA s(e), N."""
        return self.axial_stiffness * self.taut(strain)

    def taut(self, strain: Any) -> Any:
        """:func:`taut_switch`."""
        return taut_switch(strain, self.axial_stiffness, self.slack_smoothing)

    def energy(self, strain: Any) -> Any:
        """:func:`smooth_strain_energy`, J/m."""
        return smooth_strain_energy(strain, self.axial_stiffness, self.slack_smoothing)


def _if_else(cond: Any, a: Any, b: Any) -> Any:
    if any(isinstance(v, (ca.SX, ca.MX)) for v in (cond, a, b)):
        return ca.if_else(cond, a, b)
    return np.where(cond, a, b)


#: relative width of a strain interval below which :func:`mean_smooth_tension` uses its
#: series (|x1 - x0| <= MEAN_SERIES_WIDTH sqrt(x_m^2 + delta_T^2), x = EA e)
MEAN_SERIES_WIDTH = 1e-3


def mean_smooth_tension(strain0: Any, strain1: Any, axial_stiffness: Any,
                        slack_smoothing: Any) -> Any:
    """Exact mean of :func:`smooth_tension` over the strain interval [e0, e1], N.

    The discrete-gradient tension of the energy-momentum step (Gonzalez (1996)):
    (W(e1) - W(e0)) / (e1 - e0) with W the strain energy (:func:`smooth_strain_energy`,
    the antiderivative of the law). With x = EA e, d = delta_T and S(x) = sqrt(x^2 + d^2)
    the mean is (x_0 + x_1) / 4 + (F(x_1) - F(x_0)) / (2 (x_1 - x_0)),
    F(x) = (x S(x) + d^2 asinh(x / d)) / 2 the antiderivative of S; the part x S is
    differenced without cancellation as
    x_1 S_1 - x_0 S_0 = (x_1 - x_0) ((S_0 + S_1) / 2 + (x_0 + x_1)^2 / (2 (S_0 + S_1))).
    On an interval narrower than :data:`MEAN_SERIES_WIDTH` S(x_m) the mean of S is its
    series S(x_m) + S''(x_m) h^2 / 6 (h the half width, S'' = d^2 / S^3; the next term is
    of relative order (h / S)^4 <= 1e-12).

    Unlike a Gauss rule, this is exact across the kink of the no-compression law at
    e = 0 (a slack element going taut within the step, or the reverse), and C^1 in e1.

    Parameters
    ----------
    strain0, strain1 : float, array or casadi expression
        The strains e0, e1 at the ends of the interval (-).
    axial_stiffness : float
        EA, N.
    slack_smoothing : float
        delta_T, N (> 0).
    """
    d = slack_smoothing
    x0 = axial_stiffness * strain0
    x1 = axial_stiffness * strain1
    s0 = _sqrt(x0 * x0 + d * d)
    s1 = _sqrt(x1 * x1 + d * d)
    dx = x1 - x0
    xm = 0.5 * (x0 + x1)
    sm = _sqrt(xm * xm + d * d)
    small = abs(dx) <= MEAN_SERIES_WIDTH * sm
    dx_safe = _if_else(small, 1.0, dx)
    xs_part = 0.5 * ((s0 + s1) / 2.0 + (x0 + x1) ** 2 / (2.0 * (s0 + s1)))
    as_part = 0.5 * d * d * (_asinh(x1 / d) - _asinh(x0 / d)) / dx_safe
    exact = xs_part + as_part
    half = 0.5 * dx
    series = sm + d * d / sm**3 * half * half / 6.0
    mean_s = _if_else(small, series, exact)
    return 0.5 * (xm + mean_s)


def mean_taut_switch(strain0: Any, strain1: Any, axial_stiffness: Any,
                     slack_smoothing: Any) -> Any:
    """Exact mean of :func:`taut_switch` over the strain interval [e0, e1], - (0 .. 1).

    (T(e1) - T(e0)) / (EA (e1 - e0)) with T :func:`smooth_tension` (s = T' / EA), written
    without the division: with x = EA e and S = sqrt(x^2 + delta_T^2),
    (S_1 - S_0) / (x_1 - x_0) = (x_0 + x_1) / (S_0 + S_1), so the mean is
    (1 + (x_0 + x_1) / (S_0 + S_1)) / 2, exact for any interval (the switch itself at
    e0 = e1). The damping switch of the midpoint step: like :func:`mean_smooth_tension` it
    stays smooth in e1 where the switch at the middle strain jumps over a strain of
    delta_T / EA.

    Parameters
    ----------
    strain0, strain1 : float, array or casadi expression
        The strains e0, e1 at the ends of the interval (-).
    axial_stiffness : float
        EA, N.
    slack_smoothing : float
        delta_T, N (> 0).
    """
    d = slack_smoothing
    x0 = axial_stiffness * strain0
    x1 = axial_stiffness * strain1
    s0 = _sqrt(x0 * x0 + d * d)
    s1 = _sqrt(x1 * x1 + d * d)
    return 0.5 * (1.0 + (x0 + x1) / (s0 + s1))


def no_push(tension: Any, slack_smoothing: Any) -> Any:
    """The total tension of a cable that cannot push, N: the smooth positive part
    (T + sqrt(T^2 + delta_T^2)) / 2 of an elastic-plus-damping tension T.

    The material damping c (de/dt) s(e) of a taut element that shortens fast can take
    the total below zero (the damper pushing); this caps it at the no-compression floor
    with the smoothing of :func:`smooth_tension` (it is :func:`smooth_tension` with
    EA e replaced by T). It changes a taut element's tension by at most
    delta_T^2 / (4 T) and is dissipative but for that bound.

    Parameters
    ----------
    tension : float, array or casadi expression
        Elastic plus damping tension, N.
    slack_smoothing : float
        delta_T, N.
    """
    return 0.5 * (tension + _sqrt(tension * tension + slack_smoothing * slack_smoothing))
