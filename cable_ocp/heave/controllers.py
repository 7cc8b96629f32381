"""The controllers of the heave loop, one interface for all of them.

A :class:`Controller` is reset at the start of a run and then asked, once per control
sample, for the winch command ``u0`` (m) given the plant's :class:`Observation
<cable_ocp.heave.estimators.Observation>`; it reports its name, its energy index (the
Frobenius norm of a fixed linear gain, else None), the MPC's solve times and the samples
where its solver failed. The loop (:func:`cable_ocp.heave.closed_loop.run_loop`) does not
know which controller it runs:

* :class:`Passive`: the winch held still (``u0 = 0``; not the thesis' passive compensator).
* :class:`StateFeedback`: ``u0 = -G z_hat`` on an estimator's estimate: the exact
  discrete-delay LQR on the full state (:class:`cable_ocp.heave.estimators.FullState`), the
  LQG (the same gain on the Kalman filter), and on the cable plant the LQR on the Kalman
  estimate from three sensors; with a table of designs over the deployment length the gain
  (and the filter) are interpolated in the length: the scheduled gains
  (:class:`cable_ocp.heave.design.DesignTable`).
* :class:`MPCController`: :class:`cable_ocp.heave.mpc.LinearMPC` on the estimate of the
  plant's state (the MPC keeps its own delay buffer).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any

import numpy as np

from cable_ocp.heave.estimators import Estimator, Observation
from cable_ocp.heave.mpc import LinearMPC

__all__ = ["Controller", "MPCController", "Passive", "StateFeedback"]


class Controller(ABC):
    """The interface of every heave controller (module docstring).

    Attributes
    ----------
    name : str
        The controller's name (``"passive"``, ``"lqr"``, ...).
    estimator : Estimator or None
        Where its state estimate comes from (None: it needs none).
    solve_times : list of float
        Wall time of each solver call, s (the MPC's; empty for the others).
    failures : int
        Samples at which its solver failed (the MPC's QP; it then applied its shifted plan).
    """

    name = "controller"
    estimator: Estimator | None = None

    def __init__(self) -> None:
        self.solve_times: list[float] = []
        self.failures = 0

    def reset(self) -> None:
        """Back to the start of a run: no command sent, statistics cleared."""
        self.solve_times = []
        self.failures = 0
        if self.estimator is not None:
            self.estimator.reset()

    @abstractmethod
    def step(self, obs: Observation) -> float:
        """The command ``u0`` (m) to issue now, given the observation ``obs``."""

    @property
    def energy_index(self) -> float | None:
        """Frobenius norm of a fixed linear gain (the design's energy index), else None."""
        return None


class Passive(Controller):
    """The winch held still: ``u0 = 0``."""

    name = "passive"

    def step(self, obs: Observation) -> float:  # noqa: ARG002
        return 0.0


class StateFeedback(Controller):
    """``u0 = -G z_hat``: a linear gain on an estimator's estimate.

    Parameters
    ----------
    name : str
        ``"lqr"``, ``"lqg"``, ``"lqr_fixed"``, ``"lqr_scheduled"``, ...
    gain : numpy.ndarray or object
        The gain ``G``, shape (1, nz) on the estimate (1/1: m of command per unit of state),
        or a table of designs with ``gain_at(length)`` and ``lengths`` (the scheduled gains
        of :class:`cable_ocp.heave.design.DesignTable`), interpolated at the observed
        deployment length.
    estimator : Estimator
        Gives ``z_hat``.
    """

    def __init__(self, name: str, gain: Any, estimator: Estimator) -> None:
        super().__init__()
        self.name = name
        self.estimator = estimator
        self._table = None if isinstance(gain, np.ndarray) else gain
        self._G = gain if self._table is None else None

    def gain_at(self, length: float | None) -> np.ndarray:
        """The gain at the deployment length ``length`` (m)."""
        return self._G if self._table is None else self._table.gain_at(length)

    @property
    def energy_index(self) -> float | None:
        """``||G||_F`` of a fixed gain; None for a schedule over several lengths (the gain
        changes with the length)."""
        if self._table is None:
            G = self._G
        elif len(self._table.lengths) == 1:
            G = self._table.G[0]
        else:
            return None
        return float(np.sqrt(np.sum(G**2)))

    def step(self, obs: Observation) -> float:
        xh = self.estimator.update(obs)
        u0 = float(-(self.gain_at(obs.length) @ xh)[0])
        self.estimator.predict(u0)
        return u0


class MPCController(Controller):
    """:class:`cable_ocp.heave.mpc.LinearMPC` on an estimator's estimate of the plant's state.

    The forecast of the observation (wave preview) enters the prediction as its known
    boom-tip input (:meth:`cable_ocp.heave.mpc.LinearMPC.preview_correction`). Where the QP
    fails the MPC applies its shifted previous plan and the failure is counted.

    Parameters
    ----------
    mpc : LinearMPC
        Built once for the run; it keeps its own delay buffer and last command.
    estimator : Estimator
        Gives the estimate; its first ``mpc.n`` states are the plant's.
    name : str
        Default ``"mpc"``.
    """

    def __init__(self, mpc: LinearMPC, estimator: Estimator, name: str = "mpc") -> None:
        super().__init__()
        self.name = name
        self.mpc = mpc
        self.estimator = estimator

    def reset(self) -> None:
        super().reset()
        self.mpc.reset()

    def step(self, obs: Observation) -> float:
        xh = self.estimator.update(obs)
        x = xh[: self.mpc.n]
        D = (self.mpc.preview_correction(x, obs.forecast) if obs.forecast is not None
             else None)
        r = self.mpc.step(x, D=D)
        self.solve_times.append(r.solve_time)
        if not r.success:
            self.failures += 1
        self.estimator.predict(r.u0)
        return r.u0
