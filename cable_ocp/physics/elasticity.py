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
object. A material is an object with the :class:`AxialMaterial` interface:

* :class:`LinearElastic`: T = EA e (the models' default);
* :class:`NonlinearElastic`: a measured tension-strain table ``[[T_k, e_k], ...]`` (004
  (12.4): T = T(e), EA = dT/de depending on the tension; Huang (1992) 3.4), with the same
  no-compression switch applied to the table's tension u(e): T = (u + sqrt(u^2 +
  delta_T^2)) / 2. The table (:class:`TensionStrainTable`) is interpolated by monotone
  piecewise-cubic Hermite polynomials (PCHIP, Fritsch-Carlson slopes): u(e) in strain for
  the dynamics, e(T) in tension for the statics (stretch 1 + e(T)). Both pass through every
  row, are monotone and C1, and continue past the first and last rows by the straight line
  of the end slope (C1, so Newton sees a continuous stiffness everywhere). They are each
  other's inverse at the rows, between them to the interpolation error of the table (a
  linear table gives exactly EA e in both), and past the rows exactly: e(T)'s end slopes
  are the reciprocals of u(e)'s (capped at 3 secants, which keeps its end cubics
  monotone). The same code evaluates numbers and CasADi
  symbols (a chain of ``if_else``), so the collocation NLP keeps exact derivatives;
* :class:`~cable_ocp.physics.viscoelastic.StandardLinearSolid` (its own module): the
  rate-dependent spring-dashpot law of synthetic rope
  (polyester, nylon): a spring EA_s in parallel with a Maxwell arm (a spring EA_d - EA_s in
  series with a dashpot (EA_d - EA_s) tau). Its internal state is the dashpot's strain
  e_v (one per element)::

      T = EA_s e + (EA_d - EA_s) (e - e_v),   de_v/dt = (e - e_v) / tau

  A fast load sees EA_d (the dynamic modulus), a slow one EA_s (the static one: at rest
  e_v = e). A strain step e0 relaxes as T(t) = e0 (EA_s + (EA_d - EA_s) exp(-t / tau))
  (``relaxation``); a load step T0 creeps as
  e(t) = T0 / EA_s - T0 (1 / EA_s - 1 / EA_d) exp(-t / tau_c), tau_c = tau EA_d / EA_s
  (``creep``).

