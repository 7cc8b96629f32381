"""The cable as the heave plant: the axial cable model stepped one control sample at a time.

Huang (1992) designs the compensator on the second-order unit model (6.2), identified from
the cable model of his ch. 3 (section 6.2.3), and never closes the loop on the cable itself.
Here the controllers (designed on (6.2), identified or given) run against the axial cable
model (:class:`cable_ocp.dynamics.axial.AxialModel`, Huang's (3.1)-(3.3)) of a dynamic scene:

* the boom-tip heave ``x0(t)`` moves end_b (the sheave) vertically;
* the winch output ``u(t)`` (m, ``u > 0`` hauls the unit up, as in (6.4)) pays cable in at
  end_b: the unstretched length is ``L(t) = L_dep(t) - u(t)``, with ``L_dep`` the deployment
  length (constant, or the pay-out of a lowering);
* the winch itself is the scene's winch model ((6.1) or the second-order winch) with the
  command delayed by exactly ``tau``, integrated exactly (zero-order hold) on the plant's
  sub-steps; it is a position source, as in (6.4).

:class:`AxialCablePlant` builds, once, a CasADi function that advances the cable over one
control sample: the cable scene's ``[simulation] time_step`` divides the sample into ``m``
implicit-midpoint steps, the axial model's own step with the top motion and the length as
inputs (:meth:`cable_ocp.dynamics.axial.AxialModel.driven_step`: ``L`` and the sheave height
linear in time over each step), each solved by Newton's method. One call per sample, no Python per
sub-step.
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.dynamics.axial import AxialModel, static_profile
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.block_tridiagonal import block_tridiagonal_solve
from cable_ocp.numerics.compile import compile_functions
from cable_ocp.scene.dynamics import DynamicScene

__all__ = ["AxialCablePlant", "SampledCablePlant", "compile_plant_functions"]


# ------------------------------------------------------------------------------------------
# The step-able cable
# ------------------------------------------------------------------------------------------

class SampledCablePlant:
    """What the heave loop needs of a cable plant stepped one control sample per call:
    :meth:`advance` (one sample from the state) and :meth:`run_open_loop` (a prescribed
    top and length, for the identification), on top of a subclass's ``_flat`` (one sample,
    flat outputs), ``_sample`` (one sample, for ``mapaccum``), ``substeps``, ``length0``,
    ``z_top0``, :meth:`initial_state`, :meth:`static_unit_height` and
    :meth:`static_tensions`."""

    substeps: int
    length0: float
    z_top0: float
    _chunk_name = "cable_chunk"

    def _setup(self, scene: DynamicScene, sample_time: float, wrong_model: str | None = None,
               need_unit: bool = True) -> None:
        """Check the cable scene (its ``simulation.model`` is this plant's, else
        ``wrong_model`` is the error, by default "<class>: simulation.model = ...;
        expected ..."; a ``[unit]`` where ``need_unit``; its time step divides the control
        sample) and set the sampling attributes: ``scene``, ``h``, ``substeps``, ``dt``,
        ``length0``, ``z_top0``, ``tolerance``."""
        sim = scene.simulation
        if sim.model != self.model_name:
            raise CableOCPError(wrong_model or (
                f"{type(self).__name__}: simulation.model = {sim.model!r}; "
                f'expected "{self.model_name}"'))
        if need_unit and scene.unit is None:
            raise CableOCPError(f'simulation.model = "{self.model_name}" as the heave plant: '
                                "the cable scene needs a [unit] at end_a (the unit the winch "
                                "lifts)")
        ratio = sample_time / sim.time_step
        m = int(round(ratio))
        if m < 1 or abs(ratio - m) > 1e-9 * max(1.0, ratio):
            raise CableOCPError(f"cable scene: [simulation] time_step = {sim.time_step} s must "
                                f"divide the control sample time {sample_time} s")
        self.scene = scene
        self.h = float(sample_time)
        self.substeps = m
        self.dt = self.h / m
        self.length0 = scene.length
        self.z_top0 = float(scene.top_position[2])
        self.tolerance = sim.tolerance

    def advance(self, x: np.ndarray, lengths: np.ndarray, tops: np.ndarray
                ) -> tuple[np.ndarray, dict[str, Any]]:
        """Advance one sample.

        Parameters
        ----------
        x : numpy.ndarray
            State (``2 N``).
        lengths, tops : numpy.ndarray, shape (substeps + 1,)
            Unstretched length (m) and sheave height (m) at the sub-step points of the
            sample, start included.

        Returns
        -------
        x_next : numpy.ndarray
        out : dict
            ``z_unit``, ``v_unit``, ``t_unit``, ``t_top`` (m, m/s, N, N at the ends of the
            sub-steps, shape (substeps,)), ``t_min`` (smallest element tension, N) and
            ``residual`` (largest scaled Newton residual).
        """
        m = self.substeps
        P = np.empty(4 * m)
        P[0::4] = lengths[:-1]
        P[1::4] = lengths[1:]
        P[2::4] = tops[:-1]
        P[3::4] = tops[1:]
        r = self._flat(x, P).full().ravel()
        n2 = x.size
        out = {"z_unit": r[n2: n2 + m], "v_unit": r[n2 + m: n2 + 2 * m],
               "t_unit": r[n2 + 2 * m: n2 + 3 * m], "t_top": r[n2 + 3 * m: n2 + 4 * m],
               "t_min": float(r[n2 + 4 * m]), "residual": float(r[n2 + 4 * m + 1])}
        return r[:n2], out

    def run_open_loop(self, lengths: np.ndarray, tops: np.ndarray,
                      chunk: int = 200) -> dict[str, np.ndarray]:
        """Run a prescribed top motion and length from the static state (identification).

        ``lengths``, ``tops``: on the sub-step grid, ``K * substeps + 1`` points (K samples).
        Returns ``z_unit``, ``t_unit``, ``t_top`` on that grid (the first point static) and
        ``t_min``, ``residual`` (over the run). Chunks of samples are stepped by ``mapaccum``.

        Parameters
        ----------
        lengths, tops : numpy.ndarray
            Unstretched length and top height on the sub-step grid, m.
        chunk : int
            Samples per mapaccum call.
        """
        m = self.substeps
        nk = (len(lengths) - 1) // m
        if nk * m + 1 != len(lengths) or len(tops) != len(lengths):
            raise CableOCPError("run_open_loop: lengths and tops need K * substeps + 1 points")
        x = self.initial_state()
        t_u0, t_t0 = self.static_tensions(float(lengths[0]))
        z = [np.array([float(self.static_unit_height(self.length0)) + tops[0] - self.z_top0])]
        tu, tt = [np.array([t_u0])], [np.array([t_t0])]
        t_min, rmax = min(t_u0, t_t0), 0.0
        done = 0
        while done < nk:
            k = min(chunk, nk - done)
            if k not in self._chunks:
                self._chunks[k] = self._sample.mapaccum(self._chunk_name, k)
            i0 = done * m
            L = lengths[i0: i0 + k * m + 1]
            T = tops[i0: i0 + k * m + 1]
            P = np.vstack([L[:-1], L[1:], T[:-1], T[1:]])
            r = self._chunks[k](x, P)
            x = np.asarray(r[0])[:, -1]
            z.append(np.asarray(r[1]).ravel())
            tu.append(np.asarray(r[3]).ravel())
            tt.append(np.asarray(r[4]).ravel())
            t_min = min(t_min, float(np.min(np.asarray(r[5]))))
            rmax = max(rmax, float(np.max(np.asarray(r[6]))))
            done += k
        return {"z_unit": np.concatenate(z), "t_unit": np.concatenate(tu),
                "t_top": np.concatenate(tt), "t_min": t_min, "residual": rmax}




class AxialCablePlant(SampledCablePlant):
    """The axial cable model advanced one control sample per call (module docstring).

    Parameters
    ----------
    scene : DynamicScene
        An axial scene (``[simulation] model = "axial"``): the line, the unit, the static
        top position, ``segments``, and ``time_step`` (the sub-step, s, which must divide
        ``sample_time``); ``tolerance`` and ``max_iterations`` of the Newton steps. Its
        ``[top_motion]`` is not used: the heave scene moves the top.
    sample_time : float
        Control sample ``h``, s.

    Attributes
    ----------
    substeps : int
        Midpoint steps per sample.
    model : AxialModel
        The discretised line.
    """

    #: the cable scene's ``simulation.model`` of this plant
    model_name = "axial"

    def __init__(self, scene: DynamicScene, sample_time: float) -> None:
        sim = scene.simulation
        self._setup(scene, sample_time, f"cable plant: [simulation] model = {sim.model!r}; "
                    "the heave plant uses the axial model (model = \"axial\")",
                    need_unit=False)
        self.model = AxialModel(scene)
        self._sample = self._build(sim.tolerance, sim.max_iterations)
        self._chunks: dict[int, ca.Function] = {}

    def _build(self, tol: float, max_iter: int) -> ca.Function:
        """The sample function ``(x, P) -> (x_next, z_unit, v_unit, t_unit, t_top, t_min,
        residual)`` (see :meth:`advance`).

        Each midpoint step ``x1 - x0 - dt f(dt/2, (x0 + x1)/2) = 0`` takes two Newton
        iterations from ``x1 = x0``. The Jacobian is block tridiagonal in the node order
        (zeta_i, V_i) (each node couples to its neighbours only: checked when built), so an
        iteration is a block Thomas elimination of 2 x 2 blocks written in SX
        (:func:`cable_ocp.numerics.block_tridiagonal.block_tridiagonal_solve`), about 140
        operations per node: no sparse LU, no Python. The line is nearly linear (the drag
        and the pay-out terms are the only nonlinearities), so one iteration is already
        exact up to them and the second squares that error; the scaled residual of the
        result (as :meth:`AxialModel.step_function` scales it) is returned, and a value above
        ``1e3 tolerance`` marks the run as failed. The functions are compiled to C when a
        compiler is found (:func:`compile_plant_functions`).
        """
        md = self.model
        n = md.n
        n2 = 2 * n
        # the model's step with the top motion and the length as inputs
        st = md.driven_step(self.dt)
        x1, x0, p, res = st.unknown, st.state, st.inputs, st.residual
        perm = [int(i) for i in np.ravel(np.column_stack([np.arange(n), n + np.arange(n)]))]
        back = [int(i) for i in np.argsort(perm)]
        jac = ca.jacobian(res, x1)[perm, perm]
        rows, cols = np.nonzero(np.array(ca.DM(jac.sparsity(), 1)))
        if rows.size and np.max(np.abs(rows // 2 - cols // 2)) > 1:
            raise CableOCPError("cable plant: the axial model's Jacobian is not block "
                                "tridiagonal (internal error)")

        def blk(i: int, j: int) -> ca.SX:
            return jac[2 * i: 2 * i + 2, 2 * j: 2 * j + 2]

        rp = res[perm]
        step = ca.vertcat(*block_tridiagonal_solve(
            [blk(i, i) for i in range(n)], [blk(i + 1, i) for i in range(n - 1)],
            [blk(i, i + 1) for i in range(n - 1)], [rp[2 * i: 2 * i + 2] for i in range(n)]))
        newton = ca.Function("axial_newton", [x1, x0, p], [x1 - step[back]])
        resid = ca.Function("axial_resid", [x1, x0, p],
                            [ca.norm_inf(res * st.residual_scale)])
        out = ca.Function("axial_out", [x1, p], [st.outputs])
        newton, resid, out = compile_plant_functions([newton, resid, out])

        # one sub-step: two iterations, then more (up to max_iterations, evaluated only
        # while the scaled residual exceeds the tolerance: a short-circuit switch)
        xa = ca.MX.sym("xa", n2)
        pm = ca.MX.sym("p", 4)
        x2 = newton(newton(xa, xa, pm), xa, pm)
        y = ca.vertcat(x2, resid(x2, xa, pm))
        yb = ca.MX.sym("y", n2 + 1)
        xb = newton(yb[:n2], xa, pm)
        more = ca.Function("more", [yb, xa, pm], [ca.vertcat(xb, resid(xb, xa, pm))])
        keep = ca.Function("keep", [yb, xa, pm], [yb])
        switch = ca.Function.conditional("newton_more", [keep], more)
        for _ in range(max(0, max_iter - 2)):
            y = switch(y[n2] > tol, y, xa, pm)
        sub = ca.Function("axial_substep", [xa, pm], [y[:n2], y[n2]])

        m = self.substeps
        X = ca.MX.sym("X", n2)
        P = ca.MX.sym("P", 4, m)
        xx = X
        cols_out, rs = [], []
        for j in range(m):
            pj = P[:, j]
            xn, r = sub(xx, pj)
            rs.append(r)
            cols_out.append(out(xn, pj))
            xx = xn
        rmax = rs[0]
        for r in rs[1:]:
            rmax = ca.fmax(rmax, r)
        o = ca.horzcat(*cols_out)
        tmin = o[4, 0]
        for j in range(1, m):
            tmin = ca.fmin(tmin, o[4, j])
        sample = ca.Function("cable_sample", [X, P],
                             [xx, o[0, :], o[1, :], o[2, :], o[3, :], tmin, rmax],
                             ["x", "P"], ["x_next", "z_unit", "v_unit", "t_unit", "t_top",
                                          "t_min", "residual"])
        # the same as one column (one conversion per call in the closed loop)
        Pf = ca.MX.sym("Pf", 4 * m)
        r = sample(X, ca.reshape(Pf, 4, m))
        self._flat = ca.Function("cable_sample_flat", [X, Pf], [ca.vertcat(
            r[0], r[1].T, r[2].T, r[3].T, r[4].T, r[5], r[6])])
        return sample

    # ------------------------------------------------------------------------------------
    def initial_state(self) -> np.ndarray:
        """The static state at the scene's length, at rest (relative to the top, so a top
        that starts displaced carries the static line with it)."""
        return self.model.rest_state()

    def static_unit_height(self, length: float | np.ndarray) -> np.ndarray:
        """Static height of the unit (m) hanging on ``length`` (m) from the top's static
        position: ``z_b - L - (W L + w L^2 / 2) / EA``."""
        return static_profile(self.scene, 0.0, np.asarray(length, dtype=float))[0]

    def static_tensions(self, length: float | None = None) -> tuple[float, float]:
        """(tension at the unit, at the top) of the static line of ``length`` (m), N."""
        length = self.length0 if length is None else length
        tension = static_profile(self.scene, np.array([0.0, length]), length)[1]
        return float(tension[0]), float(tension[1])


def compile_plant_functions(fns: list[ca.Function], flags: str = "-O1") -> list[ca.Function]:
    """Compile the plant's functions to one shared library (``cc -O1``: on the generated
    straight-line code ``-O2`` is no faster and compiles as slowly), cached
    (:func:`cable_ocp.numerics.compile.compile_functions`). Returns them unchanged when compiling is
    off (``CABLE_OCP_CACHE=0``), no compiler is found or anything fails (the interpreted
    functions compute the same numbers, about 5x slower).

    Parameters
    ----------
    fns : list of casadi.Function
        The plant's functions.
    flags : str
        The C compiler's flags.
    """
    return compile_functions(fns, flags, prefix="heave_")

