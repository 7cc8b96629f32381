"""The controllers on the cable plant: passive, LQR, LQG and MPC on the Kalman estimate
(:class:`cable_ocp.heave.estimators.KalmanEstimator`)."""

from __future__ import annotations

import numpy as np

from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave.design import DesignTable
from cable_ocp.heave.estimators import KalmanEstimator


class _Ctrl:
    """A controller on estimated states: ``__call__(y, u_prev, buffer, length, fore)``."""

    def __init__(self, name: str, table: DesignTable | None, mpc: mpc_mod.LinearMPC | None
                 ) -> None:
        self.name = name
        self.est = None if table is None else KalmanEstimator(table, 1 if name == "lqg" else 3)
        self.mpc = mpc
        self.times: list[float] = []
        self.failures = 0

    def __call__(self, y: np.ndarray, u_prev: float, buffer: np.ndarray, length: float,
                 fore: np.ndarray | None) -> float:
        if self.est is None:
            return 0.0
        xh, des = self.est.estimate(y, buffer, length)
        if self.mpc is not None:
            z = xh[: self.est.table.nz]
            D = self.mpc.preview_correction(z, fore) if fore is not None else None
            r = self.mpc.step(z, u_prev, D)
            self.times.append(r.solve_time)
            if not r.success:
                self.failures += 1
            u0 = r.u0
        else:
            u0 = float(-(des[2] @ xh)[0])
        self.est.predict(xh, u0, des)
        return u0