Where the models call them: the axial model :func:`axial_law_tension` (compression
allowed), the planar model :func:`cable_material` (over a step
:func:`mean_material_tension`, :func:`mean_material_switch`), the lumped model
:func:`strain_tension` and :func:`strain_switch` at an instant and
:func:`mean_strain_tension`, :func:`mean_strain_switch` over a step (its segment law and
compiled kernel; both models pass a damped element's elastic plus damping tension through
:func:`smooth_positive`: a cable cannot push), the
statics ``Cable.strain_at`` (:meth:`TensionStrainTable.strain_of`). The standard linear
solid: the axial model through :func:`axial_law_tension` (its e_v in the state, the
model's own time schemes), the planar and lumped models' midpoint steps through
:mod:`cable_ocp.physics.viscoelastic` (``mean_solid_tension``, ``step_internal``: e_v
advanced in closed form each step; ``solid_tension`` at an instant).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import casadi as ca
import numpy as np
from scipy.interpolate import PchipInterpolator

if TYPE_CHECKING:
    from cable_ocp.physics.viscoelastic import StandardLinearSolid

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


def axial_law_tension(strain: Any, strain_rate: Any, axial_stiffness: Any, damping: Any, *,
                      table: TensionStrainTable | None = None,
                      solid: StandardLinearSolid | None = None,
                      internal_strain: Any = None) -> Any:
    """The axial model's tension, N (compression allowed, as (3.2)-(3.3)): u(e) + c de/dt
    with a table, T_SLS(e, e_v) + c de/dt with a standard linear solid, else
    :func:`kelvin_voigt_tension`.

    Parameters
    ----------
    strain, strain_rate : float, array or casadi expression
        e (-) and de/dt (1/s).
    axial_stiffness : float
        EA, N (the linear law).
    damping : float
        c, N s.
    table : TensionStrainTable, optional
        The nonlinear law u(e).
    solid : StandardLinearSolid, optional
        The viscoelastic law; needs ``internal_strain``.
    internal_strain : float, array or casadi expression, optional
        The dashpot strain e_v (-).
    """
    if table is not None:
        return table.tension_of(strain) + damping * strain_rate
    if solid is not None:
        return solid.tension(strain, internal_strain) + damping * strain_rate
    return kelvin_voigt_tension(strain, strain_rate, axial_stiffness, damping)


def cable_material(axial_stiffness: float, table: TensionStrainTable | None = None,
                   damping: float = 0.0, slack_smoothing: float = SLACK_SMOOTHING) -> Any:
    """The no-compression material of a cable: :class:`NonlinearElastic` with a table,
    else :class:`LinearElastic`.

    Parameters
    ----------
    axial_stiffness : float
        EA, N (the linear law).
    table : TensionStrainTable, optional
        The tension-strain law.
    damping : float
        Material damping c, N s.
    slack_smoothing : float
        delta_T, N.
    """
    if table is not None:
        return NonlinearElastic(table, damping, slack_smoothing)
    return LinearElastic(axial_stiffness, damping, slack_smoothing)


def strain_tension(strain: Any, axial_stiffness: Any, slack_smoothing: Any,
                   table: TensionStrainTable | None = None) -> Any:
    """No-compression tension, N: :func:`smooth_tension`, or with a table
    :func:`smooth_positive` of its u(e).

    Parameters
    ----------
    strain : float, array or casadi expression
        Axial strain (-).
    axial_stiffness : float or casadi expression
        EA, N (the linear law).
    slack_smoothing : float or casadi expression
        delta_T, N.
    table : TensionStrainTable, optional
        The tension-strain law.
    """
    if table is None:
        return smooth_tension(strain, axial_stiffness, slack_smoothing)
    return smooth_positive(table.tension_of(strain), slack_smoothing)


def strain_switch(strain: Any, axial_stiffness: Any, slack_smoothing: Any,
                  table: TensionStrainTable | None = None) -> Any:
    """0 (slack) .. 1 (taut), -: :func:`taut_switch`, or with a table
    :func:`positive_switch` of its u(e).

    Parameters
    ----------
    strain : float, array or casadi expression
        Axial strain (-).
    axial_stiffness : float or casadi expression
        EA, N.
    slack_smoothing : float or casadi expression
        delta_T, N.
    table : TensionStrainTable, optional
        The tension-strain law.
    """
    if table is None:
        return taut_switch(strain, axial_stiffness, slack_smoothing)
    return positive_switch(table.tension_of(strain), slack_smoothing)


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


def _is_symbolic(x: Any) -> bool:
    return isinstance(x, (ca.SX, ca.MX))


def smooth_positive(force: Any, slack_smoothing: Any) -> Any:
    """(u + sqrt(u^2 + delta_T^2)) / 2, N: the no-compression switch applied to a tension u.

    Parameters
    ----------
    force : float, array or casadi expression
        The material law's tension u, N (negative in compression).
    slack_smoothing : float
        delta_T, N.
    """
    return 0.5 * (force + _sqrt(force * force + slack_smoothing * slack_smoothing))


def positive_switch(force: Any, slack_smoothing: Any) -> Any:
    """d/du of :func:`smooth_positive`: (1 + u / sqrt(u^2 + delta_T^2)) / 2 in (0, 1).

    Parameters
    ----------
    force : float, array or casadi expression
        The material law's tension u, N.
    slack_smoothing : float
        delta_T, N.
    """
    return 0.5 * (1.0 + force / _sqrt(force * force + slack_smoothing * slack_smoothing))


def hermite(x: Any, knots: np.ndarray, values: np.ndarray, slopes: np.ndarray,
            derivative: bool = False) -> Any:
    """Piecewise-cubic Hermite interpolant through (knots, values) with ``slopes``,
    continued by the end slopes' straight lines outside [knots[0], knots[-1]] (C1).

    Parameters
    ----------
    x : float, array or casadi expression
        Where to evaluate (the knots' unit).
    knots, values, slopes : ndarray
        Strictly increasing abscissae, the values and the derivatives there.
    derivative : bool
        Return the derivative instead of the value.
    """
    xk, yk, dk = (np.asarray(a, dtype=float) for a in (knots, values, slopes))
    n = len(xk)

    def piece(i: int, xx: Any) -> Any:
        h = xk[i + 1] - xk[i]
        t = (xx - xk[i]) / h
        if derivative:
            return ((6 * t * t - 6 * t) / h * yk[i] + (3 * t * t - 4 * t + 1) * dk[i]
                    + (-6 * t * t + 6 * t) / h * yk[i + 1] + (3 * t * t - 2 * t) * dk[i + 1])
        return ((2 * t**3 - 3 * t * t + 1) * yk[i] + (t**3 - 2 * t * t + t) * h * dk[i]
                + (-2 * t**3 + 3 * t * t) * yk[i + 1] + (t**3 - t * t) * h * dk[i + 1])

    def line(j: int, xx: Any) -> Any:
        return dk[j] + 0.0 * xx if derivative else yk[j] + dk[j] * (xx - xk[j])

    if _is_symbolic(x):
        out = line(n - 1, x)
        for i in range(n - 2, -1, -1):
            out = ca.if_else(x < xk[i + 1], piece(i, x), out)
        return ca.if_else(x < xk[0], line(0, x), out)
    xa = np.asarray(x, dtype=float)
    idx = np.clip(np.searchsorted(xk, xa, side="right") - 1, 0, n - 2)
    h = xk[idx + 1] - xk[idx]
    t = (xa - xk[idx]) / h
    if derivative:
        out = ((6 * t * t - 6 * t) / h * yk[idx] + (3 * t * t - 4 * t + 1) * dk[idx]
               + (-6 * t * t + 6 * t) / h * yk[idx + 1] + (3 * t * t - 2 * t) * dk[idx + 1])
        out = np.where(xa < xk[0], dk[0], np.where(xa > xk[-1], dk[-1], out))
    else:
        out = ((2 * t**3 - 3 * t * t + 1) * yk[idx] + (t**3 - 2 * t * t + t) * h * dk[idx]
               + (-2 * t**3 + 3 * t * t) * yk[idx + 1] + (t**3 - t * t) * h * dk[idx + 1])
        out = np.where(xa < xk[0], yk[0] + dk[0] * (xa - xk[0]),
                       np.where(xa > xk[-1], yk[-1] + dk[-1] * (xa - xk[-1]), out))
    return out if np.ndim(out) else float(out)


def pchip_slopes(knots: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Monotone (Fritsch-Carlson) PCHIP derivatives at the knots (scipy's
    ``PchipInterpolator``; a straight line for two knots).

    Parameters
    ----------
    knots, values : ndarray
        Strictly increasing abscissae and monotone values.
    """
    xk, yk = np.asarray(knots, dtype=float), np.asarray(values, dtype=float)
    if len(xk) == 2:
        s = (yk[1] - yk[0]) / (xk[1] - xk[0])
        return np.array([s, s])
    return np.asarray(PchipInterpolator(xk, yk).derivative()(xk), dtype=float)


@dataclass(frozen=True)
class TensionStrainTable:
    """A measured tension-strain curve (``[cable] tension_strain``), interpolated both ways.

    Attributes
    ----------
    tension : tuple of float
        T_k, N: 0 first, strictly increasing.
    strain : tuple of float
        e_k (-): 0 first, strictly increasing.
    """

    tension: tuple[float, ...]
    strain: tuple[float, ...]

    def _t_of_e(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        e, t = np.array(self.strain), np.array(self.tension)
        return e, t, pchip_slopes(e, t)

    def _e_of_t(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        e, t = np.array(self.strain), np.array(self.tension)
        slopes = pchip_slopes(t, e)
        # the end slopes: the reciprocals of u(e)'s, so that both continuations past the
        # rows are the same straight line, within the bound 3 x secant that keeps the end
        # cubics monotone (Fritsch-Carlson)
        d_u = pchip_slopes(e, t)
        for end, nxt in ((0, 1), (-1, -2)):
            secant = (e[end] - e[nxt]) / (t[end] - t[nxt])
            if d_u[end] > 0.0:
                slopes[end] = min(1.0 / d_u[end], 3.0 * secant)
        return t, e, slopes

    def tension_of(self, strain: Any) -> Any:
        """u(e): the table's tension at a strain, N (PCHIP in strain; negative below 0).

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain (-).
        """
        return hermite(strain, *self._t_of_e())

    def tangent(self, strain: Any) -> Any:
        """du/de, N: the tangent axial stiffness EA(e) of :meth:`tension_of`.

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain (-).
        """
        return hermite(strain, *self._t_of_e(), derivative=True)

    def strain_of(self, tension: Any) -> Any:
        """e(T): the table's strain at a tension (-), PCHIP in tension (the statics' law).

        Parameters
        ----------
        tension : float, array or casadi expression
            Tension, N.
        """
        return hermite(tension, *self._e_of_t())

    def invert(self, tension: Any) -> np.ndarray:
        """The strain e with u(e) = T exactly (numbers only; bisection on the monotone
        :meth:`tension_of`): the dynamics' own static strain.

        Parameters
        ----------
        tension : float or array
            Tension, N.
        """
        tt = np.atleast_1d(np.asarray(tension, dtype=float))
        lo = np.minimum(self.strain_of(tt), 0.0) - 1.0
        hi = np.maximum(self.strain_of(tt), 0.0) + 1.0
        for _ in range(200):  # 2 / 2^200: below round-off
            mid = 0.5 * (lo + hi)
            up = self.tension_of(mid) > tt
            hi, lo = np.where(up, mid, hi), np.where(up, lo, mid)
        out = 0.5 * (lo + hi)
        return out if np.ndim(tension) else float(out[0])

    def energy(self, strain: Any) -> Any:
        """int_0^e u(x) dx, J/m: the stored energy per unstretched length of
        :meth:`tension_of` (exact for the piecewise cubic and its straight continuations;
        numbers or CasADi symbols).

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain (-).
        """
        xk, yk, dk = self._t_of_e()
        n = len(xk)
        h = np.diff(xk)
        # integral of each piece of the Hermite cubic over its interval
        full = h * (yk[:-1] + yk[1:]) / 2.0 + h * h * (dk[:-1] - dk[1:]) / 12.0
        cum = np.concatenate([[0.0], np.cumsum(full)])

        def part(i: int, x: Any) -> Any:  # int from x_i to x of piece i
            t = (x - xk[i]) / h[i]
            return h[i] * ((t**4 / 2 - t**3 + t) * yk[i] + (t**4 / 4 - 2 * t**3 / 3 + t * t / 2)
                           * h[i] * dk[i] + (-t**4 / 2 + t**3) * yk[i + 1]
                           + (t**4 / 4 - t**3 / 3) * h[i] * dk[i + 1])

        def tail(x: Any) -> Any:
            dx = x - xk[-1]
            return cum[-1] + yk[-1] * dx + 0.5 * dk[-1] * dx * dx

        def head(x: Any) -> Any:  # below the first row (x_0 = 0, y_0 = 0): the line d_0 x
            return 0.5 * dk[0] * (x - xk[0]) ** 2 + yk[0] * (x - xk[0])

        if _is_symbolic(strain):
            out = tail(strain)
            for i in range(n - 2, -1, -1):
                out = ca.if_else(strain < xk[i + 1], cum[i] + part(i, strain), out)
            return ca.if_else(strain < xk[0], head(strain), out)
        x = np.asarray(strain, dtype=float)
        idx = np.clip(np.searchsorted(xk, x, side="right") - 1, 0, n - 2)
        vals = np.array([cum[i] + part(int(i), xi) for i, xi in zip(np.ravel(idx),
                                                                      np.ravel(x),
                                                                      strict=True)])
        vals = np.where(np.ravel(x) < xk[0], head(np.ravel(x)),
                        np.where(np.ravel(x) > xk[-1], tail(np.ravel(x)), vals))
        return vals.reshape(x.shape) if x.ndim else float(vals[0])

    @property
    def initial_stiffness(self) -> float:
        """du/de at e = 0, N."""
        return float(self._t_of_e()[2][0])

    @property
    def max_stiffness(self) -> float:
        """The largest tangent stiffness of :meth:`tension_of` over the rows, N (the
        fastest axial wave; the PCHIP's extreme slopes are at or near the knots)."""
        e = np.array(self.strain)
        fine = np.linspace(e[0], e[-1], 40 * len(e))
        return float(max(np.max(self.tangent(fine)), np.max(self._t_of_e()[2])))

    @property
    def linear(self) -> bool:
        """True when every row lies on one line through 0 (then u = EA e exactly)."""
        e, t = np.array(self.strain), np.array(self.tension)
        return bool(np.allclose(t[1:] / e[1:], t[-1] / e[-1], rtol=1e-12, atol=0.0))


@dataclass(frozen=True)
class NonlinearElastic:
    """A tension-strain table with material damping and the no-compression switch.

    Attributes
    ----------
    table : TensionStrainTable
        The law u(e).
    damping : float
        Material damping c, N s.
    slack_smoothing : float
        delta_T, N.
    """

    table: TensionStrainTable
    damping: float = 0.0
    slack_smoothing: float = SLACK_SMOOTHING

    @property
    def bound(self) -> float:
        """:func:`no_compression_bound`, N."""
        return no_compression_bound(self.slack_smoothing)

    def tension(self, strain: Any, strain_rate: Any = None) -> Any:
        """smooth_positive(u(e)) plus c (de/dt) s when a strain rate is given, N.

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain (-).
        strain_rate : float, array, casadi expression or None
            Strain rate, 1/s (None: no damping term).
        """
        u = self.table.tension_of(strain)
        out = smooth_positive(u, self.slack_smoothing)
        if strain_rate is not None and self.damping != 0.0:
            out = out + self.damping * strain_rate * positive_switch(u, self.slack_smoothing)
        return out

    def stiffness(self, strain: Any) -> Any:
        """u'(e) s(u), N."""
        return self.table.tangent(strain) * self.taut(strain)

    def taut(self, strain: Any) -> Any:
        """:func:`positive_switch` of u(e)."""
        return positive_switch(self.table.tension_of(strain), self.slack_smoothing)

    def energy(self, strain: Any) -> Any:
        """:meth:`TensionStrainTable.energy`, J/m: the table's own law (above the smooth
        tension's energy by at most delta_T e / 2 while taut)."""
        return self.table.energy(strain)


def _if_else(cond: Any, a: Any, b: Any) -> Any:
    if any(_is_symbolic(v) for v in (cond, a, b)):
        return ca.if_else(cond, a, b)
    return np.where(cond, a, b)


#: below this relative width |x1 - x0| / sqrt(x_m^2 + delta_T^2) (x = EA e),
#: :func:`mean_smooth_tension` takes its series
MEAN_SERIES_WIDTH = 1e-3


def mean_smooth_tension(strain0: Any, strain1: Any, axial_stiffness: Any,
                        slack_smoothing: Any) -> Any:
    """Exact mean of :func:`smooth_tension` over the strain interval [e0, e1], N.

    The discrete gradient (W(e1) - W(e0)) / (e1 - e0), W = :func:`smooth_strain_energy`
    (Gonzalez (1996)). With x = EA e, d = delta_T, S = sqrt(x^2 + d^2): the mean is
    (x_0 + x_1) / 4 + (F(x_1) - F(x_0)) / (2 (x_1 - x_0)), F = (x S + d^2 asinh(x / d)) / 2,
    with x_1 S_1 - x_0 S_0 = (x_1 - x_0) ((S_0 + S_1) / 2 + (x_0 + x_1)^2 / (2 (S_0 + S_1)))
    (no cancellation); below :data:`MEAN_SERIES_WIDTH` the series S(x_m) + d^2 h^2 /
    (6 S(x_m)^3) (h the half width; next term of relative order (h / S)^4 <= 1e-12).
    Unlike a Gauss rule it is exact across the kink at e = 0, and C^1 in e1.

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
    x0, x1 = axial_stiffness * strain0, axial_stiffness * strain1
    s0, s1 = _sqrt(x0 * x0 + d * d), _sqrt(x1 * x1 + d * d)
    dx, xm = x1 - x0, 0.5 * (x0 + x1)
    sm = _sqrt(xm * xm + d * d)
    small = abs(dx) <= MEAN_SERIES_WIDTH * sm
    xs_part = 0.5 * ((s0 + s1) / 2.0 + (x0 + x1) ** 2 / (2.0 * (s0 + s1)))
    as_part = 0.5 * d * d * (_asinh(x1 / d) - _asinh(x0 / d)) / _if_else(small, 1.0, dx)
    series = sm + d * d / sm**3 * (0.5 * dx) ** 2 / 6.0
    return 0.5 * (xm + _if_else(small, series, xs_part + as_part))


def mean_taut_switch(strain0: Any, strain1: Any, axial_stiffness: Any,
                     slack_smoothing: Any) -> Any:
    """Exact mean of :func:`taut_switch` over [e0, e1], - (0 .. 1): (T(e1) - T(e0)) /
    (EA (e1 - e0)) written without the division, (1 + (x_0 + x_1) / (S_0 + S_1)) / 2 with
    x = EA e, S = sqrt(x^2 + delta_T^2) (the switch itself at e0 = e1). The planar step's
    damping switch: smooth in e1 where the switch at the mean strain jumps over a strain
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
    x0, x1 = axial_stiffness * strain0, axial_stiffness * strain1
    return 0.5 * (1.0 + (x0 + x1) / (_sqrt(x0 * x0 + d * d) + _sqrt(x1 * x1 + d * d)))


def mean_strain_tension(strain0: Any, strain1: Any, axial_stiffness: Any,
                        slack_smoothing: Any, table: TensionStrainTable | None = None) -> Any:
    """Mean of :func:`strain_tension` over the strain interval [e0, e1], N: the
    discrete-gradient tension of the planar and lumped steps.

    The linear law: exact (:func:`mean_smooth_tension`, from the strain energy, exact across
    the kink at e = 0); a tension-strain table: the 3-point Gauss mean (its ``energy`` is
    the table's own law, not the smoothed one, so its difference quotient is not the mean).

    Parameters
    ----------
    strain0, strain1 : float, array or casadi expression
        The strains e0, e1 at the ends of the interval (-).
    axial_stiffness : float or casadi expression
        EA, N (the linear law).
    slack_smoothing : float or casadi expression
        delta_T, N (> 0).
    table : TensionStrainTable, optional
        The tension-strain law.
    """
    if table is None:
        return mean_smooth_tension(strain0, strain1, axial_stiffness, slack_smoothing)
    from cable_ocp.numerics.quadrature import gauss_legendre

    x, w = gauss_legendre(3)
    em, de = 0.5 * (strain0 + strain1), 0.5 * (strain1 - strain0)
    return sum(0.5 * float(wi) * strain_tension(em + float(xi) * de, axial_stiffness,
                                                slack_smoothing, table)
               for xi, wi in zip(x, w, strict=True))


def mean_strain_switch(strain0: Any, strain1: Any, axial_stiffness: Any,
                       slack_smoothing: Any, table: TensionStrainTable | None = None) -> Any:
    """Mean of :func:`strain_switch` over [e0, e1], - (0 .. 1): the damping switch of the
    planar and lumped steps. The linear law: exact (:func:`mean_taut_switch`); a
    tension-strain table: the same identity in its tension u (:func:`mean_taut_switch` of
    u_0, u_1 with EA = 1: the mean over u).

    Parameters
    ----------
    strain0, strain1 : float, array or casadi expression
        The strains e0, e1 at the ends of the interval (-).
    axial_stiffness : float or casadi expression
        EA, N (the linear law).
    slack_smoothing : float or casadi expression
        delta_T, N (> 0).
    table : TensionStrainTable, optional
        The tension-strain law.
    """
    if table is None:
        return mean_taut_switch(strain0, strain1, axial_stiffness, slack_smoothing)
    return mean_taut_switch(table.tension_of(strain0), table.tension_of(strain1), 1.0,
                            slack_smoothing)


def mean_material_tension(material: Any, strain0: Any, strain1: Any) -> Any:
    """Mean of a material's no-compression tension over [e0, e1], N: the discrete-gradient
    tension of the planar step (:func:`mean_strain_tension` of the material's law).

    Parameters
    ----------
    material : AxialMaterial
        The material (:func:`cable_material`: :class:`LinearElastic` or
        :class:`NonlinearElastic`).
    strain0, strain1 : float, array or casadi expression
        The strains e0, e1 at the ends of the interval (-).
    """
    if isinstance(material, LinearElastic):
        return mean_strain_tension(strain0, strain1, material.axial_stiffness,
                                   material.slack_smoothing)
    return mean_strain_tension(strain0, strain1, None, material.slack_smoothing,
                               material.table)


def mean_material_switch(material: Any, strain0: Any, strain1: Any) -> Any:
    """Mean of a material's taut switch over [e0, e1], - (0 .. 1): the damping switch of
    the planar step (:func:`mean_strain_switch` of the material's law).

    Parameters
    ----------
    material : AxialMaterial
        The material (:func:`cable_material`).
    strain0, strain1 : float, array or casadi expression
        The strains e0, e1 at the ends of the interval (-).
    """
    if isinstance(material, LinearElastic):
        return mean_strain_switch(strain0, strain1, material.axial_stiffness,
                                  material.slack_smoothing)
    return mean_strain_switch(strain0, strain1, None, material.slack_smoothing,
                              material.table)
