"""The collocation mesh fitted to the kinks of the drag, for one statics solver.

Where a flow component relative to the cable changes sign, the drag's |u| u has a kink
that caps the order of the collocation (:mod:`cable_ocp.statics.kinks`). A
:class:`KinkMesh` finds the kinks of a profile (the solver's own unknowns or another
solver's solution), builds the mesh with a point on each, and converts mesh coordinates
to arc lengths; :class:`cable_ocp.statics.line_solver.StaticsSolver` moves its mesh with
them (``solver.mesh = "kinks"`` or ``"tracking"``). The interval widths are parameters of
the built functions, so a fitted mesh costs no build.
"""

from __future__ import annotations

import numpy as np

from cable_ocp.scene import Scene
from cable_ocp.statics import kinks as kink_points
from cable_ocp.statics.collocation import Collocation
from cable_ocp.statics.formulation import NX, Formulation
from cable_ocp.statics.mesh import Mesh
from cable_ocp.statics.solution import StaticsSolution

__all__ = ["KinkMesh"]


class KinkMesh:
    """Kinks of the drag and the mesh fitted to them, for one collocation.

    Parameters
    ----------
    coll : Collocation
        The solver's transcription (its mesh is the current one).
    form : Formulation
        The solver's formulation (scales, segments, stiff segments).
    scene : Scene
        The scene whose drag switches (:class:`cable_ocp.statics.kinks.Switches`) are
        evaluated.
    """

    def __init__(self, coll: Collocation, form: Formulation, scene: Scene) -> None:
        self.coll = coll
        self.form = form
        self.switches = kink_points.Switches(scene)

    def arc_lengths(self, sigma: np.ndarray, length: float, g: float) -> list[float]:
        """Unstretched arc lengths of mesh coordinates.

        Parameters
        ----------
        sigma : ndarray
            Mesh coordinates (0 at the first collocated node, 1 at end_b).
        length : float
            Total unstretched length, m.
        g : float
            Grounded length, m (0 without seabed contact).

        Returns
        -------
        list of float
            Arc lengths from end_a, m.
        """
        sig = np.asarray(sigma, dtype=float)
        if not self.form.segmented:
            return (g + sig * (length - g)).tolist()
        # per segment: its share of sigma maps onto its arc (the first starts at g)
        b = np.asarray(self.coll.mesh.bounds)
        k = np.clip(np.searchsorted(b, sig, side="right") - 1, 0, len(b) - 2)
        ss = self.coll.segment_s(length, g)
        s0 = np.array([a for a, _ in ss])[k]
        s1 = np.array([e for _, e in ss])[k]
        return (s0 + (sig - b[k]) / (b[k + 1] - b[k]) * (s1 - s0)).tolist()

    def kinks_of(self, w: np.ndarray, mesh: Mesh) -> np.ndarray:
        """Kinks (sigma) of the profile of scaled unknowns ``w`` on ``mesh``.

        Parameters
        ----------
        w : ndarray
            Scaled unknowns of the solver (node states first).
        mesh : Mesh
            The mesh ``w`` lives on.

        Returns
        -------
        ndarray
            Mesh coordinates of the kinks found.
        """
        coll, sc = self.coll, self.form.scales
        xs = np.asarray(w[: coll.n_x]).reshape(mesh.n_nodes, coll.nx)
        tau = xs[:, 3:6]
        size = np.sqrt(np.einsum("ij,ij->i", tau, tau))
        t = tau / np.where(size > 0.0, size, 1.0)[:, None]
        offs = mesh.segment_offsets()
        seg = np.repeat(np.arange(len(offs) - 1), np.diff(offs)) if mesh.segments else None
        if coll.nx > NX:  # a stiff segment's tangent is (cos theta, 0, sin theta)
            stiff = np.asarray(self.form.stiff)[seg]
            th = xs[:, 6]
            t = np.where(stiff[:, None], np.stack([np.cos(th), 0.0 * th, np.sin(th)], 1), t)
        vals = self.switches(xs[:, :3] * sc.length, t, seg)
        return kink_points.find(mesh.sigma(), vals, offs)

    def fitted_mesh(self, found: np.ndarray) -> Mesh:
        """The mesh with a point on each kink ``found`` (sigma; uniform without any)."""
        base = self.coll.mesh.uniform
        edges = kink_points.fitted_edges(base.segments or (base.intervals,),
                                         base.bounds or (0.0, 1.0), found)
        return base.with_edges(edges)

    @staticmethod
    def same_mesh(a: Mesh, b: Mesh) -> bool:
        """True when no interval end of ``a`` is farther than :data:`kinks.GAP` from
        that of ``b`` (then ``a`` serves where ``b`` is asked for).

        Parameters
        ----------
        a, b : Mesh
            Meshes with the same numbers of intervals.
        """
        return a == b or float(np.max(np.abs(a.interval_edges() - b.interval_edges()))) \
            <= kink_points.GAP

    def solution_kinks(self, sol: StaticsSolution, grounded: bool) -> np.ndarray:
        """Kinks (sigma of this collocation's part) of another solver's solution, from its
        node arrays (a joint between segments appears there twice).

        Parameters
        ----------
        sol : StaticsSolution
            A solution on any mesh, grounded or not.
        grounded : bool
            This collocation has a grounded part at end_a.

        Returns
        -------
        ndarray
            Mesh coordinates of the kinks found.
        """
        off = sol.node_offset
        g = sol.grounded_length if grounded else 0.0
        s = sol.s[off:] if grounded or not off else sol.s
        r = sol.position[len(sol.s) - len(s):]
        tension = sol.tension_vector[len(sol.s) - len(s):]
        size = np.linalg.norm(tension, axis=1)
        t = tension / np.where(size > 0.0, size, 1.0)[:, None]
        bend = sol.diagnostics.get("bending")
        if self.form.nx > NX and bend is not None and len(bend["angle_rad"]) == len(sol.s):
            th = np.asarray(bend["angle_rad"])[len(sol.s) - len(s):]
            stiff_t = np.stack([np.cos(th), 0.0 * th, np.sin(th)], axis=1)
        else:
            stiff_t = None
        # the segment of each node: a joint appears twice, as the end of the segment
        # before it and the start of the next
        cum = np.cumsum([c.length for c in self.form.lines])[:-1]
        seg = np.searchsorted(cum, s, side="right")
        if cum.size:
            tol = 1e-9 * max(sol.length, 1.0)
            at_joint = np.abs(s[:, None] - cum[None, :]).min(axis=1) <= tol
            first = np.concatenate([at_joint[:-1] & at_joint[1:], [False]])
            seg = np.where(first & (seg > 0), seg - 1, seg)
        offs = [0, *np.searchsorted(seg, np.arange(1, len(self.form.lines))).tolist(), len(s)]
        if stiff_t is not None:
            stiff = np.asarray(self.form.stiff)[seg]
            t = np.where(stiff[:, None], stiff_t, t)
        vals = self.switches(r, t, seg)
        found = kink_points.find(np.asarray(s, dtype=float), vals, offs)
        return self.coll.sigma_of_s(found, sol.length, g) if found.size else found
