"""End sensitivities of a solved line: its stiffness at the ends whose position is fixed.

The implicit-function theorem on the collocated equations G(w, p) = 0 of one
:class:`cable_ocp.statics.line_solver.StaticsSolver` gives dw/dp = -G_w^-1 G_p, with the
end positions among the parameters p; the end forces F(w) then give dF/dx = F_w dw/dp.
Exact for the discretised equations (no finite differences), one sparse LU of G_w.
The fixed unstretched length is a parameter too (p[P_LENGTH] = L / ell): the same
factorisation gives the sensitivities to it (:meth:`EndStiffness.length_sensitivity`).
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import sparse_lu
from cable_ocp.physics import seabed
from cable_ocp.scene import Scene
from cable_ocp.statics.formulation import P_END_A, P_END_B, P_LENGTH, Formulation

__all__ = ["EndStiffness"]


class EndStiffness:
    """End forces and their sensitivities for one discretised line (built on first use).

    Parameters
    ----------
    scene : Scene
        The solver's scene (end conditions, seabed, cable weight).
    form : Formulation
        The solver's formulation (its scales).
    coll : Collocation or MultipleShooting
        The solver's transcription (residual, unknown layout).
    grounded : bool
        The line has a grounded part at end_a.
    gj : casadi.Function
        ``(w, p) -> (G, G_w)``, the residual and its sparse Jacobian in the unknowns (the
        solver's Newton function).
    """

    def __init__(self, scene: Scene, form: Formulation, coll: Any, grounded: bool,
                 gj: ca.Function) -> None:
        self.scene = scene
        self.form = form
        self.coll = coll
        self.grounded = grounded
        self.gj = gj
        self._sensitivity: ca.Function | None = None
        self._lu: Any = None  # the kept sparse LU of G_w (built on first use)

    def end_forces(self, ws: ca.MX) -> ca.MX:
        """Forces (N) the cable exerts on the end_a and end_b attachments, (6,), from the
        scaled unknowns: +T(0) and -T(L); with a grounded part, the anchor force is the
        touchdown tension less the seabed's axial gradient over the grounded length, along
        the grounded line (:func:`cable_ocp.physics.seabed.grounded_nodes` at s' = 0)."""
        coll, sc = self.coll, self.form.scales
        nx, last = coll.nx, coll.mesh.n_nodes - 1
        tau0, tau_n = ws[3:6], ws[last * nx + 3: last * nx + 6]
        if self.grounded:
            tmag = ca.sqrt(ca.dot(tau0, tau0))
            e = tau0 / tmag
            k = seabed.axial_gradient(self.scene.environment.seabed,
                                      self.scene.cable.weight_in_water, e) * sc.length / sc.force
            fa = sc.force * ca.fmax(tmag - k * ws[coll.i_g], 0.0) * e
        else:
            fa = sc.force * tau0
        return ca.vertcat(fa, -sc.force * tau_n)

    def functions(self) -> ca.Function:
        """``(w, p) -> (G_e, F_w, G_L)``: the Jacobians of the collocated residual in the end
        values p[P_END_A], p[P_END_B] (n_w x 6), of the end forces (N) in the unknowns
        (6 x n_w) and of the residual in the scaled length p[P_LENGTH] (n_w x 1), on the MX
        graph of the residual (the Jacobian in the unknowns, G_w, comes from the Newton
        functions)."""
        if self._sensitivity is None:
            assert P_LENGTH == 0 and P_END_A.start == 1  # p_head below is the length alone
            n_p = self.coll.n_p
            w = ca.MX.sym("w", self.coll.n_w)
            head = ca.MX.sym("p_head", P_END_A.start)
            ends = ca.MX.sym("p_ends", P_END_B.stop - P_END_A.start)
            tail = ca.MX.sym("p_tail", n_p - P_END_B.stop)
            g = self.coll.residual(w, ca.vertcat(head, ends, tail))
            cheap = ca.Function("statics_sensitivity_parts", [w, head, ends, tail],
                                [ca.jacobian(g, ends), ca.jacobian(self.end_forces(w), w),
                                 ca.jacobian(g, head)])
            wp, pp = ca.MX.sym("w", self.coll.n_w), ca.MX.sym("p", n_p)
            args = (wp, pp[: P_END_A.start], pp[P_END_A.start: P_END_B.stop],
                    pp[P_END_B.stop:])
            self._sensitivity = ca.Function("statics_sensitivity", [wp, pp], cheap(*args),
                                            ["w", "p"], ["G_e", "F_w", "G_L"])
        return self._sensitivity

    def _sensitivities(self, w: np.ndarray, p: np.ndarray, cols: list[int]
                       ) -> tuple[np.ndarray | None, np.ndarray, str]:
        """(dw/dp, F_w, why): the unknowns' sensitivities (n_w, len(cols)) to the
        parameter columns ``cols`` (0 the scaled length p[P_LENGTH], 1-3 end_a, 4-6 end_b,
        scaled), the unstretched length held, and F_w (6, n_w) dense; dw None when they do
        not exist.

        With a fixed length and the compiled sparse LU (:mod:`cable_ocp.numerics.sparse_lu`)
        G_w is refactorised on a pivot order kept between calls (the solves of a mooring
        system's Newton iteration call this once per line and step); else SuperLU
        factorises it anew."""
        g_e, f_w, g_l = self.functions()(w, p)
        h_p = np.hstack([g_l.full(), g_e.full()])[:, cols]
        g_w = self.gj(w, p)[1]
        if not self.coll.free_length and sparse_lu.available():
            if self._lu is None:
                self._lu = sparse_lu.SparseLU(g_w.sparsity())
            self._lu.nz[:] = g_w.nonzeros()
            self._lu.factor()
            # newton_step(b) = -G_w^-1 b: dw = -G_w^-1 G_p column by column
            dw = np.column_stack([self._lu.newton_step(h_p[:, j]) for j in range(len(cols))])
            if not np.all(np.isfinite(dw)):
                return None, f_w.full(), "the Jacobian is singular"
            return dw, f_w.full(), ""
        from scipy.sparse import csr_matrix
        from scipy.sparse.linalg import splu

        h_w = g_w.sparse().tocsr()
        if self.coll.free_length:
            # hold the unstretched length (the line as installed), not the tension: the
            # tension condition, the last residual (Collocation._boundary), becomes
            # "lam (+ g) keeps its value", with no dependence on the end positions
            n, last = self.coll.n_w, self.coll.n_w - 1
            h_w.data[h_w.indptr[last]: h_w.indptr[last + 1]] = 0.0
            hold = np.zeros(n)
            hold[self.coll.i_lam] = 1.0
            if self.coll.grounded:
                hold[self.coll.i_g] = 1.0
            h_w = h_w + csr_matrix((hold, (np.full(n, last), np.arange(n))), shape=(n, n))
            h_p[last] = 0.0
        try:
            dw = splu(h_w.tocsc()).solve(-h_p)  # one factorisation, one column per coordinate
        except RuntimeError as exc:  # "Factor is exactly singular"
            return None, f_w.full(), f"the Jacobian is singular ({exc})"
        return dw, f_w.full(), ""

    def _end_sensitivity(self, w: np.ndarray, p: np.ndarray, cols: list[int]
                         ) -> tuple[np.ndarray | None, str]:
        """dF/dx (N/m, (6, len(cols))) of both end forces in the end coordinates ``cols``
        (0-2 end_a, 3-5 end_b), the unstretched length held; or (None, why)."""
        dw, f_w, why = self._sensitivities(w, p, [c + 1 for c in cols])
        if dw is None:
            return None, why
        dfdx = (f_w @ dw) / self.form.scales.length  # N/m
        if not np.all(np.isfinite(dfdx)):
            return None, "the sensitivity is not finite (ill-conditioned Jacobian)"
        return dfdx, ""

    def _require_fixed_ends(self, what: str) -> None:
        """Raise unless both end positions are fully fixed (``what`` needs them)."""
        if not (all(self.scene.end_a.fixed_mask) and all(self.scene.end_b.fixed_mask)):
            raise CableOCPError(f"{what} needs both end positions fixed")

    def length_sensitivity(self, w: np.ndarray, p: np.ndarray) -> dict[str, Any]:
        """Sensitivities to the unstretched length L and to the end positions of a line
        whose two ends are fixed, from one factorisation (the implicit-function theorem,
        dw/dp = -G_w^-1 G_p with p = (L / ell, x_a / ell, x_b / ell)); exact for the
        discretised equations.

        On a multi-segment line L is the total length with every segment's share L_k / L
        held (the shares are baked into the built functions, ``Formulation.fractions``):
        the derivative in one segment's length alone is not a parameter of the
        formulation (a finite difference of two solves gives it).

        Parameters
        ----------
        w : ndarray
            Converged scaled unknowns of the solver.
        p : ndarray
            Parameter vector of the solve (:meth:`Formulation.params`).

        Returns
        -------
        dict
            ``force``: dF/dL (6,), N/m, F = (F_a, F_b) the forces on the attachments;
            ``end_jacobian``: dF/dx (6x6), N/m (:meth:`end_jacobian`); ``grounded_length``:
            dg/dL (-), g the grounded length at end_a (0 without contact);
            ``grounded_length_ends``: dg/dx (6,) (-). With a grounded part, the z_a entries
            are NaN (one-sided contact).

        Raises
        ------
        CableOCPError
            When an end is not fixed, the length is an unknown (a prescribed tension), or
            the sensitivity does not exist.
        """
        self._require_fixed_ends("length_sensitivity")
        if self.coll.free_length:
            raise CableOCPError("length_sensitivity: the length is an unknown of this scene "
                                "(a prescribed tension), not a parameter; give cable.length")
        dw, f_w, why = self._sensitivities(w, p, list(range(7)))
        if dw is None:
            raise CableOCPError(f"the line's length sensitivity was not computed: {why}")
        ell = self.form.scales.length
        df = (f_w @ dw) / ell  # (6, 7): d/dL, then d/dx, N/m
        # w[i_g] = g / ell and p = (L, x) / ell: d w[i_g] / dp is dg/d(L, x) as it stands
        dg = dw[self.coll.i_g].copy() if self.grounded else np.zeros(7)
        if not (np.all(np.isfinite(df)) and np.all(np.isfinite(dg))):
            raise CableOCPError("the line's length sensitivity is not finite "
                                "(ill-conditioned Jacobian)")
        jac, dg_x = df[:, 1:].copy(), dg[1:].copy()
        if self.grounded:
            jac[:, 2] = np.nan
            dg_x[2] = np.nan
        return {"force": df[:, 0].copy(), "end_jacobian": jac,
                "grounded_length": float(dg[0]), "grounded_length_ends": dg_x}

    def end_jacobian(self, w: np.ndarray, p: np.ndarray) -> np.ndarray:
        """The 6x6 dF/dx of a line whose two ends are fixed: F = (F_a, F_b), the forces
        the cable exerts on its two attachments (N), x = (x_a, x_b) the end positions
        (m), the unstretched length held (the coupling of the two ends included: the
        blocks dF_a/dx_b and dF_b/dx_a). With a grounded part at end_a the column of
        z_a is NaN (one-sided contact, :meth:`matrices`).

        Parameters
        ----------
        w : ndarray
            Converged scaled unknowns of the solver.
        p : ndarray
            Parameter vector of the solve (:meth:`Formulation.params`).

        Raises
        ------
        CableOCPError
            When an end is not fully fixed, or the sensitivity does not exist.
        """
        self._require_fixed_ends("end_jacobian")
        dfdx, why = self._end_sensitivity(w, p, [0, 1, 2, 3, 4, 5])
        if dfdx is None:
            raise CableOCPError(f"the line's end stiffness was not computed: {why}")
        if self.grounded:
            dfdx[:, 2] = np.nan
        return dfdx

    def matrices(self, w: np.ndarray, p: np.ndarray) -> dict[str, dict[str, Any]]:
        """The line's stiffness at each end whose position is fully fixed.

        K[i][j] = dF_i/dx_j (N/m), F the force the cable exerts on that end's attachment
        (as :attr:`StaticsSolution.force_a`/``force_b`` report it) and x that end's
        position, the other end held as the scene says (fixed position or prescribed
        force) and the unstretched length held (a free-length scene holds the length it
        solved for, not the prescribed tension). Exact for the discretised equations:
        the implicit-function theorem on G(w, p) = 0 gives dw/dp = -G_w^-1 G_p, with the
        end positions among the parameters p (one sparse LU factorisation of G_w, one
        column per fixed end coordinate), then dF/dx = F_w dw/dp / ell.

        Parameters
        ----------
        w : ndarray
            Converged scaled unknowns of the solver.
        p : ndarray
            Parameter vector of the solve (:meth:`Formulation.params`).

        Returns
        -------
        dict
            ``{"a": {...}, "b": {...}}``, each with ``matrix`` (3x3 nested list of floats,
            N/m, with None entries where a derivative does not exist; or None) and ``note``
            (what is held, or why there is no matrix).
        """
        scene = self.scene
        held = "the unstretched length held"
        if self.coll.free_length:
            held += " (the length the prescribed tension gave; the tension is not held)"
        out: dict[str, dict[str, Any]] = {}
        fixed: list[str] = []  # ends with a fully fixed position, in the order a, b
        for key, end, other in (("a", scene.end_a, scene.end_b), ("b", scene.end_b,
                                                                  scene.end_a)):
            if not all(end.fixed_mask):
                free = ", ".join("xyz"[i] for i, f in enumerate(end.fixed_mask) if not f)
                out[key] = {"matrix": None, "note": (
                    f"end_{key}'s position is not fully fixed (free in {free}, where a force "
                    "is prescribed): no stiffness at a free end")}
                continue
            how = "fixed" if all(other.fixed_mask) else \
                "as the scene says (its prescribed force components held)"
            out[key] = {"matrix": None,
                        "note": f"end_{'b' if key == 'a' else 'a'} held {how}, {held}"}
            fixed.append(key)
        if not fixed:
            return out
        # parameter columns of the fixed ends among p[P_END_A], p[P_END_B] (scaled m)
        cols = [c for key in fixed for c in ((0, 1, 2) if key == "a" else (3, 4, 5))]
        dfdx, why = self._end_sensitivity(w, p, cols)
        if dfdx is None:
            for key in fixed:
                out[key]["note"] = f"not computed: {why}"
            return out
        for j, key in enumerate(fixed):
            rows = slice(0, 3) if key == "a" else slice(3, 6)  # F_a, F_b in the outputs
            mat = dfdx[rows, 3 * j: 3 * j + 3]
            k_list: list[list[float | None]] = [[float(v) for v in row] for row in mat]
            if key == "a" and self.grounded:
                if scene.environment.seabed.slope_deg != 0.0:  # type: ignore[union-attr]
                    out[key] = {"matrix": None, "note": (
                        "the anchor lies on a sloping seabed with the cable grounded: any "
                        "displacement off the seabed plane lifts the grounded part, where "
                        "the anchor force is not differentiable (one-sided contact)")}
                    continue
                for row in k_list:
                    row[2] = None
                out[key]["note"] += (
                    "; the z column is null: the cable lies on the seabed at the anchor, where "
                    "lifting the anchor changes the force at an unbounded rate (one-sided "
                    "contact), so dF/dz does not exist")
            out[key]["matrix"] = k_list
        return out
