"""The controllers' designs on the unit model (6.2) for a line under the winch: the design
scene, the design table (exact discrete-delay LQR gains, Kalman gains and the estimator's
sampled model at each deployment length, interpolated in the length: gain scheduling) and
the controllers on it (:func:`cable_controller`).

The estimator's model is the delayed design model extended by a depth offset
(:func:`_design`); the Kalman gains are those of the current estimator
(:func:`cable_ocp.heave.estimators.kalman_gain`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave import plant as pl
from cable_ocp.heave.controllers import Controller, MPCController, Passive, StateFeedback
from cable_ocp.heave.discrete import DelayedDiscreteModel, discretize_delayed
from cable_ocp.heave.estimators import KalmanFilter, kalman_gain, process_noise
from cable_ocp.heave.stochastic import discrete_delay_lqr
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.heave import HeaveScene

__all__ = ["B_MIN", "DesignTable", "cable_controller", "design_damping", "design_scene",
           "design_table"]


#: the smallest damping b (s) a design takes: an identified b below it (a line without drag
#: gives b ~ -1e-4 s, the fit's RK4 dissipating a little where the plant's midpoint rule
#: dissipates nothing) is raised to it, with a warning
B_MIN = 1e-6


def design_damping(b: float, where: str) -> tuple[float, str | None]:
    """``(b used by the design, warning or None)``: an identified ``b`` below :data:`B_MIN`
    is raised to it (the unit model (6.2) needs b >= 0).

    Parameters
    ----------
    b : float
        The identified damping, s.
    where : str
        What the warning names.
    """
    if b >= B_MIN:
        return float(b), None
    return B_MIN, (f"{where}: the identified b = {b:.3g} s is below {B_MIN:g} s (a line with "
                   "almost no damping, or an experiment too short for its resonance); the "
                   f"design uses b = {B_MIN:g} s")


def design_scene(scene: HeaveScene, identification: Any | None, cable_scene: DynamicScene
                 ) -> tuple[HeaveScene, str]:
    """The heave scene with its design model: identified ``a, b`` (and ``b_quadratic``)
    unless ``[unit] a`` and ``b`` are given in the file; the unit's mass and static tension
    from the cable scene when not given. Returns ``(scene, source)``.

    Parameters
    ----------
    scene : HeaveScene
        The heave scene.
    identification : CableIdentification or None
        The identification (needed unless ``[unit] a, b`` are given).
    cable_scene : DynamicScene
        The cable scene (the unit's mass and weight when not given).
    """
    given = isinstance(scene.raw.get("unit"), dict) and {"a", "b"} <= set(scene.raw["unit"])
    unit = scene.unit
    kw: dict[str, Any] = {"cable_scene": None}
    source = "given"
    if not given:
        if identification is None:
            raise CableOCPError("[unit] a and b are not given and nothing was identified")
        kw.update(a=identification.linear.a,
                  b=design_damping(identification.linear.b, "design model")[0])
        if identification.quadratic is not None and "b_quadratic" not in scene.raw["unit"]:
            kw["b_quadratic"] = identification.quadratic.b
        source = "identified"
    if not unit.mass > 0 and cable_scene.unit is not None:
        kw["mass"] = cable_scene.unit.mass + cable_scene.unit.added_mass[2]
        kw["static_tension"] = cable_scene.unit.weight_in_water
    return replace(scene, unit=replace(unit, **kw),
                   simulation=replace(scene.simulation, plant="model")), source


# ------------------------------------------------------------------------------------------
# Estimator and controllers
# ------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class DesignTable:
    """A design (or a table of designs over lengths) the controllers interpolate.

    Attributes
    ----------
    lengths : numpy.ndarray, shape (K,)
        Deployment lengths of the designs, m (one entry: a fixed design).
    a, b : numpy.ndarray, shape (K,)
        Design-model coefficients of (6.2), s^2 and s.
    Ad, Bd : numpy.ndarray, shapes (K, nz + 1, nz + 1), (K, nz + 1, 1)
        The estimator's models: the sampled delayed design models
        (:func:`cable_ocp.heave.discrete.discretize_delayed`) and the depth offset.
    G : numpy.ndarray, shape (K, 1, nz + 1)
        Exact discrete-delay LQR gains, ``u0 = -G z`` (0 on the offset).
    M3, M1 : numpy.ndarray, shapes (K, nz + 1, 3), (K, nz + 1, 1)
        Kalman gains of the current estimator with the three sensors (depth, winch,
        boom tip) and with the depth alone.
    C3 : numpy.ndarray, shape (3, nz + 1)
        Measurement rows (depth, winch, boom tip); the first row is the depth's.
    n : int
        Plant states (the delay buffer follows).
    nz : int
        Plant states and delay buffer: the design model's state (the depth offset follows,
        the estimator's last state; :func:`_design`).
    """

    lengths: np.ndarray
    a: np.ndarray
    b: np.ndarray
    Ad: np.ndarray
    Bd: np.ndarray
    G: np.ndarray
    M3: np.ndarray
    M1: np.ndarray
    C3: np.ndarray
    n: int
    nz: int

    def _interp(self, arrays: tuple[np.ndarray, ...], length: float | None
                ) -> tuple[np.ndarray, ...]:
        """The entries of ``arrays`` linearly interpolated at ``length`` (m; held outside the
        table; None or a one-entry table: the first design)."""
        L = self.lengths
        if L.size == 1 or length is None:
            return tuple(arr[0] for arr in arrays)
        if length <= L[0]:
            i, w = 0, 0.0
        elif length >= L[-1]:
            i, w = L.size - 2, 1.0
        else:
            i = int(np.searchsorted(L, length) - 1)
            w = (length - L[i]) / (L[i + 1] - L[i])
        return tuple((1 - w) * arr[i] + w * arr[i + 1] for arr in arrays)

    def at(self, length: float) -> tuple[np.ndarray, ...]:
        """``(Ad, Bd, G, M3, M1)`` linearly interpolated in the length (m; held outside)."""
        return self._interp((self.Ad, self.Bd, self.G, self.M3, self.M1), length)

    def gain_at(self, length: float | None) -> np.ndarray:
        """The LQR gain ``G`` at the deployment length ``length`` (m): the scheduled gain."""
        return self._interp((self.G,), length)[0]

    def filter_at(self, length: float | None, sensors: int) -> tuple[np.ndarray, ...]:
        """``(Ad, Bd, M)`` of the scheduled Kalman filter
        (:class:`cable_ocp.heave.estimators.KalmanFilter`).

        Parameters
        ----------
        length : float or None
            Deployment length, m (None: the first design).
        sensors : int
            3: depth, winch and boom tip; 1: the depth alone.
        """
        return self._interp((self.Ad, self.Bd, self.M3 if sensors == 3 else self.M1), length)

    def kalman_filter(self, sensors: int) -> KalmanFilter:
        """The (scheduled) Kalman filter with the first ``sensors`` measurements (3 or 1)."""
        return KalmanFilter(lambda length: self.filter_at(length, sensors), self.C3[:sensors],
                            self.n, self.nz - self.n)


def _design(sc: HeaveScene, a: float, b: float, compensator: bool = False
            ) -> tuple[pl.HeavePlant, np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                       np.ndarray, np.ndarray, int]:
    """Plant (6.28) with ``a, b``; the estimator's sampled model (delayed design model plus
    a depth offset); LQR gain; Kalman gains; measurement rows; ``nz``.

    The estimator's state is ``[plant (n); past commands (d); depth offset]``. The offset is
    a random walk seen only by the depth sensor: the static depth of the unit is never known
    exactly (a pressure sensor's offset, the tide, the drag of a pay-out, which shifts the
    unit by centimetres, the design model's own static error). Its intensity gives the
    filter a time constant ``[controller] depth_bias_time`` for it (per-sample variance
    ``(sigma_depth h / tau_b)^2``: the bandwidth ``1 / tau_b`` of a random walk seen in white
    noise), far below the waves, so that a slow offset is not taken for heave and not
    compensated; without it the filter forces the design model's states to explain it.
    """
    from cable_ocp.heave.design_loop import build_models

    s2 = replace(sc, unit=replace(sc.unit, a=a, b=b))
    models = build_models(s2)
    p = models.plant_phc if compensator else models.plant
    c = sc.controller
    h, tau = c.sample_time, sc.winch.delay
    G = np.atleast_2d(discrete_delay_lqr(p.A, p.B1, p.e("x"), c.q, c.r, h, tau))
    mdl: DelayedDiscreteModel = discretize_delayed(p.A, p.B1, h, tau)
    nz, n = mdl.Ad.shape[0], p.n
    ne = nz + 1
    Ad = np.eye(ne)
    Ad[:nz, :nz] = mdl.Ad
    Bd = np.zeros((ne, 1))
    Bd[:nz] = mdl.Bd
    Qw = process_noise(p, h, ne)
    tb = c.depth_bias_time
    Qw[nz, nz] = (c.measurement_noise * h / tb) ** 2 if tb > 0 else 0.0
    C3 = np.zeros((3, ne))
    C3[0, :n] = p.e("x")
    C3[0, nz] = 1.0 if tb > 0 else 0.0
    C3[1, :n] = p.e("u")
    C3[2, :n] = p.e("x0")
    R3 = np.diag([c.measurement_noise**2, c.winch_noise**2, c.boom_tip_noise**2])
    if tb > 0:
        M3 = kalman_gain(Ad, C3, Qw, R3)
        M1 = kalman_gain(Ad, C3[:1], Qw, R3[:1, :1])
    else:  # no offset state: the filter on the design model alone
        M3 = np.zeros((ne, 3))
        M1 = np.zeros((ne, 1))
        M3[:nz] = kalman_gain(mdl.Ad, C3[:, :nz], Qw[:nz, :nz], R3)
        M1[:nz] = kalman_gain(mdl.Ad, C3[:1, :nz], Qw[:nz, :nz], R3[:1, :1])
    Ge = np.zeros((1, ne))
    Ge[:, :nz] = G
    return p, Ad, Bd, Ge, M3, M1, C3, nz


def design_table(scene: HeaveScene, lengths: np.ndarray, a: np.ndarray, b: np.ndarray,
                 compensator: bool = False) -> tuple[DesignTable, pl.HeavePlant]:
    """Designs (LQR gain, Kalman gains, sampled model) at each ``(length, a, b)``.

    Parameters
    ----------
    scene : HeaveScene
        The design scene (weights, noises, winch, sea).
    lengths : numpy.ndarray
        Deployment lengths of the designs, m.
    a, b : numpy.ndarray
        The design model's coefficients there, s^2 and s.
    compensator : bool
        On the plant with the passive compensator (``[passive_compensator]``, the block
        ``"comp"``: :attr:`cable_ocp.heave.design_loop.Models.plant_phc`), whose stroke the
        Kalman filter estimates from the same sensors.
    """
    rows = [_design(scene, float(ai), float(bi), compensator)
            for ai, bi in zip(a, b, strict=True)]
    p = rows[0][0]
    return DesignTable(lengths=np.asarray(lengths, dtype=float), a=np.asarray(a, dtype=float),
                       b=np.asarray(b, dtype=float),
                       Ad=np.stack([r[1] for r in rows]), Bd=np.stack([r[2] for r in rows]),
                       G=np.stack([r[3] for r in rows]), M3=np.stack([r[4] for r in rows]),
                       M1=np.stack([r[5] for r in rows]), C3=rows[0][6], n=p.n,
                       nz=rows[0][7]), p


def cable_controller(name: str, table: DesignTable | None, mpc: mpc_mod.LinearMPC | None
                     ) -> Controller:
    """The controller ``name`` on a line under the winch, on the Kalman estimate of the
    design model (:meth:`DesignTable.kalman_filter`): ``passive``; ``lqg`` (its own sensor
    set: the unit's depth only, as on the design model) and the others (the three sensors:
    depth, winch and boom tip) with the table's (scheduled) gain, or the MPC ``mpc`` on the
    estimate (certainty equivalence).

    Parameters
    ----------
    name : str
        ``"passive"``, ``"lqr"``, ``"lqg"``, ``"mpc"``, ``"lqr_fixed"``, ``"lqr_scheduled"``.
    table : DesignTable or None
        The design (None for ``passive``).
    mpc : LinearMPC or None
        The MPC of a ``"mpc"`` run.
    """
    if table is None:
        return Passive()
    est = table.kalman_filter(1 if name == "lqg" else 3)
    if mpc is not None:
        return MPCController(mpc, est, name)
    return StateFeedback(name, table, est)
