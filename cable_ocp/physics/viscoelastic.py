"""The standard linear solid: the rate-dependent spring-dashpot law of synthetic rope.

A spring EA_s in parallel with a Maxwell arm (a spring EA_d - EA_s in series with a dashpot
(EA_d - EA_s) tau), the law of ``[cable] viscoelastic`` (polyester, nylon; Huang (1992) 3.4's
"more general constitutive relation", 004 (12.4))::

    T = EA_s e + (EA_d - EA_s) (e - e_v),   de_v/dt = (e - e_v) / tau

with one dashpot strain e_v per element. Where the models call it: the axial model through
:func:`cable_ocp.physics.elasticity.axial_law_tension` (e_v in its ODE state, integrated by
its own schemes); the planar and lumped models' midpoint steps through
:func:`mean_solid_tension` (the step's tension, with the no-compression switch of
:mod:`cable_ocp.physics.elasticity`) and :meth:`StandardLinearSolid.step_internal` (e_v
advanced by the same midpoint rule, in closed form), their outputs through
:func:`solid_tension`. The statics use the static modulus EA_s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from cable_ocp.physics.elasticity import (
    mean_smooth_tension,
    mean_taut_switch,
    positive_switch,
    smooth_positive,
)

__all__ = ["StandardLinearSolid", "mean_solid_tension", "solid_tension"]


@dataclass(frozen=True)
class StandardLinearSolid:
    """Spring EA_s in parallel with a Maxwell arm (EA_d - EA_s, dashpot (EA_d - EA_s) tau).

    Attributes
    ----------
    static_stiffness : float
        EA_s, N: the modulus under a slow (static) load.
    dynamic_stiffness : float
        EA_d, N (>= EA_s): the modulus under a fast load.
    relaxation_time : float
        tau, s: the Maxwell arm's relaxation time.
    """

    static_stiffness: float
    dynamic_stiffness: float
    relaxation_time: float

    def tension(self, strain: Any, internal_strain: Any) -> Any:
        """T = EA_s e + (EA_d - EA_s) (e - e_v), N (negative in compression).

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain e (-).
        internal_strain : float, array or casadi expression
            The dashpot's strain e_v (-).
        """
        arm = self.dynamic_stiffness - self.static_stiffness
        return self.static_stiffness * strain + arm * (strain - internal_strain)

    def internal_rate(self, strain: Any, internal_strain: Any) -> Any:
        """de_v/dt = (e - e_v) / tau, 1/s.

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain e (-).
        internal_strain : float, array or casadi expression
            The dashpot's strain e_v (-).
        """
        return (strain - internal_strain) / self.relaxation_time

    def energy(self, strain: Any, internal_strain: Any) -> Any:
        """Stored energy per unstretched length, J/m: EA_s e^2 / 2 + (EA_d - EA_s)
        (e - e_v)^2 / 2 (the spring and the Maxwell arm's spring; its dissipation rate is
        (EA_d - EA_s) (e - e_v)^2 / tau).

        Parameters
        ----------
        strain : float, array or casadi expression
            Axial strain e (-).
        internal_strain : float, array or casadi expression
            The dashpot's strain e_v (-).
        """
        arm = self.dynamic_stiffness - self.static_stiffness
        return 0.5 * self.static_stiffness * strain**2 + 0.5 * arm * (strain - internal_strain)**2

    def _step_factor(self, time_step: Any) -> Any:
        return 1.0 + 0.5 * time_step / self.relaxation_time

    def step_stiffness(self, time_step: Any) -> Any:
        """The midpoint step's stiffness, N: over a step of dt the midpoint rule of
        de_v/dt = (e - e_v) / tau gives e_m - e_v,m = (e_m - e_v0) / (1 + dt / (2 tau)),
        so the midpoint tension is linear in the midpoint strain e_m,
        T_m = k e_m - F_0 with k = EA_s + (EA_d - EA_s) / (1 + dt / (2 tau)) (EA_d for a
        step much shorter than tau, EA_s for a much longer one or tau -> 0) and
        F_0 = :meth:`step_offset`.

        Parameters
        ----------
        time_step : float or casadi expression
            dt, s.
        """
        arm = self.dynamic_stiffness - self.static_stiffness
        return self.static_stiffness + arm / self._step_factor(time_step)

    def step_offset(self, internal_strain: Any, time_step: Any) -> Any:
        """F_0 = (EA_d - EA_s) e_v0 / (1 + dt / (2 tau)), N: the midpoint tension's offset
        (:meth:`step_stiffness`) from the dashpot strain e_v0 at the start of the step.

        Parameters
        ----------
        internal_strain : float, array or casadi expression
            e_v0 (-).
        time_step : float or casadi expression
            dt, s.
        """
        arm = self.dynamic_stiffness - self.static_stiffness
        return arm * internal_strain / self._step_factor(time_step)

    def step_internal(self, strain0: Any, strain1: Any, internal_strain: Any,
                      time_step: Any) -> Any:
        """e_v at the end of a midpoint step, (-): e_v1 = e_v0 + dt (e_m - e_v,m) / tau
        with e_m, e_v,m the means of the two levels, solved (it is linear):
        e_v1 = ((1 - a) e_v0 + a (e0 + e1)) / (1 + a), a = dt / (2 tau). The work of the
        midpoint tension T_m (e1 - e0) is then the change of :meth:`energy` plus
        (EA_d - EA_s) (e_m - e_v,m) (e_v1 - e_v0) >= 0, dt times the dissipation rate at
        the midpoint (the discrete energy balance is exact).

        Parameters
        ----------
        strain0, strain1 : float, array or casadi expression
            e at the two levels (-).
        internal_strain : float, array or casadi expression
            e_v0 (-).
        time_step : float or casadi expression
            dt, s.
        """
        a = 0.5 * time_step / self.relaxation_time
        return ((1.0 - a) * internal_strain + a * (strain0 + strain1)) / (1.0 + a)

    def relaxation(self, time: Any, strain: float) -> Any:
        """Tension after a strain step ``strain`` at t = 0 held since, N.

        Parameters
        ----------
        time : float or array
            Time since the step, s (>= 0).
        strain : float
            The step e0 (-).
        """
        arm = self.dynamic_stiffness - self.static_stiffness
        return strain * (self.static_stiffness
                         + arm * np.exp(-np.asarray(time) / self.relaxation_time))

    def creep(self, time: Any, tension: float) -> Any:
        """Strain after a tension step ``tension`` at t = 0 held since (-).

        Parameters
        ----------
        time : float or array
            Time since the step, s (>= 0).
        tension : float
            The step T0, N.
        """
        es, ed = self.static_stiffness, self.dynamic_stiffness
        tau_c = self.relaxation_time * ed / es
        return tension / es - tension * (1.0 / es - 1.0 / ed) * np.exp(-np.asarray(time)
                                                                        / tau_c)


def mean_solid_tension(solid: StandardLinearSolid, strain0: Any, strain1: Any,
                       internal_strain: Any, time_step: Any, slack_smoothing: Any
                       ) -> tuple[Any, Any]:
    """The midpoint step's tension of a standard linear solid with the no-compression
    switch, N, and its damping switch (-): the exact mean of smooth_positive(u) over the
    step's u = k e - F_0 (:meth:`StandardLinearSolid.step_stiffness`, ``step_offset``),
    e in [e0, e1] (:func:`mean_smooth_tension` in u; linear in e_m when taut), and the
    mean of its switch (:func:`mean_taut_switch`). The planar and lumped steps' law.

    Parameters
    ----------
    solid : StandardLinearSolid
        The law.
    strain0, strain1 : float, array or casadi expression
        The strains at the two levels (-).
    internal_strain : float, array or casadi expression
        e_v0, the dashpot strain at the start of the step (-).
    time_step : float or casadi expression
        dt, s.
    slack_smoothing : float
        delta_T, N.
    """
    k = solid.step_stiffness(time_step)
    f0 = solid.step_offset(internal_strain, time_step)
    u0, u1 = k * strain0 - f0, k * strain1 - f0
    return (mean_smooth_tension(u0, u1, 1.0, slack_smoothing),
            mean_taut_switch(u0, u1, 1.0, slack_smoothing))


def solid_tension(solid: StandardLinearSolid, strain: Any, internal_strain: Any,
                  slack_smoothing: Any) -> tuple[Any, Any]:
    """smooth_positive of the standard linear solid's tension at (e, e_v), N, and its
    switch (-): the planar and lumped models' tension at an instant (outputs).

    Parameters
    ----------
    solid : StandardLinearSolid
        The law.
    strain, internal_strain : float, array or casadi expression
        e and e_v (-).
    slack_smoothing : float
        delta_T, N.
    """
    u = solid.tension(strain, internal_strain)
    return smooth_positive(u, slack_smoothing), positive_switch(u, slack_smoothing)
