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
