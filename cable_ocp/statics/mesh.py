"""The collocation mesh of a line on sigma = s/L in [0, 1]: its intervals (uniform, or with
points on the drag's kinks: :mod:`cable_ocp.statics.kink_mesh`), the collocation points in
each, and the node positions (:class:`Mesh`), shared by the transcription
(:mod:`cable_ocp.statics.collocation`) and the solvers that refit it.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace

import numpy as np

__all__ = ["Mesh"]


@functools.lru_cache(maxsize=64)
def _mesh_sigma(mesh: Mesh) -> np.ndarray:
    """:meth:`Mesh.sigma`, cached per mesh (read-only)."""
    if mesh.edges:
        edges = np.asarray(mesh.edges)
        tau = np.asarray(mesh.tau)
        parts = []
        first = 0
        for n in mesh.segments or (mesh.intervals,):
            e = edges[first: first + n + 1]
            inner = e[:-1, None] + np.diff(e)[:, None] * tau[None, :]
            parts.append(np.concatenate([np.hstack([e[:-1, None], inner]).ravel(), e[-1:]]))
            first += n
        out = np.concatenate(parts)
    elif mesh.segments:
        parts = []
        for k, n in enumerate(mesh.segments):
            lo, hi = mesh.bounds[k], mesh.bounds[k + 1]
            local = _mesh_sigma(replace(mesh, intervals=n, segments=(), bounds=()))
            parts.append(lo + (hi - lo) * local)
        out = np.concatenate(parts)
    else:
        h = 1.0 / mesh.intervals
        pts: list[float] = []
        for k in range(mesh.intervals):
            pts.append(k * h)
            pts.extend(k * h + h * t for t in mesh.tau)
        pts.append(1.0)
        out = np.asarray(pts)
    out.setflags(write=False)
    return out


@functools.lru_cache(maxsize=64)
def _mesh_edges(mesh: Mesh) -> np.ndarray:
    """:meth:`Mesh.interval_edges`, cached per mesh (read-only)."""
    if mesh.edges:
        out = np.asarray(mesh.edges, dtype=float)
    elif mesh.segments:
        out = np.concatenate([[0.0]] + [
            mesh.bounds[k] + (mesh.bounds[k + 1] - mesh.bounds[k])
            * np.arange(1, n + 1) / n for k, n in enumerate(mesh.segments)])
        out[-1] = 1.0
    else:
        out = np.arange(mesh.intervals + 1) / mesh.intervals
    out.setflags(write=False)
    return out


@functools.lru_cache(maxsize=64)
def _local_widths(mesh: Mesh) -> np.ndarray:
    """:meth:`Mesh.local_widths`, cached per mesh (read-only)."""
    if not mesh.edges:
        out = np.concatenate([np.full(n, 1.0 / n) for n in (mesh.segments or (mesh.intervals,))])
    else:
        out = np.diff(np.asarray(mesh.edges))
        if mesh.segments:
            out = out / np.repeat(np.diff(np.asarray(mesh.bounds)), mesh.segments)
    out.setflags(write=False)
    return out


@dataclass(frozen=True)
class Mesh:
    """Node locations of a collocation mesh on sigma in [0, 1].

    The intervals are uniform (in each segment) unless ``edges`` gives their ends: the
    built functions do not depend on where the interval ends lie (each interval's width
    is a parameter of the residual, :meth:`Collocation.params`), so one solver serves
    every mesh with the same numbers of intervals (:mod:`cable_ocp.statics.kinks` places
    mesh points on the kinks of the drag)."""

    intervals: int
    degree: int
    scheme: str
    tau: tuple[float, ...]
    #: per-segment numbers of intervals of a multi-segment line (empty: one cable)
    segments: tuple[int, ...] = ()
    #: sigma at the segment ends, 0 = b_0 < b_1 < ... < b_n = 1 (empty: one cable)
    bounds: tuple[float, ...] = ()
    #: sigma at every interval end, increasing from 0 to 1 (the segment ends among them);
    #: empty: uniform intervals in each segment
    edges: tuple[float, ...] = ()

    @property
    def n_intervals(self) -> int:
        """Number of intervals in all (over every segment)."""
        return sum(self.segments) if self.segments else self.intervals

    @property
    def uniform(self) -> Mesh:
        """The same mesh with uniform intervals (in each segment)."""
        return replace(self, edges=()) if self.edges else self

    def with_edges(self, edges: np.ndarray | None) -> Mesh:
        """The same numbers of intervals with interval ends ``edges`` (sigma, increasing
        from 0 to 1 through the segment ends; None: uniform)."""
        if edges is None:
            return self.uniform
        edges = np.asarray(edges, dtype=float)
        if edges.shape != (self.n_intervals + 1,) or not np.all(edges[1:] > edges[:-1]):
            raise ValueError("edges: expected n_intervals + 1 increasing values")
        return replace(self, edges=tuple(edges.tolist()))

    def interval_edges(self) -> np.ndarray:
        """sigma at every interval end (n_intervals + 1 values; read-only)."""
        return _mesh_edges(self)

    def local_widths(self) -> np.ndarray:
        """Width of every interval in its segment's own coordinate (the segment's share
        of sigma scaled to 1), in interval order: 1/N on a uniform mesh (read-only)."""
        return _local_widths(self)

    @property
    def n_nodes(self) -> int:
        """Number of state nodes (interval starts, collocation points, final point)."""
        if self.segments:
            return sum(n * (self.degree + 1) + 1 for n in self.segments)
        return self.intervals * (self.degree + 1) + 1

    def segment_offsets(self) -> list[int]:
        """Index of the first node of every segment, and the total number of nodes."""
        out = [0]
        for n in self.segments or (self.intervals,):
            out.append(out[-1] + n * (self.degree + 1) + 1)
        return out

    def sigma(self) -> np.ndarray:
        """sigma of every state node, in unknown order (not sorted for Radau: the last
        collocation point of an interval coincides with the next interval start; a joint
        between segments appears twice). A new array (computed once per mesh)."""
        return _mesh_sigma(self).copy()

    def mesh_index(self) -> np.ndarray:
        """Indices of the mesh points (interval ends) among the state nodes."""
        if self.segments:
            offs = self.segment_offsets()
            return np.concatenate([offs[k] + np.arange(n + 1) * (self.degree + 1)
                                   for k, n in enumerate(self.segments)])
        return np.arange(self.intervals + 1) * (self.degree + 1)

    @property
    def order(self) -> int:
        """Nominal convergence order at the mesh points."""
        return 2 * self.degree if self.scheme == "legendre" else 2 * self.degree - 1
