"""An independent static-cable reference for the tests: single shooting with scipy.

Written from the equations, sharing no code with ``cable_ocp``: it reads the problem's raw
TOML tables itself (no scene parser), writes the loads in numpy (no CasADi, no smoothing of
the modulus, no vertical blend) and solves the two-point boundary-value problem by shooting
from end_a with ``scipy.integrate.solve_ivp`` (DOP853, rtol :data:`RTOL`) and
``scipy.optimize.root``.

Equations (unstretched arc length s from end_a, s = 0, to end_b, s = L; z up, seabed z = 0):

    dr/ds = (1 + |T|/EA) T/|T|
    dT/ds = -f,   f = (0, 0, -w) + (1 + |T|/EA) f_drag(U(z), t)       (per unstretched length)

``f_drag`` per stretched length (Huang (1992), eqs (2.46)-(2.47); Wang, Cheong &
Chucheepsakul (1993), eqs (4)-(6)):

* vector law: ``1/2 rho D (C_n |U_n| U_n + C_t pi |U_t| U_t)``, ``U_t = (U.t) t``,
  ``U_n = U - U_t``;
* componentwise law: the normal flow split along ``e_b = z x t / |z x t|`` and
  ``e_n = t x e_b``, each component squared with its own sign.

The current is uniform, or a profile ``[[z, speed, heading_deg], ...]`` interpolated linearly
in its velocity components between knots and constant outside them.

End conditions per component: a prescribed position, or a prescribed external load ``F`` on
the attachment, i.e. ``T(0) = -F`` at end_a and ``T(L) = +F`` at end_b; ``tension`` at an end
makes L an unknown. Seabed contact (a plane ``z = tan(alpha) (x cos beta + y sin beta)``
through the origin, rising towards the heading beta): the cable lies straight on it from the
anchor (end_a) for a grounded length g, along a direction e in the plane; the tension drops
by ``k = w e_z + mu w n_z`` per metre (the weight's component along the line plus axial
friction on the normal reaction) from the touchdown point towards the anchor (zero where it
would go negative); it lifts off tangentially (T parallel to e); the suspended part is shot
from the touchdown point.
"""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import root

FREE = "free"
#: relative tolerance of the integration (DOP853)
RTOL = 1e-11


def _vec(value: list | None) -> list[float | None]:
    if value is None:
        return [None, None, None]
    return [None if isinstance(v, str) else float(v) for v in value]


@dataclass
class RawProblem:
    """The inputs of a single-cable problem, read from its TOML tables."""

    rho: float
    current: tuple[np.ndarray, np.ndarray, np.ndarray] | None  # knots z, ux, uy
    friction: float | None  # None: no seabed contact modelled
    slope: tuple[float, float]  # seabed slope and the heading it rises towards, rad
    length: float | None  # None: free length
    diameter: float
    w: float
    ea: float
    cn: float
    ct: float
    law: str
    pos_a: list[float | None]
    frc_a: list[float | None]
    pos_b: list[float | None]
    frc_b: list[float | None]
    tension_a: float | None
    tension_b: float | None


def read_problem(path: Path | str, overrides: dict | None = None) -> RawProblem:
    """Read a problem file. ``overrides`` maps dotted keys (``"layout.psi0_deg"``) to values."""
    with open(path, "rb") as fh:
        return problem_from_dict(tomllib.load(fh), overrides)


def problem_from_dict(data: dict, overrides: dict | None = None) -> RawProblem:
    """The same from the problem's tables as a dict (TOML layout)."""
    data = copy.deepcopy(data)
    for key, val in (overrides or {}).items():
        node = data
        *head, last = key.split(".")
        for k in head:
            node = node.setdefault(k, {})
        node[last] = val
    env = data["environment"]
    cur = env.get("current")
    current = None
    if cur is not None:
        rows = cur.get("profile") or [[0.0, cur["speed"], cur.get("heading_deg", 0.0)]]
        rows = sorted(rows, key=lambda r: r[0])
        z = np.array([r[0] for r in rows], dtype=float)
        ux = np.array([r[1] * math.cos(math.radians(r[2])) for r in rows])
        uy = np.array([r[1] * math.sin(math.radians(r[2])) for r in rows])
        current = (z, ux, uy)
    seabed = env.get("seabed")
    friction = None
    slope = (0.0, 0.0)
    if seabed is not None:
        assert seabed.get("depth_offset", 0.0) == 0.0
        friction = float(seabed.get("friction", 0.0))
        slope = (math.radians(seabed.get("slope_deg", 0.0)),
                 math.radians(seabed.get("slope_heading_deg", 0.0)))
    cab = data["cable"]
    length = None if cab["length"] == FREE else float(cab["length"])
    ea = cab.get("axial_stiffness", math.inf)
    ea = math.inf if isinstance(ea, str) else float(ea)
    a, b = data["end_a"], data["end_b"]
    pos_b = _vec(b.get("position"))
    psi = data.get("layout", {}).get("psi0_deg")
    pos_a = _vec(a.get("position"))
    if psi is not None:  # Wang et al. (1993), eq. (28): end_b rotated about end_a's vertical
        rad = math.hypot(pos_b[0] - pos_a[0], pos_b[1] - pos_a[1])
        pos_b = [pos_a[0] + rad * math.cos(math.radians(psi)),
                 pos_a[1] + rad * math.sin(math.radians(psi)), pos_b[2]]
    return RawProblem(
        rho=float(env["water_density"]), current=current, friction=friction, slope=slope,
        length=length,
        diameter=float(cab.get("diameter", 0.0)), w=float(cab["weight_in_water"]), ea=ea,
        cn=float(cab.get("normal_drag", 0.0)), ct=float(cab.get("tangential_drag", 0.0)),
        law=cab.get("drag_law", "vector"), pos_a=pos_a, frc_a=_vec(a.get("force")),
        pos_b=pos_b, frc_b=_vec(b.get("force")), tension_a=a.get("tension"),
        tension_b=b.get("tension"))


