"""The planar model's line properties per element: a line of ``[[cable.segments]]`` on one
uniform grid.

The planar model (:mod:`cable_ocp.dynamics.planar`) discretises the line on y_i = i / N,
elements of one length L / N. A line of segments fits that grid when every joint falls on a
node (each segment a whole number of elements); its elements then carry their segment's
mass, added mass, weight, EA, damping and drag factors, and a node the mean of its two
elements' (half of each element's mass and weight, as on a uniform line). A pay-out stretches
every element alike, which would move the joints along the material: a line of different
segments keeps its length. A uniform line (a single ``[cable]``, or segments that differ only
in their bending stiffness, :mod:`cable_ocp.dynamics.bending_terms`) has plain numbers, so its
expressions are unchanged. Also here: the damped Newton of the planar static state
(:func:`damped_newton`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.added_mass import added_mass_per_length
from cable_ocp.physics.drag import line_drag_factors, vector_drag_columns
from cable_ocp.scene.dynamics import DynamicScene

__all__ = ["PlanarLine", "damped_newton"]

#: the per-element quantities (units: kg/m, kg/m, kg/m, N/m, N, N s, N s^2/m^3, N s^2/m^3)
NAMES = ("mu", "man", "mat", "w", "ea", "c", "kn", "kt")


class PlanarLine:
    """The element properties of a planar scene's line on ``n`` equal elements.

    Parameters
    ----------
    scene : DynamicScene
        The scene (its segments from end_a, or its single cable).
    n : int
        Number of elements.

    Attributes
    ----------
    uniform : bool
        True when every element has the same properties (bending stiffness aside).
    rows : dict of numpy.ndarray
        Per element (N values) each quantity of :data:`NAMES`: mass per length mu,
        normal and tangential added mass man, mat (kg/m), weight in water w (N/m), EA (N),
        damping c (N s), drag factors kn, kt (N s^2/m^3).
    """

    def __init__(self, scene: DynamicScene, n: int) -> None:
        st = scene.statics
        rho = st.environment.water_density
        lines = st.lines
        length = float(scene.length)
        h = length / n
        props = []
        for c, d in zip(lines, scene.cable, strict=True):
            kn, kt = line_drag_factors(rho, c.diameter, c.normal_drag, c.tangential_drag)
            props.append({
                "mu": d.mass_per_length,
                "man": added_mass_per_length(d.added_mass_coefficient, rho, c.diameter),
                "mat": added_mass_per_length(d.tangential_added_mass_coefficient, rho,
                                             c.diameter),
                "w": float(c.weight_in_water), "ea": float(c.axial_stiffness),
                "c": float(d.axial_damping), "kn": kn, "kt": kt})
        same = [replace(c, length=None, bending_stiffness=0.0) for c in lines]
        self.uniform = all(s == same[0] for s in same) and all(
            d == scene.cable[0] for d in scene.cable)
        ends = np.cumsum([float(c.length) for c in lines])  # type: ignore[arg-type]
        if not self.uniform:
            off = np.abs(ends / h - np.round(ends / h))
            if np.any(off > 1e-9 * n):
                raise CableOCPError(
                    f"simulation.segments = {n}: the planar model puts the joints of "
                    "[[cable.segments]] on nodes; give a number of elements that makes "
                    f"every segment a whole number of elements of {h:.6g} m (segment "
                    f"lengths {[float(c.length) for c in lines]} m)")  # type: ignore[arg-type]
            tm = scene.top_motion
            if tm.varying_length:
                raise CableOCPError(
                    "top_motion: a pay-out with [[cable.segments]] of different properties: "
                    'the planar model stretches its uniform grid; give no pay-out (or use '
                    'model = "axial" for a uniform vertical line)')
        mids = (np.arange(n) + 0.5) * h
        k = np.minimum(np.searchsorted(ends, mids), len(lines) - 1)
        self.rows = {name: np.array([float(props[i][name]) for i in k]) for name in NAMES}

    def value(self, name: str) -> Any:
        """Quantity ``name`` of :data:`NAMES`: a number on a uniform line, else a row of the
        elements (casadi DM, 1 x N), in its unit.

        Parameters
        ----------
        name : str
            One of :data:`NAMES`.
        """
        r = self.rows[name]
        return float(r[0]) if self.uniform else ca.DM(r).T

    def nodes(self, name: str) -> Any:
        """Half the sum of the adjacent elements' ``name`` at each node (casadi DM,
        1 x (N+1)): the share of a per-length quantity lumped at a node, per element length
        (one element's half at the ends).

        Parameters
        ----------
        name : str
            One of :data:`NAMES`.
        """
        r = self.rows[name]
        out = np.zeros(r.size + 1)
        out[:-1] += 0.5 * r
        out[1:] += 0.5 * r
        return ca.DM(out).T

    def drag(self, urel: Any, tt: Any, delta: float) -> Any:
        """Vector-law drag per stretched length (N/m, 2 x K) on the last K elements (all N,
        or the top element alone) with unit tangents ``tt`` in the relative flows ``urel``
        (m/s) (:func:`cable_ocp.physics.drag.vector_drag_columns` with each element's
        factors).

        Parameters
        ----------
        urel : casadi SX (2 x K)
            Flow relative to the elements, m/s.
        tt : casadi SX (2 x K)
            Unit tangents, -.
        delta : float
            Smoothing velocity, m/s.
        """
        if self.uniform:
            return vector_drag_columns(urel, tt, self.rows["kn"][0], self.rows["kt"][0],
                                       delta)
        rows, k = urel.shape
        fn = vector_drag_columns(urel, tt, 1.0, 0.0, delta)
        ft = vector_drag_columns(urel, tt, 0.0, 1.0, delta)
        return (ca.repmat(ca.DM(self.rows["kn"][-k:]).T, rows, 1) * fn
                + ca.repmat(ca.DM(self.rows["kt"][-k:]).T, rows, 1) * ft)


def damped_newton(fj: ca.Function, q: np.ndarray, tol: float, max_iter: int,
                  force_scale: float, length: float) -> tuple[np.ndarray, dict[str, Any]]:
    """Damped Newton on the nodal forces of ``fj`` (``q -> (F, dF/dq)``, N and N/m) from
    the offsets ``q`` (m): the planar model's static equilibrium
    (:meth:`cable_ocp.dynamics.planar.PlanarModel.static_equilibrium`).

    Parameters
    ----------
    fj : casadi.Function
        The forces and their Jacobian.
    q : numpy.ndarray
        The start, m.
    tol : float
        Tolerance on the forces, times ``force_scale`` (-).
    max_iter : int
        Newton iterations allowed.
    force_scale : float
        N.
    length : float
        The line's length, m (the rounding floor of the steps: 1e-13 of it).
    """
    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import spsolve

    q = q.copy()

    def ev(x: np.ndarray) -> tuple[np.ndarray, Any]:
        f, j = fj(x)
        return np.asarray(f).ravel(), j

    f, jac = ev(q)
    stalled = False
    it = 0
    for it in range(1, max_iter + 1):  # noqa: B007 - reported
        if not np.all(np.isfinite(f)) or np.abs(f).max() <= tol * force_scale:
            it -= 1
            break
        try:
            with warnings.catch_warnings():  # a singular Jacobian: NaN, reported below
                warnings.simplefilter("ignore")
                dq = -spsolve(csc_matrix(jac.sparse()), f)
        except Exception:  # noqa: BLE001 - reported, never raised
            break
        if not np.all(np.isfinite(dq)):
            break
        n0 = np.linalg.norm(f)
        lam = 1.0
        while lam > 1e-6:
            fn, jn = ev(q + lam * dq)
            if np.all(np.isfinite(fn)) and np.linalg.norm(fn) < (1.0 - 1e-4 * lam) * n0:
                break
            lam *= 0.5
        else:  # no decrease along the Newton step: the rounding floor (or a failure)
            stalled = True
            break
        q = q + lam * dq
        f, jac = fn, jn
        # the rounding floor of a stiff line: steps of 1e-13 of the length
        stalled = lam * np.abs(dq).max() <= 1e-13 * length
        if stalled and np.abs(f).max() <= 1e-9 * force_scale:
            break
    rmax = float(np.abs(f).max()) if np.all(np.isfinite(f)) else math.inf
    ok = rmax <= tol * force_scale or (stalled and rmax <= 1e-9 * force_scale)
    return q, {"converged": bool(ok), "iterations": it, "residual_N": rmax,
               "relative_residual": rmax / force_scale}
