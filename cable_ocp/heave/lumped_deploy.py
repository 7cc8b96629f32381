"""The 3D lumped-mass line with pay-out as the heave plant of a deployment.

:class:`LumpedPayoutPlant` steps the lumped-mass line whose nodes enter and leave at the
winch (:class:`cable_ocp.dynamics.lumped_payout.PayoutLine`, Huang (1992) ch. 5 with the
varying length of ch. 3-4, 004 7.3 (2)) one control sample per call, with the interface of
the other heave plants (:class:`cable_ocp.heave.axial_plant.SampledCablePlant`): the
boom-tip heave raises the top (end_b) vertically, its x and y stay; the winch output ``u``
and the deployment's pay-out set the unstretched length ``L = L_dep - u``, which the top
segment takes (``l_top = L - sum of the others``).

Per number of segments ``n`` one CasADi function advances a sample: ``substeps``
implicit-midpoint steps of the pay-out line's own step (``step_top`` of
:meth:`~cable_ocp.dynamics.lumped_payout.PayoutLine.functions`: the discrete-gradient
tension, the masses at the mean lengths, the top raised linearly over each step), each
solved by CasADi's Newton ``rootfinder``, with the outputs. It is built on first use and
cached for the run (the three controllers of a deployment share it): about 0.15 s at 5
segments, 0.4 s at 20, several seconds at 100 (the symbolic build grows with ``n``; the
step itself about 0.4 ms at 5 segments). A sample whose Newton steps do not converge (a
line going slack, where the no-compression law bends sharply) is taken again with 2, 4 and
8 times the steps (:data:`HALVINGS`; each such function also built once). After each
sample the top segment is checked: above ``SPLIT`` element lengths a node enters at the
winch, below ``MERGE`` the top node leaves
(:meth:`~cable_ocp.dynamics.lumped_payout.PayoutLine.split`, ``merge``: the mass and
momentum bookkeeping of :mod:`cable_ocp.dynamics.lumped_payout`); so events fall on the
sample grid (the top segment overshoots a threshold by at most the length paid out in one
sample, ``h dL/dt``).

The unit's heave is measured from its static height at the paid-out length, in the
current: the lumped-mass equilibrium (:func:`cable_ocp.dynamics.lumped_scene.lumped_start`)
at :data:`STATIC_POINTS` lengths over the deployment, ``round(L / l_e)`` segments each,
interpolated by a cubic spline in ``L`` (exact for the vertical line without current,
whose static depth ``z_b - L - (W L + w L^2 / 2) / EA`` is quadratic in ``L`` and the same
for any mesh).

Outputs per sub-step as the fixed-length lumped plant's
(:class:`cable_ocp.heave.cable_models.LumpedCablePlant`): the unit's height and vertical
velocity, the pull of the cable on the unit (segment 0's tension less the half segment
that the unit's node carries: its weight in water and its inertia at the sub-step's mean
acceleration; its drag and added mass, a few newtons, are left out), the top tension (the
winch's force on the line without the heave's acceleration) and the smallest Hooke tension
``EA eps`` (``<= 0`` where a segment is slack). The unit's horizontal position (m) at the
end of every sample is kept in :attr:`LumpedPayoutPlant.unit_xy`.
"""

from __future__ import annotations

import math
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.lumped_payout import MERGE, SPLIT, PayoutLine, PayoutState
from cable_ocp.dynamics.lumped_scene import LumpedSceneModel
from cable_ocp.errors import CableOCPError
from cable_ocp.heave.axial_plant import SampledCablePlant
from cable_ocp.scene.dynamics import DynamicScene

__all__ = ["HALVINGS", "STATIC_POINTS", "THRESHOLDS", "LumpedPayoutPlant"]

#: lengths at which the static height of the unit is solved for the heave's reference
STATIC_POINTS = 9
#: a sample whose Newton steps do not converge is taken again with 2, 4, 8 times the steps
HALVINGS = 3