@dataclass
class Reference:
    """Result of :func:`shoot`. The force the cable exerts on the end_a attachment is
    ``tension_a`` (= T(0)), on the end_b attachment ``-tension_b`` (= -T(L))."""

    tension_a: np.ndarray  # T at end_a (the anchor, s = 0), N
    tension_b: np.ndarray  # T at end_b (s = L), N
    length: float  # unstretched, m
    grounded_length: float  # m
    s: np.ndarray  # suspended part, m
    r: np.ndarray  # (n, 3), m
    t: np.ndarray  # (n, 3), N
    residual: float  # largest scaled residual of the shooting equations
    dense: object = None  # solve_ivp dense output on the suspended part (local arc length)

    def at(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Position (n, 3), m, and tension vector (n, 3), N, at arc lengths s >= g, m."""
        y = self.dense(np.asarray(s, dtype=float) - self.grounded_length)
        return y[:3].T, y[3:].T


def _current(p: RawProblem, z: float) -> tuple[float, float]:
    """Horizontal current (u_x, u_y) at height z, m/s."""
    zk, ux, uy = p.current
    if len(zk) == 1:
        return float(ux[0]), float(uy[0])
    return float(np.interp(z, zk, ux)), float(np.interp(z, zk, uy))


def _drag(p: RawProblem, ux: float, uy: float, t: tuple[float, float, float]
          ) -> tuple[float, float, float]:
    """Drag per stretched length, N/m (exact moduli; the current is horizontal)."""
    tx, ty, tz = t
    ut = ux * tx + uy * ty
    k = 0.5 * p.rho * p.diameter
    kt = k * p.ct * math.pi * abs(ut) * ut
    if p.law == "vector":
        nx, ny, nz = ux - ut * tx, uy - ut * ty, -ut * tz
        kn = k * p.cn * math.sqrt(nx * nx + ny * ny + nz * nz)
        return kn * nx + kt * tx, kn * ny + kt * ty, kn * nz + kt * tz
    sb = math.hypot(tx, ty)  # |e_z x t|
    assert sb > 1e-2, "componentwise law: cable within 0.57 deg of vertical (basis undefined)"
    eb = (-ty / sb, tx / sb, 0.0)  # e_z x t / |e_z x t|
    en = (ty * eb[2] - tz * eb[1], tz * eb[0] - tx * eb[2], tx * eb[1] - ty * eb[0])  # t x e_b
    cb = ux * eb[0] + uy * eb[1]
    cn = ux * en[0] + uy * en[1]
    kb, kn = k * p.cn * abs(cb) * cb, k * p.cn * abs(cn) * cn
    return (kb * eb[0] + kn * en[0] + kt * tx, kb * eb[1] + kn * en[1] + kt * ty,
            kn * en[2] + kt * tz)


def _rhs(p: RawProblem):  # noqa: ANN202
    inv_ea = 0.0 if math.isinf(p.ea) else 1.0 / p.ea
    w = p.w
    with_drag = p.current is not None

    def f(_s: float, y: np.ndarray) -> list[float]:
        _, _, z, t1, t2, t3 = y.tolist()
        tm = math.sqrt(t1 * t1 + t2 * t2 + t3 * t3)
        t = (t1 / tm, t2 / tm, t3 / tm)
        st = 1.0 + tm * inv_ea
        fx, fy, fz = 0.0, 0.0, -w
        if with_drag:
            dx, dy, dz = _drag(p, *_current(p, z), t)
            fx, fy, fz = fx + st * dx, fy + st * dy, fz + st * dz
        return [st * t[0], st * t[1], st * t[2], -fx, -fy, -fz]

    return f


def _integrate(p: RawProblem, y0: np.ndarray, length: float, dense: bool = False):  # noqa: ANN202
    return solve_ivp(_rhs(p), (0.0, length), y0, method="DOP853", rtol=RTOL,
                     atol=RTOL * max(1.0, float(np.max(np.abs(y0)))), dense_output=dense)


def _seabed_line(p: RawProblem, heading: float) -> tuple[np.ndarray, float]:
    """Unit vector in the seabed plane whose horizontal part points at ``heading`` (rad), and
    the tension drop per metre k (N/m) along it."""
    alpha, beta = p.slope
    tan_a = math.tan(alpha)
    e = np.array([math.cos(heading), math.sin(heading),
                  tan_a * (math.cos(heading) * math.cos(beta)
                           + math.sin(heading) * math.sin(beta))])
    e /= np.linalg.norm(e)
    n_z = 1.0 / math.sqrt(1.0 + tan_a**2)  # vertical component of the plane's unit normal
    return e, p.w * e[2] + p.friction * p.w * n_z


def _grounded(p: RawProblem, g: float, h: float, k: float) -> tuple[float, float]:
    """Stretched distance anchor -> touchdown and the anchor tension of a grounded length g
    (m) with touchdown tension h (N) and drop k (N/m): T(s') = max(h - k (g - s'), 0)."""
    g_t = g if k <= 0 else min(g, h / k)  # length that carries tension
    integral = h * g_t - 0.5 * k * g_t**2
    dist = g + (0.0 if math.isinf(p.ea) else integral / p.ea)
    return dist, max(h - k * g, 0.0)


def shoot(p: RawProblem, t0_guess: np.ndarray, *, r0_guess: np.ndarray | None = None,
          length_guess: float | None = None, grounded_guess: float | None = None,
          n_profile: int = 201) -> Reference:
    """Solve the BVP by single shooting from end_a.

    Unknowns: ``T(0)`` components where end_a's position is fixed, ``r(0)`` components where
    its force is given, L when it is free. With ``grounded_guess`` (a seabed scene whose
    cable lies on the seabed at end_a): the grounded length g, the touchdown tension and its
    heading instead of ``T(0)``. The guesses only start Newton's method (``root``, hybr);
    the residual is checked at the end.
    """
    lscale = p.length or float(np.linalg.norm(np.subtract(p.pos_b, p.pos_a)))
    fscale = float(np.linalg.norm(t0_guess))
    fixed_a = [v is not None for v in p.pos_a]
    grounded = grounded_guess is not None
    free_len = p.length is None

    def unpack(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, float]:
        x = list(x)
        if grounded:
            g, h, head = x[0] * lscale, x[1] * fscale, x[2]
            e, k = _seabed_line(p, head)
            dist, _ = _grounded(p, g, h, k)
            r0 = np.array(p.pos_a) + dist * e
            t0 = h * e
            x = x[3:]
        else:
            g = 0.0
            r0 = np.array([v if v is not None else 0.0 for v in p.pos_a])
            t0 = np.zeros(3)
            for i in range(3):
                if fixed_a[i]:
                    t0[i] = x.pop(0) * fscale
                else:
                    r0[i] = x.pop(0) * lscale
                    t0[i] = -p.frc_a[i]
        length = x.pop(0) * lscale if free_len else p.length
        return r0, t0, length, g

    def residual(x: np.ndarray) -> np.ndarray:
        r0, t0, length, g = unpack(x)
        y = _integrate(p, np.concatenate([r0, t0]), length - g).y[:, -1]
        res = []
        for i in range(3):
            if p.pos_b[i] is not None:
                res.append((y[i] - p.pos_b[i]) / lscale)
            else:
                res.append((y[3 + i] - p.frc_b[i]) / fscale)
        if p.tension_b is not None:
            res.append((np.linalg.norm(y[3:]) - p.tension_b) / fscale)
        if p.tension_a is not None:
            res.append((np.linalg.norm(t0) - p.tension_a) / fscale)
        return np.array(res)

    if grounded:
        t0g = np.asarray(t0_guess, dtype=float)
        x0 = [grounded_guess / lscale, np.linalg.norm(t0g) / fscale,
              math.atan2(t0g[1], t0g[0])]
    else:
        x0 = []
        for i in range(3):
            x0.append(t0_guess[i] / fscale if fixed_a[i] else r0_guess[i] / lscale)
    if free_len:
        x0.append(length_guess / lscale)
    sol = root(residual, np.array(x0), method="hybr", options={"xtol": 1e-13})
    res = float(np.max(np.abs(residual(sol.x))))
    r0, t0, length, g = unpack(sol.x)
    ivp = _integrate(p, np.concatenate([r0, t0]), length - g, dense=True)
    ss = np.linspace(0.0, length - g, n_profile)
    ys = ivp.sol(ss)
    t_anchor = t0
    if grounded:
        e, k = _seabed_line(p, math.atan2(t0[1], t0[0]))
        _, ta = _grounded(p, g, float(np.linalg.norm(t0)), k)
        t_anchor = ta * t0 / np.linalg.norm(t0)
    return Reference(tension_a=t_anchor, tension_b=ys[3:, -1], length=length,
                     grounded_length=g, s=g + ss, r=ys[:3].T, t=ys[3:].T, residual=res,
                     dense=ivp.sol)
