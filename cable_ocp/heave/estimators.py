"""What a controller knows of the plant: the observation and the estimators.

Every controller (:mod:`cable_ocp.heave.controllers`) acts on an estimate of the state of
its design model, the sampled delayed model ``z = [x; u0_{k-d}, ..., u0_{k-1}]``
(:func:`cable_ocp.heave.discrete.discretize_delayed`, with a depth offset on the cable
plant: :func:`cable_ocp.heave.design.design_table`). An :class:`Estimator` gives it:

* :class:`FullState`: the identity. The plant's state as measured (the unit and winch
  states and the sea and vessel filters' states: the full-state LQR and MPC of
  :func:`cable_ocp.heave.design_loop.compare`), the delay buffer from the controller's own
  commands.
* :class:`KalmanFilter`: the discrete Kalman filter in current-estimator form, the one
  implementation for the LQG on the design model (depth alone) and for every controller on
  the cable plant (depth, winch and boom tip; a table of designs over the deployment length
  is a scheduled filter). The delay buffer is the controller's own past commands, known
  exactly: it is reset to them at each measurement update.

The gain is that of the current estimator (:func:`kalman_gain`): ``x_hat = x_pred + M (y -
C x_pred)`` with ``M = P C^T (C P C^T + R)^-1``, ``P`` the a-priori covariance of the DARE.
python-control's ``dlqe`` returns the gain of the predictor form (``x_pred+ = A x_pred + B u
+ L (y - C x_pred)``, ``L = A M``) instead; it is not used here.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import linalg

from cable_ocp.heave.delay import DelayLine
from cable_ocp.heave.discrete import discretize_noise
from cable_ocp.heave.plant import HeavePlant
from cable_ocp.heave.stochastic import WHITE_NOISE_INTENSITY

__all__ = ["Estimator", "FullState", "KalmanFilter", "Observation", "kalman_gain",
           "process_noise"]


@dataclass(frozen=True)
class Observation:
    """What the plant gives the controller at one sample (:meth:`LoopPlant.observe
    <cable_ocp.heave.closed_loop.LoopPlant.observe>`).

    Attributes
    ----------
    y : numpy.ndarray
        Sensor readings with their noise, m: the unit's depth (heave) first, then, where the
        plant has them, the winch position and the boom-tip heave.
    state : numpy.ndarray or None
        The plant's state (full-state feedback: the design model's state without the delay
        buffer), or None where it is not measured.
    length : float or None
        Deployment length, m (the scheduling variable), or None without a cable.
    forecast : numpy.ndarray or None
        The boom-tip heave known ahead at the next samples (wave preview), m, or None.
    """

    y: np.ndarray
    state: np.ndarray | None = None
    length: float | None = None
    forecast: np.ndarray | None = None


class Estimator(ABC):
    """The estimate of the design model's state from the observations (module docstring).

    Per sample a controller calls :meth:`update` (the measurement update, returning the
    estimate) and, once it has chosen the command, :meth:`predict` (the time update).
    The estimate holds the plant's state, then the buffer (and any further states of the
    estimator's model).

    Parameters
    ----------
    n : int
        The plant's states.
    d : int
        The delay buffer's length (samples of delay).
    """

    n: int
    d: int

    def __init__(self, n: int, d: int) -> None:
        self.n, self.d = int(n), int(d)
        self.delay = DelayLine(d)

    def reset(self) -> None:
        """Back to the start (no command sent, the estimator's initial estimate)."""
        self.delay.reset()

    @abstractmethod
    def update(self, obs: Observation) -> np.ndarray:
        """The estimate after the observation ``obs``."""

    def predict(self, u0: float) -> None:
        """Time update with the command ``u0`` (m) just issued."""
        self.delay.push(u0)


class FullState(Estimator):
    """The identity: ``[obs.state; the buffer of the controller's own commands]``."""

    def update(self, obs: Observation) -> np.ndarray:
        return np.concatenate([obs.state, self.delay.buffer])


#: a filter's model at a deployment length: ``(Ad, Bd, M)``, the sampled model and the gain
FilterModel = tuple[np.ndarray, np.ndarray, np.ndarray]


class KalmanFilter(Estimator):
    """Discrete Kalman filter, current-estimator form, on a sampled delayed model.

    Parameters
    ----------
    model : tuple or callable
        ``(Ad, Bd, M)``: the sampled model ``z+ = Ad z + Bd u0`` (states: plant ``n``,
        buffer ``d``, then any others, such as a depth offset) and the current estimator's
        gain ``M`` (:func:`kalman_gain`); or a function of the deployment length (m, or None)
        that returns them (a scheduled filter, :meth:`cable_ocp.heave.design.DesignTable.
        filter_at`).
    C : numpy.ndarray, shape (ny, nz)
        Measurement rows of the sensors used, the first ``ny`` of the observation's ``y``.
    n, d : int
        Plant states and delay buffer length.
    """

    def __init__(self, model: FilterModel | Callable[[float | None], FilterModel],
                 C: np.ndarray, n: int, d: int) -> None:  # noqa: N803
        super().__init__(n, d)
        self._model = model if callable(model) else (lambda length: model)
        self.C = C
        self.ny = C.shape[0]
        self.size = C.shape[1]
        self.reset()

    def reset(self) -> None:
        super().reset()
        self.xp = np.zeros(self.size)  # the a-priori estimate
        self._xh: np.ndarray | None = None
        self._des: FilterModel | None = None

    def model_at(self, length: float | None = None) -> FilterModel:
        """``(Ad, Bd, M)`` at the deployment length ``length`` (m)."""
        return self._model(length)

    def update(self, obs: Observation) -> np.ndarray:
        des = self._model(obs.length)
        xh = self.xp + des[2] @ (obs.y[: self.ny] - self.C @ self.xp)
        xh[self.n: self.n + self.d] = self.delay.buffer  # own past commands: known exactly
        self._xh, self._des = xh, des
        return xh

    def predict(self, u0: float) -> None:
        des = self._des
        self.xp = des[0] @ self._xh + des[1][:, 0] * u0
        super().predict(u0)


def kalman_gain(Ad: np.ndarray, C: np.ndarray, Qw: np.ndarray, R: np.ndarray  # noqa: N803
                ) -> np.ndarray:
    """Steady-state gain ``M = P C^T (C P C^T + R)^-1`` of the current estimator
    (``x_hat = x_pred + M (y - C x_pred)``), ``P`` the a-priori covariance from the DARE.

    Parameters
    ----------
    Ad : numpy.ndarray, shape (nz, nz)
        Sampled model.
    C : numpy.ndarray, shape (ny, nz)
        Measurement rows.
    Qw : numpy.ndarray, shape (nz, nz)
        Process-noise covariance per sample (:func:`process_noise`).
    R : numpy.ndarray, shape (ny, ny)
        Measurement-noise covariance, m^2.
    """
    P = linalg.solve_discrete_are(Ad.T, C.T, Qw, R)
    return P @ C.T @ np.linalg.inv(C @ P @ C.T + R)


def process_noise(p: HeavePlant, h: float, size: int) -> np.ndarray:
    """Process-noise covariance per sample of a filter whose first states are the plant's:
    the sea's white noise (intensity ``pi``, :data:`cable_ocp.heave.stochastic.
    WHITE_NOISE_INTENSITY`) sampled exactly over ``h`` (s) on the plant's states, zero on the
    others (the delay buffer, an offset), plus ``1e-14`` times its largest entry on the
    diagonal (the DARE needs a positive definite covariance).

    Parameters
    ----------
    p : HeavePlant
        The plant (6.28); its disturbance input drives the sea filter.
    h : float
        Sample time, s.
    size : int
        States of the filter (``>= p.n``).
    """
    Qw = np.zeros((size, size))
    Qw[: p.n, : p.n] = discretize_noise(p.A, p.B2, WHITE_NOISE_INTENSITY, h)
    Qw += 1e-14 * np.eye(size) * np.max(np.abs(Qw))
    return Qw
