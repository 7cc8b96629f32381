"""The thesis' printed regulator gains G3, G5 as controllers (Huang 1992, 6.2.4-6.2.6).

Huang prints two gains for the 6.2.6 unit and no weights (:mod:`cable_ocp.heave.thesis`):
**G3** on ``[x, x', u]`` of (6.6), designed without a delay (6.2.4; Figs. 6.15-6.16), and
**G5** on ``[x, x', u, u0(t - tau), u0'(t - tau)]`` of (6.14), the Taylor model (6.13) of a
0.2 s delay (6.2.5; Fig. 6.17). Both are ``u0 = -G z`` (the printed gains are positive). The
controller of G5 cannot measure the two Taylor states: it computes them by running the filter
(6.13) on its own commands, sampled exactly with its command held over the sample
(:class:`TaylorFilterEstimator`).

In a heave scene they are the controllers ``"printed-g3"`` and ``"printed-g5"``
(:data:`cable_ocp.scene.heave.PRINTED_CONTROLLERS`), each run on the plant it was designed for:
the scene's first-order winch with the gain's design delay (none for G3, 0.2 s for G5), whatever
``[winch] delay`` the scene gives the other controllers (:func:`printed_run`). The studies of
the printed gains (poles, free responses, Figs. 6.14-6.17) are :mod:`cable_ocp.heave.regulator`.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from scipy import linalg

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import lqr
from cable_ocp.heave import plant as pl
from cable_ocp.heave.controllers import StateFeedback
from cable_ocp.heave.estimators import Estimator, Observation
from cable_ocp.heave.thesis import G3_626, G5_626, TAU_626
from cable_ocp.scene.heave import PRINTED_CONTROLLERS, HeaveScene

__all__ = ["N_PLANT", "PRINTED", "PrintedGain", "TaylorFilterEstimator", "printed_controller",
           "printed_gain", "printed_run"]

#: unit and winch states of the regulator plant (6.6): ``[x, x', u]``
N_PLANT = 3


@dataclass(frozen=True)
class PrintedGain:
    """A gain printed in the thesis and the plant it was designed for.

    Attributes
    ----------
    name : str
        ``"G3"`` or ``"G5"``.
    G : numpy.ndarray, shape (1, 3) or (1, 5)
        The gain, ``u0 = -G z`` (m of command per m, per m/s, ...).
    delay_model : str
        ``"none"`` (state (6.6)) or ``"taylor"`` (state (6.14)).
    tau : float
        The delay of its plant, s.
    figures : str
        The thesis' figures of its response.
    """

    name: str
    G: np.ndarray
    delay_model: str
    tau: float
    figures: str


#: the thesis' printed gains (Figs. 6.15-6.17)
PRINTED = {
    "G3": PrintedGain("G3", G3_626, "none", 0.0, "Figs. 6.14-6.16"),
    "G5": PrintedGain("G5", G5_626, "taylor", TAU_626, "Fig. 6.17"),
}


def printed_gain(gain: PrintedGain | str) -> PrintedGain:
    """The printed gain of a name: ``"G3"``, ``"G5"``, or a scene's controller name
    ``"printed-g3"``, ``"printed-g5"``.

    Parameters
    ----------
    gain : PrintedGain or str
        The gain or its name.

    Raises
    ------
    CableOCPError
        For any other name, naming the valid ones.
    """
    if isinstance(gain, PrintedGain):
        return gain
    key = gain[len("printed-"):].upper() if gain in PRINTED_CONTROLLERS else gain
    if key not in PRINTED:
        raise CableOCPError(f"printed gain {gain!r} is unknown; valid: {', '.join(PRINTED)} "
                            f"(as controllers: {', '.join(PRINTED_CONTROLLERS)})")
    return PRINTED[key]


class TaylorFilterEstimator(Estimator):
    """The plant's unit and winch states as measured, and the two states of the Taylor delay
    model (6.13) computed by running that filter on the controller's own commands (held over
    the sample, sampled exactly).

    Parameters
    ----------
    tau : float
        The design delay of the filter, s (> 0).
    h : float
        Sample time, s.
    """

    def __init__(self, tau: float, h: float) -> None:
        super().__init__(N_PLANT, 0)
        blk = pl.delay_block("taylor", tau)
        A, B = np.asarray(blk.A), np.asarray(blk.B)
        M = linalg.expm(np.block([[A, B], [np.zeros((1, 3))]]) * h)
        self.Phi, self.Gam = M[:2, :2], M[:2, 2]
        self.w = np.zeros(2)

    def reset(self) -> None:
        super().reset()
        self.w = np.zeros(2)

    def update(self, obs: Observation) -> np.ndarray:
        return np.concatenate([obs.state[:N_PLANT], self.w])

    def predict(self, u0: float) -> None:
        self.w = self.Phi @ self.w + self.Gam * u0


class _UnitWinchOnly(Estimator):
    """The plant's unit and winch states ``[x, x', u]`` as measured."""

    def update(self, obs: Observation) -> np.ndarray:
        return np.asarray(obs.state[:N_PLANT], dtype=float)


def printed_controller(gain: PrintedGain | str, h: float) -> StateFeedback:
    """The printed gain as a :class:`cable_ocp.heave.controllers.StateFeedback` on
    ``[x, x', u]`` (G3) or on ``[x, x', u]`` and the Taylor filter's states (G5).

    Parameters
    ----------
    gain : PrintedGain or str
        The gain.
    h : float
        Sample time, s.
    """
    g = printed_gain(gain)
    est = (TaylorFilterEstimator(g.tau, h) if g.delay_model == "taylor"
           else _UnitWinchOnly(N_PLANT, 0))
    return StateFeedback(g.name, np.asarray(g.G, dtype=float), est)


def printed_run(scene: HeaveScene, name: str) -> tuple[HeaveScene, StateFeedback, str, str]:
    """What a scene's controller ``"printed-g3"`` or ``"printed-g5"`` runs: the scene with the
    gain's design delay as ``[winch] delay``, the controller (named ``name``), and the status
    and message of its design: ``"unstable"`` when the loop sampled at the scene's
    ``sample_time`` with that delay, on the scene's unit (a, b) and winch gain K, has a pole
    outside the unit circle (:func:`cable_ocp.heave.lqr.true_discrete_loop`), ``"failed"``
    when that loop cannot be computed (non-finite numbers), else ``"solved"``.

    Parameters
    ----------
    scene : HeaveScene
        The scene (first-order winch: :func:`cable_ocp.scene.heave.check`).
    name : str
        ``"printed-g3"`` or ``"printed-g5"``.
    """
    g = printed_gain(name)
    h = scene.controller.sample_time
    sc = dataclasses.replace(scene, winch=dataclasses.replace(scene.winch, delay=g.tau))
    ctrl = printed_controller(g, h)
    ctrl.name = name
    what = (f"the thesis' {g.name} ({g.figures}) on its plant: winch delay {g.tau:g} s, "
            f"K = {scene.winch.gain:g} 1/s")
    try:
        des = lqr.design_from_gains(scene.unit.a, scene.unit.b, g.G, tau=g.tau,
                                    method=g.delay_model, K=scene.winch.gain)
        with np.errstate(all="ignore"):
            loop = lqr.true_discrete_loop(des, g.tau, h).A
            rho = float(np.max(np.abs(np.linalg.eigvals(loop))))
    except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
        return sc, ctrl, "failed", (f"{what}: its sampled loop cannot be computed: "
                                    f"{type(exc).__name__}: {exc}")
    if not rho < 1.0:
        return sc, ctrl, "unstable", (f"{what}: the sampled loop is unstable (spectral radius "
                                      f"{rho:.6g} >= 1)")
    return sc, ctrl, "solved", f"{what}; ran to the end with finite, bounded states"