class LumpedPayoutPlant(SampledCablePlant):
    """The lumped-mass line with pay-out, one control sample per call (module docstring).

    Parameters
    ----------
    scene : DynamicScene
        A lumped3d scene with a unit at end_a (``[simulation] model = "lumped3d"``):
        ``segments`` at its length, ``element_length`` (default: its top segment's
        length), ``time_step`` (must divide ``sample_time``), ``tolerance``,
        ``max_iterations``. Its ``[top_motion]`` is not used.
    sample_time : float
        Control sample ``h``, s.
    lengths : tuple of float
        The shortest and longest unstretched length of the deployment, m (the range of
        the static reference).
    """

    model_name = "lumped3d"

    def __init__(self, scene: DynamicScene, sample_time: float,
                 lengths: tuple[float, float]) -> None:
        from cable_ocp.dynamics.lumped_payout_run import payout_line
        from cable_ocp.heave.cable_models import still_scene

        self._setup(scene, sample_time)
        still = still_scene(scene)
        start = LumpedSceneModel(still)
        self.line: PayoutLine = payout_line(start)  # checks the element length
        x0, info = start.static_positions()
        if x0 is None:
            raise CableOCPError(f"cable scene: the static state failed: {info['message']}")
        self.model = start  # ``model.n``: the segments at the start
        self._fns: dict[tuple[int, int], ca.Function] = {}
        self._top0 = np.asarray(self.line._top(0.0, 0.0), float).ravel()
        self._x0 = self.line.state(0.0, np.asarray(start.params.segment_length, float),
                                   np.asarray(x0, float), np.zeros(len(x0)))
        self._x0.v[-1] = 0.0  # at rest (the scene's pay-out speed is not this plant's)
        self.unit_xy: list[np.ndarray] = []
        self.segment_counts: list[int] = []
        r = self._sample_fn(start.n)(*self._args(self._x0, np.full(self.substeps + 1,
                                                                self.length0),
                                              np.zeros(self.substeps + 1)))
        self._t_static = (float(r[4][0]), float(r[5][0]))
        self._static_table(still, start, float(x0[2]), lengths)

    # ------------------------------------------------------------------------------------
    def _static_table(self, still: DynamicScene, start: LumpedSceneModel, z0: float,
                      lengths: tuple[float, float]) -> None:
        """The unit's static height (m) at :data:`STATIC_POINTS` lengths, splined."""
        from scipy.interpolate import CubicSpline

        lo, hi = min(lengths[0], self.length0), max(lengths[1], self.length0)
        pts = np.unique(np.concatenate([np.linspace(lo, hi, STATIC_POINTS), [self.length0]]))
        z = np.empty(pts.size)
        le = self.line.element_length
        for k, length in enumerate(pts):
            if abs(length - self.length0) <= 1e-9 * self.length0:
                z[k] = z0
                continue
            sc = still.with_overrides({"cable.length": float(length)})
            m = LumpedSceneModel(sc, segments=max(1, int(round(length / le))))
            x, info = m.static_positions()
            if x is None:
                raise CableOCPError(f"cable scene at {length:.6g} m: the static state failed: "
                                    f"{info['message']}")
            z[k] = float(x[2])
        self.static_lengths, self.static_heights = pts, z
        self._spline = CubicSpline(pts, z)
        self._range = (lo, hi)

    def _sample_fn(self, n: int, substeps: int | None = None) -> ca.Function:
        """The sample function with ``n`` segments (built on first use, cached):
        ``(q, v, l_low, l_top, z) -> (q1, v1, z_unit, v_unit, t_unit, t_top, t_min,
        residual)`` over ``substeps`` steps (default the plant's), ``l_low`` the fixed
        segments' lengths (m), ``l_top`` and ``z`` the top segment's length and the top's
        rise at the sub-step points (m)."""
        m = self.substeps if substeps is None else int(substeps)
        if (n, m) in self._fns:
            return self._fns[(n, m)]
        line, dt = self.line, self.h / m
        fns = line.functions(n)
        step, forces = fns["step_top"], fns["forces_top"]
        nf = line.free(n).size
        pr = line.props(n)
        w0, mu0 = float(pr["weight_in_water"][0]), float(pr["mass_per_length"][0])
        ea = ca.DM(pr["axial_stiffness"])
        q0s, v0s = ca.MX.sym("q", 3 * nf), ca.MX.sym("v", 3 * nf)
        low = ca.MX.sym("l_low", n - 1)
        ltop, z = ca.MX.sym("l_top", m + 1), ca.MX.sym("z", m + 1)
        top = ca.DM(self._top0)
        ez = ca.DM([0.0, 0.0, 1.0])
        q, v = q0s, v0s
        zu, vu, tu, tt, tmin, res = [], [], [], [], [], []
        for j in range(m):
            l0, l1 = ca.vertcat(low, ltop[j]), ca.vertcat(low, ltop[j + 1])
            q1, v1, r = step(q, v, l0, l1, 0.0, dt, z[j], z[j + 1])
            tens, strain, f_top = forces(q1, v1, l1, 0.0, (ltop[j + 1] - ltop[j]) / dt,
                                         z[j + 1], (z[j + 1] - z[j]) / dt)
            up = q1[3:6] if n > 1 else top + z[j + 1] * ez
            chord = up - q1[0:3]
            # the cable's pull on the unit: segment 0 less the half segment at node 0
            pull = (tens[0] * chord / ca.norm_2(chord) - 0.5 * w0 * l1[0] * ez
                    - 0.5 * mu0 * l1[0] * (v1[0:3] - v[0:3]) / dt)
            zu.append(q1[2])
            vu.append(v1[2])
            tu.append(ca.norm_2(pull))
            tt.append(ca.norm_2(f_top))
            tmin.append(ca.mmin(ea * strain))
            res.append(r)
            q, v = q1, v1
        fn = ca.Function(f"lumped_payout_sample_{n}_{m}", [q0s, v0s, low, ltop, z], [
            q, v, ca.vertcat(*zu), ca.vertcat(*vu), ca.vertcat(*tu), ca.vertcat(*tt),
            ca.mmin(ca.vertcat(*tmin)), ca.mmax(ca.vertcat(*res))])
        self._fns[(n, m)] = fn
        return fn

    def _args(self, x: PayoutState, lengths: np.ndarray, rise: np.ndarray) -> list[Any]:
        q, v = self.line.free_vectors(x)
        low = x.lengths[:-1]
        return [q, v, low, np.asarray(lengths, float) - float(np.sum(low)), rise]

    # ------------------------------------------------------------------------------------
    def initial_state(self) -> PayoutState:
        """The static line at the scene's length, at rest (a :class:`PayoutState`; the
        history of :attr:`unit_xy` and :attr:`segment_counts` starts again)."""
        self.unit_xy = []
        self.segment_counts = []
        x = self._x0
        return PayoutState(x.t, x.lengths.copy(), x.r.copy(), x.v.copy())

    def static_unit_height(self, length: float | np.ndarray) -> np.ndarray:
        """Static height of the unit (m) on the unstretched ``length`` (m), in the current
        (module docstring), within the deployment's lengths."""
        length = np.asarray(length, dtype=float)
        lo, hi = self._range
        if np.any((length < lo - 1e-6 * hi) | (length > hi + 1e-6 * hi)):
            raise CableOCPError(f"the lumped3d deployment plant knows the static depth between "
                                f"{lo:.6g} m and {hi:.6g} m of line only")
        return np.asarray(self._spline(length))

    def static_tensions(self, length: float | None = None) -> tuple[float, float]:
        """(tension at the unit, at the top) of the static line at the scene's length, N
        (``length`` other than that: an error)."""
        if length is not None and abs(length - self.length0) > 1e-9 * self.length0:
            raise CableOCPError("the lumped3d deployment plant starts at the cable scene's "
                                f"length {self.length0} m")
        return self._t_static

    def advance(self, x: PayoutState, lengths: np.ndarray, tops: np.ndarray
                ) -> tuple[PayoutState, dict[str, Any]]:
        """Advance one sample, then let nodes enter or leave at the winch.

        Parameters
        ----------
        x : PayoutState
            The line.
        lengths, tops : numpy.ndarray, shape (substeps + 1,)
            Unstretched length and top height at the sub-step points of the sample, m.

        Returns
        -------
        x_next : PayoutState
        out : dict
            As :meth:`SampledCablePlant.advance`, with ``stop`` (why) where the top segment
            would vanish or no node can leave (the state then unchanged, the outputs NaN).
        """
        lengths = np.asarray(lengths, float)
        args = self._args(x, lengths, np.asarray(tops, float) - self.z_top0)
        if np.min(args[3]) <= 0.0:
            return self._stopped(x, f"the top segment's unstretched length would reach "
                                    f"{np.min(args[3]):.3g} m (the line hauled in faster "
                                    "than a node can leave at the winch)")
        n = x.segments
        q1, v1, zu, vu, tu, tt, tmin, res = (np.asarray(a, float).ravel()
                                             for a in self._sample_fn(n)(*args))
        fail = max(1e3 * self.tolerance, 1e-6)  # the closed loop's failure threshold
        for k in range(1, HALVINGS + 1):
            if res[0] <= fail and np.all(np.isfinite(q1)):
                break
            # a step whose Newton did not converge: the sample again in 2^k times the steps
            # (inputs linear between the sub-step points; outputs at the plant's sub-steps)
            fine = self.substeps * 2**k
            s_c = np.arange(self.substeps + 1) / self.substeps
            s_f = np.arange(fine + 1) / fine
            a_f = args[:3] + [np.interp(s_f, s_c, args[3]), np.interp(s_f, s_c, args[4])]
            q1, v1, zu, vu, tu, tt, tmin, res = (np.asarray(a, float).ravel()
                                                 for a in self._sample_fn(n, fine)(*a_f))
            pick = slice(2**k - 1, None, 2**k)
            zu, vu, tu, tt = zu[pick], vu[pick], tu[pick], tt[pick]
        line, dt = self.line, self.dt
        new = line.state(0.0, np.concatenate([x.lengths[:-1], [args[3][-1]]]), q1, v1)
        new.r[-1, 2] = float(tops[-1])  # the raised top; its velocity the last step's
        ldot = (lengths[-1] - lengths[-2]) / dt
        new.v[-1] = (np.array([0.0, 0.0, (tops[-1] - tops[-2]) / dt])
                     - ldot * (new.r[-1] - new.r[-2]) / new.lengths[-1])
        while True:
            ltop = new.lengths[-1]
            if ltop > line.split_at:
                new = line.split(new)
            elif ltop < line.merge_at and new.segments > 1:
                if not line.can_merge(new):
                    return self._stopped(x, f"the line is hauled in to a top segment of "
                                            f"{ltop:.3g} m (< {MERGE} element lengths) and "
                                            "no node can leave (the unit is next)")
                new = line.merge(new)
            else:
                break
        self.unit_xy.append(new.r[0, :2].copy())
        self.segment_counts.append(new.segments)
        out = {"z_unit": zu, "v_unit": vu, "t_unit": tu, "t_top": tt, "t_min": float(tmin[0]),
               "residual": float(res[0])}
        return new, out

    def _stopped(self, x: PayoutState, why: str) -> tuple[PayoutState, dict[str, Any]]:
        nan = np.full(self.substeps, np.nan)
        return x, {"z_unit": nan, "v_unit": nan.copy(), "t_unit": nan.copy(),
                   "t_top": nan.copy(), "t_min": math.nan, "residual": math.inf, "stop": why}

    def run_open_loop(self, lengths: np.ndarray, tops: np.ndarray,
                      chunk: int = 200) -> dict[str, np.ndarray]:
        """Not offered: the identification runs on the fixed-length lumped plant
        (:class:`cable_ocp.heave.cable_models.LumpedCablePlant`) at each length.

        Parameters
        ----------
        lengths, tops : numpy.ndarray
            Unused.
        chunk : int
            Unused.
        """
        raise CableOCPError("LumpedPayoutPlant.run_open_loop: identify on the fixed-length "
                            "lumped3d plant (cable_ocp.heave.cable_models.cable_plant)")


#: the thresholds of the events, element lengths (re-exported for the docs)
THRESHOLDS = (MERGE, SPLIT)
