"""The estimator of the controllers on the cable plant: the LQG's discrete Kalman filter
(current estimator) on the design model, extended to the three measurements (the unit's
depth, the winch position, the boom-tip heave)."""

from __future__ import annotations

import numpy as np

from cable_ocp.heave.design import DesignTable

__all__ = ["KalmanEstimator"]


class KalmanEstimator:
    """The LQG's discrete Kalman filter (current estimator) on the design model.

    ``sensors = 3``: the unit's depth, the winch position and the boom-tip heave;
    ``sensors = 1``: the depth alone. The delay buffer is set to the known past commands.
    With a :class:`DesignTable` of several lengths the model and gains are interpolated at
    the current deployment length (a scheduled filter).
    """

    def __init__(self, table: DesignTable, sensors: int) -> None:
        self.table = table
        self.sensors = sensors
        self.C = table.C3[:sensors]
        self.xp = np.zeros(table.Ad.shape[1])

    def estimate(self, y: np.ndarray, buffer: np.ndarray, length: float
                 ) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
        """Measurement update; returns the estimate and the interpolated design."""
        des = self.table.at(length)
        M = des[3] if self.sensors == 3 else des[4]
        xh = self.xp + M @ (y[: self.sensors] - self.C @ self.xp)
        n, nz = self.table.n, self.table.nz
        xh[n:nz] = buffer
        return xh, des

    def predict(self, xh: np.ndarray, u0: float, des: tuple[np.ndarray, ...]) -> None:
        """Time update with the command just issued."""
        self.xp = des[0] @ xh + des[1][:, 0] * u0

