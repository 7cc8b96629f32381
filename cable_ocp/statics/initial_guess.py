"""Initial guesses for a cold solve: drag-free catenaries and straight lines.

Returned as node arrays in physical units, so they feed any transcription.

* Both ends fixed, length known: the inextensible drag-free catenary through both ends
  in their vertical plane (Irvine 1981; Huang (1992), eqs (2.31)-(2.33), with no point loads).
* Both ends fixed, tension known, length free: the catenary through both ends whose
  tension at that end equals the prescribed one; of the two such catenaries, the one
  with the shorter cable (docs/conventions.md: Berteaux's problem has a second, non-physical
  solution near 15 km).
* One end fixed, the other loaded by a known force: the drag-free hanging solution
  T(s) = T_end - w (s_end - s) e_z, integrated for the positions (Huang (1992), eqs (2.40)-(2.42)).
* Otherwise (mixed ends), or when the above degenerate: a straight line with the
  tension of a vertically hanging cable.
* An anchored end_a with seabed contact: the catenary with touchdown
  (:func:`touchdown_guess`); a towed line with bending (end_b free under a load): a
  straight line downstream (:func:`towed_guess`); a multi-segment line: the guesses of
  its mean cable (:func:`mean_cable_scene`).

The catenary formulas themselves (the parameter through two points, the vertex, the nodes,
the touchdown catenary) are those of :mod:`cable_ocp.statics.catenary`.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.optimize import brentq

from cable_ocp.physics.drag import line_drag_factors
from cable_ocp.scene import Scene
from cable_ocp.statics.catenary import (
    catenary_nodes,
    catenary_parameter,
    catenary_parameter_bracketed,
    catenary_vertex,
    touchdown_catenary,
    vertex_nodes,
)


def _plane(scene: Scene) -> tuple[np.ndarray, np.ndarray, float, float]:
    ra = np.asarray(scene.end_a.position, dtype=float)
    rb = np.asarray(scene.end_b.position, dtype=float)
    d = rb - ra
    h = math.hypot(d[0], d[1])
    eh = np.array([d[0] / h, d[1] / h, 0.0]) if h > 1e-9 else np.array([1.0, 0.0, 0.0])
    return ra, eh, h, float(d[2])


def _catenary_guess(scene: Scene, sigma: np.ndarray, length: float
                    ) -> tuple[np.ndarray, np.ndarray] | None:
    w = scene.cable.weight_in_water
    ra, eh, h, v = _plane(scene)
    if h < 1e-6 * length or abs(w) < 1e-12 or length <= math.hypot(h, v) * (1 + 1e-9):
        return None
    flip = -1.0 if w < 0 else 1.0
    a = catenary_parameter_bracketed(h, flip * v, length)
    s = sigma * length
    xs, zs, ht = catenary_nodes(a, h, flip * v, s, abs(w))
    r = ra + np.outer(xs, eh) + np.outer(flip * zs, [0, 0, 1.0])
    t = np.outer(ht[:, 0], eh) + np.outer(flip * ht[:, 1], [0, 0, 1.0])
    return r, t


def free_length_guess(scene: Scene) -> float:
    """Cable length (m) of the drag-free catenary with the prescribed end tension."""
    w = abs(scene.cable.weight_in_water)
    ra, eh, h, v = _plane(scene)
    chord = math.hypot(h, v)
    tension = scene.end_a.tension or scene.end_b.tension
    if w < 1e-12 or h < 1e-9 * chord:
        return chord * 1.01
    at_b = scene.end_b.tension is not None
    flip = -1.0 if scene.cable.weight_in_water < 0 else 1.0

    def end_tension(length: float) -> float:
        a = catenary_parameter(h, flip * v, length)
        x0 = catenary_vertex(a, h, flip * v)
        xe = h if at_b else 0.0
        return w * a * math.cosh((xe - x0) / a)

    # tension falls from infinity (taut) to a minimum as the cable lengthens; take the
    # shorter-cable branch: the first length where the tension drops to the target.
    lengths = chord * (1.0 + np.geomspace(1e-6, 50.0, 48))
    vals = np.array([end_tension(float(x)) for x in lengths])
    below = np.nonzero(vals <= tension)[0]
    if below.size == 0:
        return float(lengths[int(np.argmin(vals))])
    i = int(below[0])
    if i == 0:
        return float(lengths[0])
    return float(brentq(lambda x: end_tension(x) - tension, lengths[i - 1], lengths[i]))


def _hanging_guess(scene: Scene, sigma: np.ndarray, length: float
                   ) -> tuple[np.ndarray, np.ndarray] | None:
    """One end fully fixed, the other fully force-loaded."""
    a_fixed, b_fixed = all(scene.end_a.fixed_mask), all(scene.end_b.fixed_mask)
    w = scene.cable.weight_in_water
    fine = np.linspace(0.0, 1.0, 20 * len(sigma) + 1)
    s = fine * length
    if a_fixed and not any(scene.end_b.fixed_mask):
        tb = np.asarray(scene.end_b.force, dtype=float)
        tens = tb[None, :] - np.outer(length - s, [0, 0, w])
        start, from_a = np.asarray(scene.end_a.position, dtype=float), True
    elif b_fixed and not any(scene.end_a.fixed_mask):
        ta = -np.asarray(scene.end_a.force, dtype=float)
        tens = ta[None, :] + np.outer(s, [0, 0, w])
        start, from_a = np.asarray(scene.end_b.position, dtype=float), False
    else:
        return None
    mag = np.linalg.norm(tens, axis=1)
    if mag.min() < 1e-6 * max(mag.max(), 1e-12):
        return None
    t = tens / mag[:, None]
    disp = cumulative_trapezoid(t, s, axis=0, initial=0.0)
    r = start + disp if from_a else start - (disp[-1] - disp)
    ri = np.stack([np.interp(sigma, fine, r[:, k]) for k in range(3)], axis=1)
    ti = np.stack([np.interp(sigma, fine, tens[:, k]) for k in range(3)], axis=1)
    return ri, ti


def _straight_guess(scene: Scene, sigma: np.ndarray, length: float
                    ) -> tuple[np.ndarray, np.ndarray]:
    ea, eb = scene.end_a, scene.end_b
    pa = np.array([p if p is not None else np.nan for p in ea.position])
    pb = np.array([p if p is not None else np.nan for p in eb.position])
    for i in range(3):
        if np.isnan(pa[i]):
            pa[i] = pb[i] - length / math.sqrt(3.0)
        if np.isnan(pb[i]):
            pb[i] = pa[i] + length / math.sqrt(3.0)
    d = pb - pa
    chord = float(np.linalg.norm(d))
    e = d / chord if chord > 0 else np.array([0.0, 0.0, 1.0])
    r = pa + np.outer(sigma, d)
    w = scene.cable.weight_in_water
    tmag = max(abs(w) * length, 1.0)
    env, cab = scene.environment, scene.cable
    if env.current is not None:  # the drag scale: a weightless cable is held by drag alone
        kn = line_drag_factors(env.water_density, cab.diameter, cab.normal_drag,
                               cab.tangential_drag)[0]
        tmag = max(tmag, kn * env.current.max_speed**2 * length)
    for end in (ea, eb):
        tmag = max([tmag, *(abs(f) for f in end.force if f is not None)])
        if end.tension is not None:
            tmag = end.tension
    t = np.outer(np.ones_like(sigma), tmag * e)
    return r, t


def initial_guess(scene: Scene, sigma: np.ndarray, kind: str = "catenary"
                  ) -> tuple[np.ndarray, np.ndarray, float, str]:
    """Guess positions (n, 3) [m], tensions (n, 3) [N] and length [m] at ``sigma`` nodes.

    Returns the name of the guess actually used as the last element.

    Parameters
    ----------
    scene : Scene
        The statics scene (a single uniform cable).
    sigma : ndarray
        Node coordinates along the line, 0 at end_a and 1 at end_b.
    kind : {"catenary", "straight"}
        ``solver.initial_guess``: the drag-free catenary (or hanging line) where one
        exists, else a straight line; or the straight line.
    """
    length = scene.cable.length if scene.cable.length is not None else free_length_guess(scene)
    if kind == "catenary":
        both_fixed = all(scene.end_a.fixed_mask) and all(scene.end_b.fixed_mask)
        guess = _catenary_guess(scene, sigma, length) if both_fixed else _hanging_guess(
            scene, sigma, length)
        if guess is not None:
            return guess[0], guess[1], length, "catenary" if both_fixed else "hanging"
    r, t = _straight_guess(scene, sigma, length)
    return r, t, length, "straight"


def touchdown_guess(scene: Scene, sigma: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, float, float] | None:
    """Drag-free inextensible catenary with touchdown, for an anchored end_a.

    The cable lies straight from the anchor towards end_b's horizontal position for a
    grounded length g, then hangs as a catenary that leaves the seabed horizontally:
    with a = H/w, suspended length L_s = sqrt(h^2 + 2 h a) and span x_s = a acosh(1 + h/a)
    for a rise h; H solves L - L_s + x_s = X (the horizontal distance). Returns the
    suspended part's nodes at ``sigma`` (0 = touchdown point), the total length and g;
    None when no such catenary exists (the cable is too short to touch).

    Parameters
    ----------
    scene : Scene
        The statics scene (end_a anchored on a horizontal seabed, w > 0, length known).
    sigma : ndarray
        Node coordinates of the suspended part, 0 at touchdown and 1 at end_b.
    """
    w = scene.cable.weight_in_water
    length = scene.cable.length
    if w <= 0 or length is None:
        return None
    ra, eh, x_tot, h = _plane(scene)
    if h <= 0:
        return None
    found = touchdown_catenary(h, x_tot, length)
    if found is None:
        return None
    a, ls = found
    g = length - ls
    s = sigma * ls
    xs, zs, ht = vertex_nodes(a, s, w)
    r = ra + np.outer(g + xs, eh) + np.outer(zs, [0, 0, 1.0])
    t = np.outer(ht[:, 0], eh) + np.outer(ht[:, 1], [0, 0, 1.0])
    return r, t, length, g


def mean_cable_scene(scene: Scene) -> Scene:
    """A single-cable scene with the line's mean weight per length, the bodies' vertical
    loads spread over it (for the drag-free initial guesses of a multi-segment line)."""
    total = sum(c.length for c in scene.segments)  # type: ignore[misc]
    weight = sum(c.weight_in_water * c.length for c in scene.segments)  # type: ignore[operator]
    weight -= sum(b.static_load[2] for b in scene.bodies)
    cable = replace(scene.cable, weight_in_water=weight / total)
    return replace(scene, cable=cable, segments=(), segment_intervals=(), bodies=())


def towed_guess(scene: Scene, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Guess for a towed line (end_a fixed, end_b free under a given load, a uniform
    current in the x-z plane): a straight line from end_a downstream, sloping down at
    0.1 rad, with the tension of the tangential drag and the end load accumulated from
    end_b; in still water a line hanging straight down. None when the scene is not of
    that kind.

    Parameters
    ----------
    scene : Scene
        The statics scene (segments, ends, current).
    s : ndarray
        Unstretched arc lengths of the nodes, m.

    Returns
    -------
    tuple or None
        Positions (n, 3) in m, tension vectors (n, 3) in N and the total length in m.
    """
    cur, a, b = scene.environment.current, scene.end_a, scene.end_b
    if not all(a.fixed_mask) or any(b.fixed_mask):
        return None
    lens = [c.length for c in scene.segments]
    cum = np.concatenate([[0.0], np.cumsum(lens)])
    total = float(cum[-1])
    if cur is None or cur.max_speed == 0.0:
        # still water: the line hangs straight down from end_a, its tension the weight
        # below (a sinking line; an inverted start would land on the unstable branch)
        e = np.array([0.0, 0.0, -1.0])
        ft = [abs(c.weight_in_water) for c in scene.segments]
    else:
        rho = scene.environment.water_density
        ux = cur.ux[0] if cur.ux[0] != 0.0 else cur.max_speed
        e = np.array([math.copysign(math.cos(0.1), ux), 0.0, -math.sin(0.1)])
        # tangential drag per metre of each segment, N/m (0.5 rho C_t pi D U^2), plus the
        # weight's component along the 0.1 rad slope
        ft = [line_drag_factors(rho, c.diameter, c.normal_drag, c.tangential_drag)[1] * ux**2
              + abs(c.weight_in_water) * 0.1 for c in scene.segments]
    pull = float(np.linalg.norm([f or 0.0 for f in b.force]))

    def beyond(sv: float) -> float:
        """Drag on the line beyond arc length sv, N."""
        return sum(f * max(0.0, min(hi, total) - max(lo, sv))
                   for f, lo, hi in zip(ft, cum[:-1], cum[1:], strict=True))

    tmag = np.array([pull + beyond(float(v)) for v in s])
    tmag = np.maximum(tmag, 1e-6 * max(tmag.max(), 1.0))
    r = np.asarray(a.position, dtype=float) + np.outer(s, e)
    return r, np.outer(tmag, e), total
