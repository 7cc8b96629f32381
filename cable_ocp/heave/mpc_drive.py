"""The winch motor's limits in the linear MPC (:class:`cable_ocp.heave.mpc.LinearMPC`).

The torque ``tau = R T + J u''/R`` and the power ``P = tau u'/R`` of
:mod:`cable_ocp.physics.winch_drive`, written as limit rows on the MPC's prediction: the torque
is linear in the state and the commands; the power is bilinear and is linearised about the
static tension (drum at rest) in the QP, which makes it the speed limit ``|u'| <= P_max / T0``
(Huang (1992), 004_7da4a1ee8042db40.txt, 6.5: the winch's feasibility "in terms of the
magnitudes of the speed, acceleration and torque").
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.plant import HeavePlant

__all__ = ["drive_rows"]


def drive_rows(mpc: Any, plant: HeavePlant, add: Callable, applied: Callable, eu: np.ndarray,
               iu: int, iud: int | None, part: str) -> dict[int, tuple]:
    """The winch motor's limits (:mod:`cable_ocp.physics.winch_drive`) at the samples
    ``k = 0 .. N-1``, once the command of sample ``k`` is applied: the torque ``R T0 +
    R k_c stretch_k + (J/R) u''_k`` within ``[-torque_max, torque_max]``, soft (a slack with
    the tension limit's penalties, the row divided by ``R k_c`` so that its slack is in metres
    of stretch as theirs; linear in the state and the commands; ``u''`` the first-order
    winch's ``-K u' = -K^2 (v - u)`` just after the sample, the second-order winch's
    ``w^2 (v - u) - 2 zeta w u'``), and the
    power ``tau u'/R`` linearised about the static tension, ``|T0 u'_k| <= power_max``,
    a speed limit (rows tagged ``"power"``; the IPOPT formulation of
    :mod:`cable_ocp.heave.mpc` writes the bilinear power instead). Returns ``{k: (tz, tu,
    td, sz, su)}``: the torque ``R T0 + tz z_k + tu u0_k + td D_k`` and the speed ``sz z_k +
    su u0_k`` at each sample.

    Parameters
    ----------
    mpc : LinearMPC
        The MPC being built (its settings, horizon, state sizes).
    plant : HeavePlant
        Its plant (the stretch output, the winch's rows).
    add : callable
        ``add(k, cz, cu, limit, cd=..., lo_only=..., tag=...)``: appends a limit row.
    applied : callable
        ``applied(k)``: the applied command at step ``k`` as ``(z-row, coefficient of u0_k)``.
    eu : numpy.ndarray
        The row that picks the winch output ``u`` from the state.
    iu, iud : int, int or None
        The indices of ``u`` and (second-order winch) ``u'`` in the state.
    part : {"power", "torque"}
        Which rows to add: the hard power rows go before the soft rows, the torque's after
        the tension's (the soft rows last, as :mod:`cable_ocp.heave.mpc_daqp` needs them).
    """
    s = mpc.settings
    if not (s.unit_mass > 0 and s.static_tension > 0) or s.drum_radius is None:
        raise CableOCPError("winch.torque_max, winch.power_max: need winch.drum_radius (m), "
                            "unit.mass > 0 (kg) and unit.static_tension > 0 (N)")
    N, nz, n = mpc.N, mpc.nz, mpc.n
    R, J, t0 = s.drum_radius, s.drum_inertia, s.static_tension
    kc = s.unit_mass / plant.a
    c_str, _ = plant.output_row("stretch")
    cs_ = np.zeros(nz)
    cs_[:n] = c_str
    eud = np.zeros(nz)
    if iud is not None:
        eud[iud] = 1.0
        ww2 = float(-plant.A[iu + 1, iu])
        two_zw = float(-plant.A[iu + 1, iu + 1])
    terms: dict[int, tuple] = {}
    for k in range(N):
        cz, cu = applied(k)
        if iud is None:
            K = plant.K
            sz, su = K * (cz - eu), K * cu              # u' = K (v - u)
            az, au = -K * sz, -K * su                   # u'' = -K u'
        else:
            sz, su = eud, 0.0
            az, au = ww2 * (cz - eu) - two_zw * eud, ww2 * cu
        tz, tu, td = R * kc * cs_ + J / R * az, J / R * au, R * kc
        terms[k] = (tz, tu, td, sz, su)
        if s.torque_max is not None and part == "torque":
            # R T0 + tz z + tu u0 + td D <= torque_max, and >= -torque_max; soft, in metres
            # of stretch (divided by R k_c) so that the tension's penalties fit
            sc = R * kc
            add(k, -tz / sc, -tu / sc, -(s.torque_max - R * t0) / sc, cd=-td / sc,
                lo_only=True, slack=True)
            add(k, tz / sc, tu / sc, -(s.torque_max + R * t0) / sc, cd=td / sc, lo_only=True,
                slack=True)
        if s.power_max is not None and part == "power":
            add(k, t0 * sz, t0 * su, s.power_max, tag="power")
    return terms
