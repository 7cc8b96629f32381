"""MoorPy beside cable_ocp on mooring systems without current (issue 23): the MoorPy side.

:func:`moorpy_system_from_dict` builds a MoorPy ``System`` (NREL/MoorPy 1.3.0,
``moorpy/system.py``) from a system problem dictionary (the TOML of
``problems/systems/*.toml`` as :func:`cable_ocp.scene.read_problem` returns it; schema in
docs/conventions.md, "Mooring systems"). :func:`moorpy_reference` solves its equilibrium
with MoorPy and returns what the benchmark compares: the body poses, per line the end
tensions, end forces, laid length and anchor load, the free points, the body 6x6
stiffness three ways (MoorPy's analytic matrix, MoorPy's own central differences, and
central differences of full point equilibria in small rotations about the fixed axes) and
the timings. :func:`moorpy_reference_of_system` does the same on a MoorPy ``System`` built
by MoorPy itself (its test systems), :func:`moorpy_stiffness` the three matrices at the
current pose.

Conversions (MoorPy's conventions read from ``moorpy/system.py``, ``body.py``, ``line.py``):

- z: MoorPy puts z = 0 at the free surface: ``z_moorpy = z_ours - water_depth``.
- line types: MoorPy keys ``d_vol`` (our ``diameter``), ``m`` (``mass_per_length``),
  ``EA``, ``w`` = (m - rho pi d^2 / 4) g (weight in water per length,
  :func:`cable_ocp.physics.added_mass.weight_in_water`), ``MBL``, ``Cd``, ``CdAx`` =
  C_dt (MoorPy's axial drag is on pi d as ours: ``line.py``, ``0.5*rho*CdAx*np.pi*d_vol``),
  ``Ca``, ``CaAx``.
- points: ``fixed`` -> MoorPy type 1, ``free`` -> type 0 (mass, volume, ``fExt``),
  ``body`` -> type 1 attached with ``Body.attachPoint`` at its body-frame position.
- bodies: ``free`` -> type 0 (``held`` DOFs removed from ``DOFs``), ``fixed`` -> type 1;
  ``rM`` = the given ``metacenter``, else ``center_of_buoyancy`` + (Ixx / V) e_z (MoorPy
  takes one metacenter: Ixx = Iyy is required), else the centre of buoyancy; ``f6Ext`` =
  ``force`` + ``moment``.
- a line of several parts becomes one MoorPy ``Line`` per part (MoorPy's lines are
  uniform), joined by free MoorPy points of zero mass, as MoorPy's own
  ``tests/test_system.py::test_multiseg`` does. The map from our line names to MoorPy's
  line numbers is kept on the system as ``ms.cable_ocp_lines`` (our point names:
  ``ms.cable_ocp_points``, bodies: ``ms.cable_ocp_bodies``).

Stiffness sign: K = -d[F; M]/d[x; theta], F and M the mooring lines' force and moment on
the body (MoorPy's ``lines_only=True``), M about the reference point, in N/m, N, N m/rad;
positive in surge for a stable mooring (MoorPy's own sign). The body is held (made
MoorPy's "coupled" type -1) while its matrix is taken; the free points re-equilibrate.
MoorPy's analytic matrix is ``System.getCoupledStiffnessA`` (the Guyan reduction of
``getSystemStiffnessA(DOFtype="both")`` onto the coupled DOFs, i.e. with the free points
condensed out; ``getSystemStiffnessA(DOFtype="free")`` on a free body would mix in its
hydrostatics and leave the free points uncondensed). MoorPy's central differences
(``getCoupledStiffness``) perturb its Euler angles; ours (``fd_fixed_axes``) perturb small
rotations about the fixed axes, which is the project's convention: the two agree at zero
rotation only; at a rotated pose MoorPy's is K_fixed with its rotation columns times the
Euler-rate matrix J (:func:`euler_rate_matrix`), and ``fd_moorpy_in_fixed_axes`` undoes
that. The analytic matrix is in rotations about the fixed axes.

MoorPy is imported inside the functions: it is a benchmark peer (``pip install moorpy``),
never a dependency of the library or of the default test run.
"""

from __future__ import annotations

import math
import statistics
import time
from importlib import import_module
from types import ModuleType
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.rotation import (
    euler_angles,
    euler_rate_matrix,
    rotate_small,
    rotation_matrix,
)
from cable_ocp.physics.added_mass import weight_in_water

__all__ = ["EQUILIBRIUM_TOLERANCE", "FD_ANGLE_STEP", "FD_STEP", "MAX_ITERATIONS",
           "euler_from_matrix", "euler_rate_matrix", "moorpy_reference",
           "moorpy_reference_of_system",
           "moorpy_stiffness", "moorpy_system_from_dict", "rotation_matrix"]

#: MoorPy ``solveEquilibrium(tol=...)``: absolute tolerance on the positions, m (its
#: catenary solves then run to 0.01 of it; radians for rotations, divided by the
#: fairlead radius)
EQUILIBRIUM_TOLERANCE = 1e-7
#: MoorPy ``solveEquilibrium(maxIter=...)``
MAX_ITERATIONS = 1000
#: central-difference steps: translation, m, and rotation, rad
FD_STEP = 1e-3
FD_ANGLE_STEP = 1e-5

_DOF_NAMES = ("x", "y", "z", "roll", "pitch", "yaw")


def _moorpy() -> ModuleType:
    try:
        return import_module("moorpy")
    except ImportError:
        raise CableOCPError("the MoorPy benchmark needs moorpy, which is not installed: "
                            "pip install moorpy") from None


def euler_from_matrix(r: np.ndarray) -> np.ndarray:
    """(roll, pitch, yaw), rad, of R = Rz(yaw) Ry(pitch) Rx(roll)
    (:func:`cable_ocp.numerics.rotation.euler_angles`, as an array).

    Parameters
    ----------
    r : ndarray
        A rotation matrix.
    """
    return np.array(euler_angles(r))


# --------------------------------------------------------------------------------------
# our dict -> MoorPy System
# --------------------------------------------------------------------------------------

def _num(table: dict[str, Any], key: str, where: str, default: float | None = None) -> float:
    if key not in table:
        if default is None:
            raise CableOCPError(f"{where}.{key} is missing: the MoorPy benchmark needs it")
        return default
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise CableOCPError(f"{where}.{key} = {value!r}: expected a number")
    return float(value)


def _vec(table: dict[str, Any], key: str, where: str, n: int = 3) -> np.ndarray:
    value = table.get(key, [0.0] * n)
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise CableOCPError(f"{where}.{key} = {value!r}: expected {n} numbers")
    return np.asarray(value, dtype=float)


def _line_type(name: str, table: dict[str, Any], rho: float, g: float) -> dict[str, Any]:
    """One ``[line_types.NAME]`` -> MoorPy's line-type dict."""
    where = f"line_types.{name}"
    if "standard" in table:
        try:
            lt = import_module("cable_ocp.physics.line_types")
        except ImportError:
            raise CableOCPError(f"{where}.standard = {table['standard']!r}: this build has no "
                                "standard line types; give the values") from None
        base = dict(lt.standard_line_type(table["standard"],
                                          _num(table, "nominal_diameter", where)))
        base.update({k: v for k, v in table.items() if k not in ("standard",)})
        table = base
    d = _num(table, "diameter", where)
    area = math.pi * d * d / 4.0
    if "mass_per_length" in table:
        m = _num(table, "mass_per_length", where)
        w = weight_in_water(m, area, rho, g)
    elif "weight_in_water" in table:
        w = _num(table, "weight_in_water", where)
        m = w / g + rho * area
    else:
        raise CableOCPError(f"{where}: give mass_per_length (kg/m) or weight_in_water (N/m)")
    return {"name": name, "d_vol": d, "m": m, "w": w,
            "EA": _num(table, "axial_stiffness", where),
            "MBL": _num(table, "mbl", where, 0.0),
            "Cd": _num(table, "normal_drag", where, 0.0),
            "CdAx": _num(table, "tangential_drag", where, 0.0),
            "Ca": _num(table, "added_mass", where, 0.0),
            "CaAx": _num(table, "tangential_added_mass", where, 0.0),
            "cost": _num(table, "cost_per_length", where, 0.0),
            "EAd": 0.0, "EAd_Lm": 0.0, "material": str(table.get("standard", name))}


def _metacenter(body: dict[str, Any], where: str) -> np.ndarray:
    if "metacenter" in body:
        return _vec(body, "metacenter", where)
    cb = _vec(body, "center_of_buoyancy", where)
    if "waterplane_moments" in body:
        ixx, iyy = (float(v) for v in _vec(body, "waterplane_moments", where, 2))
        if not math.isclose(ixx, iyy, rel_tol=1e-12):
            raise CableOCPError(f"{where}.waterplane_moments = {[ixx, iyy]}: MoorPy takes one "
                                "metacenter, so Ixx must equal Iyy; give metacenter instead")
        volume = _num(body, "volume", where, 0.0)
        if volume <= 0.0:
            raise CableOCPError(f"{where}.volume = {volume}: waterplane_moments need a "
                                "positive displaced volume (m^3)")
        return cb + np.array([0.0, 0.0, ixx / volume])
    return cb


def _parts(line: dict[str, Any], where: str) -> list[tuple[str, float]]:
    if "parts" in line:
        parts = line["parts"]
        if not isinstance(parts, list) or not parts:
            raise CableOCPError(f"{where}.parts = {parts!r}: expected a non-empty list of "
                                "{type, length} tables")
        return [(str(p["type"]), _num(p, "length", f"{where}.parts")) for p in parts]
    return [(str(line["type"]), _num(line, "length", where))]


def moorpy_system_from_dict(data: dict[str, Any]) -> Any:
    """A MoorPy ``System`` from a system problem dictionary (the module docstring lists the
    conversions).

    Parameters
    ----------
    data : dict
        The problem file as :func:`cable_ocp.scene.read_problem` returns it: ``[environment]``,
        ``[line_types.*]``, ``[[points]]``, ``[[bodies]]``, ``[[lines]]``; z with the seabed
        at 0 (m).

    Returns
    -------
    moorpy.System
        Initialized (``ms.initialize()``), not yet in equilibrium. ``ms.cable_ocp_lines``
        maps our line names to MoorPy line numbers (1-based, from point_a to point_b),
        ``ms.cable_ocp_points`` and ``ms.cable_ocp_bodies`` our point and body names to
        MoorPy numbers.

    Raises
    ------
    CableOCPError
        moorpy not installed; a current given (the comparison is without current); a key
        missing or of the wrong kind; a ``hydrostatic_matrix`` (MoorPy has none).
    """
    mp = _moorpy()
    env = data.get("environment", {})
    depth = _num(env, "water_depth", "environment")
    rho = _num(env, "water_density", "environment", 1025.0)
    g = _num(env, "gravity", "environment", 9.81)
    current = env.get("current")
    if current and any(float(v) != 0.0 for k, v in current.items()
                       if k in ("speed", "velocity") and not isinstance(v, list)):
        raise CableOCPError("environment.current: the MoorPy benchmark runs without current "
                            "(MoorPy's statics has none here); remove [environment.current]")
    friction = _num(env.get("seabed", {}), "friction", "environment.seabed", 0.0)
    shift = np.array([0.0, 0.0, depth])

    ms = mp.System(depth=depth, rho=rho, g=g)
    for name, table in data.get("line_types", {}).items():
        ms.lineTypes[name] = _line_type(name, table, rho, g)

    bodies: dict[str, int] = {}
    poses: dict[str, np.ndarray] = {}
    for i, b in enumerate(data.get("bodies", [])):
        where = f"bodies[{i}]"
        name = str(b.get("name", f"body{i + 1}"))
        if "hydrostatic_matrix" in b:
            raise CableOCPError(f"{where}.hydrostatic_matrix: MoorPy has no linear hydrostatic "
                                "matrix; give volume, waterplane_area and a metacenter")
        kind = b.get("kind", "free")
        if kind not in ("free", "fixed"):
            raise CableOCPError(f"{where}.kind = {kind!r}: expected 'free' or 'fixed'")
        held = list(b.get("held", []))
        bad = [h for h in held if h not in _DOF_NAMES]
        if bad:
            raise CableOCPError(f"{where}.held = {held!r}: each one of {list(_DOF_NAMES)}")
        r6 = np.concatenate([_vec(b, "position", where) - shift,
                             np.radians(_vec(b, "rotation_deg", where))])
        dofs = [k for k, n in enumerate(_DOF_NAMES) if n not in held]
        body = ms.addBody(0 if kind == "free" else 1, r6, m=_num(b, "mass", where, 0.0),
                          v=_num(b, "volume", where, 0.0),
                          rCG=_vec(b, "center_of_gravity", where),
                          AWP=_num(b, "waterplane_area", where, 0.0),
                          rM=_metacenter(b, where),
                          f6Ext=np.concatenate([_vec(b, "force", where),
                                                _vec(b, "moment", where)]),
                          DOFs=dofs)
        bodies[name] = body.number
        poses[name] = r6

    points: dict[str, int] = {}
    start: dict[str, np.ndarray] = {}   # initial global positions, MoorPy frame
    for i, p in enumerate(data.get("points", [])):
        where = f"points[{i}]"
        name = str(p["name"])
        kind = p.get("kind")
        pos = _vec(p, "position", where)
        if kind == "fixed":
            pt = ms.addPoint(1, pos - shift)
            start[name] = pos - shift
        elif kind == "free":
            pt = ms.addPoint(0, pos - shift, m=_num(p, "mass", where, 0.0),
                             v=_num(p, "volume", where, 0.0), fExt=_vec(p, "force", where))
            start[name] = pos - shift
        elif kind == "body":
            bname = str(p.get("body"))
            if bname not in bodies:
                raise CableOCPError(f"{where}.body = {bname!r}: not one of {list(bodies)}")
            r6 = poses[bname]
            glob = r6[:3] + rotation_matrix(*r6[3:]) @ pos
            pt = ms.addPoint(1, glob)
            ms.bodyList[bodies[bname] - 1].attachPoint(pt.number, pos)
            start[name] = glob
        else:
            raise CableOCPError(f"{where}.kind = {kind!r}: expected 'fixed', 'free' or 'body'")
        points[name] = pt.number

    lines: dict[str, list[int]] = {}
    for i, ln in enumerate(data.get("lines", [])):
        where = f"lines[{i}]"
        name = str(ln["name"])
        a, b = str(ln["point_a"]), str(ln["point_b"])
        for key, pname in (("point_a", a), ("point_b", b)):
            if pname not in points:
                raise CableOCPError(f"{where}.{key} = {pname!r}: not one of {list(points)}")
        parts = _parts(ln, where)
        for tname, _ in parts:
            if tname not in ms.lineTypes:
                raise CableOCPError(f"{where}: part type {tname!r} is not one of the "
                                    f"[line_types] {list(ms.lineTypes)}")
        total = sum(length for _, length in parts)
        ends = [points[a]]
        s = 0.0
        for _, length in parts[:-1]:     # zero-mass joints, first guess on the chord
            s += length
            guess = start[a] + (s / total) * (start[b] - start[a])
            ends.append(ms.addPoint(0, guess).number)
        ends.append(points[b])
        lines[name] = [ms.addLine(length, tname, pointA=ends[k], pointB=ends[k + 1],
                                  cb=friction).number
                       for k, (tname, length) in enumerate(parts)]
    ms.initialize()
    ms.cable_ocp_lines = lines
    ms.cable_ocp_points = points
    ms.cable_ocp_bodies = bodies
    return ms


# --------------------------------------------------------------------------------------
# equilibrium, stiffness, timings
# --------------------------------------------------------------------------------------

def _hold_bodies(ms: Any) -> list[tuple[int, list[int], int]]:
    saved = [(b.type, list(b.DOFs), b.nDOF) for b in ms.bodyList]
    for b in ms.bodyList:
        b.type, b.DOFs, b.nDOF = -1, [0, 1, 2, 3, 4, 5], 6
    return saved


def _release_bodies(ms: Any, saved: list[tuple[int, list[int], int]]) -> None:
    for b, (t, dofs, n) in zip(ms.bodyList, saved, strict=True):
        b.type, b.DOFs, b.nDOF = t, dofs, n


def _solve_points(ms: Any, tol: float) -> None:
    if ms.getDOFs()[0] > 0:
        ms.solveEquilibrium(DOFtype="free", tol=tol, maxIter=MAX_ITERATIONS)
    else:
        ms.mooringEq(ms.getPositions(DOFtype="free"), DOFtype="free", tol=0.01 * tol)


def _body_forces(ms: Any) -> np.ndarray:
    return np.concatenate([b.getForces(lines_only=True) for b in ms.bodyList])


def _fd_fixed_axes(ms: Any, dx: float, dth: float, tol: float) -> np.ndarray:
    """-d[F; M]/d[x; theta] by central differences of full point equilibria, theta small
    rotations about the fixed axes (R -> Rot(theta) R), bodies held."""
    n = 6 * len(ms.bodyList)
    k = np.zeros((n, n))
    base = [np.array(b.r6, dtype=float) for b in ms.bodyList]
    for j in range(n):
        ib, dof = divmod(j, 6)
        f = []
        for sign in (1.0, -1.0):
            r6 = base[ib].copy()
            if dof < 3:
                r6[dof] += sign * dx
            else:
                axis = np.zeros(3)
                axis[dof - 3] = sign * dth
                rot = rotate_small(axis, rotation_matrix(*r6[3:]))
                r6[3:] = euler_from_matrix(rot)
            ms.bodyList[ib].setPosition(r6)
            _solve_points(ms, tol)
            f.append(_body_forces(ms))
        ms.bodyList[ib].setPosition(base[ib])
        k[:, j] = -(f[0] - f[1]) / (2.0 * (dx if dof < 3 else dth))
    _solve_points(ms, tol)
    return k


def _timed(fn: Any, repeats: int) -> tuple[Any, float]:
    times, out = [], None
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, statistics.median(times)


def moorpy_stiffness(ms: Any, *, dx: float = FD_STEP, dth: float = FD_ANGLE_STEP,
                     tol: float = EQUILIBRIUM_TOLERANCE, repeats: int = 1) -> dict[str, Any]:
    """The bodies' 6x6 mooring stiffness at their current poses, three ways.

    The bodies are held (MoorPy type -1) and the free points re-equilibrated first; the
    bodies' types and DOFs are restored after.

    Parameters
    ----------
    ms : moorpy.System
        With at least one body.
    dx : float
        Central-difference translation step, m.
    dth : float
        Central-difference rotation step, rad.
    tol : float
        MoorPy's equilibrium tolerance for the free points, m.
    repeats : int
        Runs of each for the median wall time.

    Returns
    -------
    dict
        ``analytic`` (``getCoupledStiffnessA(lines_only=True)``), ``fd_moorpy``
        (``getCoupledStiffness(dx, dth, lines_only=True)``: MoorPy's central differences,
        in its Euler angles), ``fd_fixed_axes`` (central differences of full point
        equilibria, small rotations about the fixed axes): 6n x 6n lists, N/m, N, N m/rad,
        sign K = -d[F; M]/d[x; theta]; ``fd_moorpy_in_fixed_axes``: ``fd_moorpy`` with its
        rotation columns times J^-1 (:func:`euler_rate_matrix`); ``analytic_vs_fd``,
        ``moorpy_fd_vs_fd``, ``analytic_vs_moorpy_fd``, ``moorpy_fd_in_fixed_axes_vs_fd``:
        the largest |difference| over the largest |entry| of the second matrix per 3x3
        block (``xx``, ``x_theta``, ``theta_x``, ``theta_theta``), and
        ``all_over_diagonal``: max |K_ij - R_ij| / sqrt(|R_ii R_jj|); ``time_s``: median
        wall times, s.
    """
    saved = _hold_bodies(ms)
    try:
        _solve_points(ms, tol)
        base = [np.array(b.r6, dtype=float) for b in ms.bodyList]
        ka, t_a = _timed(lambda: ms.getCoupledStiffnessA(lines_only=True), repeats)

        def moorpy_fd() -> np.ndarray:
            k = ms.getCoupledStiffness(dx=dx, dth=dth, lines_only=True)
            for b, r6 in zip(ms.bodyList, base, strict=True):
                b.setPosition(r6)
            _solve_points(ms, tol)
            return k

        km, t_m = _timed(moorpy_fd, repeats)
        kf, t_f = _timed(lambda: _fd_fixed_axes(ms, dx, dth, tol), repeats)
    finally:
        _release_bodies(ms, saved)
    ka, km = np.asarray(ka, dtype=float), np.asarray(km, dtype=float)
    km_fixed = km.copy()   # MoorPy's differences taken back to rotations about fixed axes
    for ib, r6 in enumerate(base):
        cols = slice(6 * ib + 3, 6 * ib + 6)
        km_fixed[:, cols] = km[:, cols] @ np.linalg.inv(euler_rate_matrix(*r6[3:]))
    return {"sign": "K = -d[F; M]/d[x; theta], lines only, positive in surge",
            "analytic": ka.tolist(), "fd_moorpy": km.tolist(), "fd_fixed_axes": kf.tolist(),
            "analytic_vs_fd": _block_errors(ka, kf), "moorpy_fd_vs_fd": _block_errors(km, kf),
            "analytic_vs_moorpy_fd": _block_errors(ka, km),
            "fd_moorpy_in_fixed_axes": km_fixed.tolist(),
            "moorpy_fd_in_fixed_axes_vs_fd": _block_errors(km_fixed, kf),
            "time_s": {"analytic": t_a, "fd_moorpy": t_m, "fd_fixed_axes": t_f}}


def _block_errors(k: np.ndarray, ref: np.ndarray) -> dict[str, float]:
    out = {}
    for key, (r, c) in {"xx": (0, 0), "x_theta": (0, 3), "theta_x": (3, 0),
                        "theta_theta": (3, 3)}.items():
        a, b = k[r:r + 3, c:c + 3], ref[r:r + 3, c:c + 3]
        out[key] = float(np.max(np.abs(a - b)) / max(float(np.max(np.abs(b))), 1e-300))
    out["all_over_diagonal"] = float(np.max(np.abs(k - ref) / np.sqrt(np.outer(
        np.abs(np.diag(ref)), np.abs(np.diag(ref))) + 1e-300)))
    return out


def _line_result(ms: Any, numbers: list[int], depth: float) -> dict[str, Any]:
    first, last = ms.lineList[numbers[0] - 1], ms.lineList[numbers[-1] - 1]
    ends = []
    for line, end in ((first, 0), (last, 1)):
        # the point at this end: MoorPy's attachments are [pointA, pointB]
        ends.append(ms.pointList[line.attached[end] - 1] if hasattr(line, "attached")
                    else None)
    out = {"moorpy_lines": list(numbers),
           "tension_a_N": float(first.TA), "tension_b_N": float(last.TB),
           "force_on_a_N": np.asarray(first.fA, dtype=float).tolist(),
           "force_on_b_N": np.asarray(last.fB, dtype=float).tolist(),
           "laid_length_m": float(sum(ms.lineList[n - 1].LBot for n in numbers))}
    for label, pt, f in (("a", ends[0], first.fA), ("b", ends[1], last.fB)):
        if (pt is not None and pt.type == 1 and not _on_body(ms, pt.number)
                and "anchor_end" not in out):
            out["anchor_end"] = label
            out["anchor_horizontal_N"] = float(np.hypot(f[0], f[1]))
            out["anchor_vertical_N"] = float(f[2])
    return out


def _on_body(ms: Any, number: int) -> bool:
    return any(number in b.attachedP for b in ms.bodyList)


def moorpy_reference_of_system(ms: Any, repeats: int = 5, *,
                               tol: float = EQUILIBRIUM_TOLERANCE,
                               stiffness: bool = True) -> dict[str, Any]:
    """Equilibrium, line results, stiffness and timings of a MoorPy ``System``.

    Parameters
    ----------
    ms : moorpy.System
        Initialized; ``ms.cable_ocp_lines`` / ``cable_ocp_points`` / ``cable_ocp_bodies``
        when built by :func:`moorpy_system_from_dict`, else MoorPy's numbering is used
        (``line1``, ``point1``, ``body1``...).
    repeats : int
        Runs for each median wall time.
    tol : float
        ``solveEquilibrium(tol=...)``, m.
    stiffness : bool
        Also the 6x6 matrices (:func:`moorpy_stiffness`), when there is a body.

    Returns
    -------
    dict
        ``converged``; ``bodies``: name -> ``position_m`` (our frame, z from the seabed) and
        ``rotation_deg``; ``lines``: name -> tensions at a and b (N), the forces the line
        exerts on its end points (N, global axes), ``laid_length_m`` (MoorPy ``LBot``
        summed over the parts), at an anchor ``anchor_horizontal_N`` and
        ``anchor_vertical_N`` (the line's pull on it, up positive); ``points``: name ->
        position (our frame, m); ``stiffness`` (:func:`moorpy_stiffness`); ``time_s``:
        median wall time of ``solveEquilibrium`` from the same start.
    """
    depth = float(ms.depth)
    shift = np.array([0.0, 0.0, depth])
    lines = getattr(ms, "cable_ocp_lines", {f"line{ln.number}": [ln.number]
                                            for ln in ms.lineList})
    points = getattr(ms, "cable_ocp_points", {f"point{p.number}": p.number
                                              for p in ms.pointList})
    bodies = getattr(ms, "cable_ocp_bodies", {f"body{b.number}": b.number
                                              for b in ms.bodyList})
    x0 = np.array(ms.getPositions(DOFtype="free"), dtype=float)

    def solve() -> bool:
        if x0.size:
            ms.setPositions(x0, DOFtype="free")
        return bool(ms.solveEquilibrium(DOFtype="free", tol=tol, maxIter=MAX_ITERATIONS))

    converged, t_eq = _timed(solve, repeats)
    out: dict[str, Any] = {"converged": converged, "tolerance_m": tol,
                           "free_dofs": int(x0.size)}
    out["bodies"] = {name: {"position_m": (ms.bodyList[n - 1].r6[:3] + shift).tolist(),
                            "rotation_deg": np.degrees(ms.bodyList[n - 1].r6[3:]).tolist(),
                            "mooring_force_N": ms.bodyList[n - 1].getForces(
                                lines_only=True).tolist()}
                     for name, n in bodies.items()}
    out["lines"] = {name: _line_result(ms, nums, depth) for name, nums in lines.items()}
    out["points"] = {name: (np.asarray(ms.pointList[n - 1].r) + shift).tolist()
                     for name, n in points.items()}
    out["time_s"] = {"solve_equilibrium": t_eq}
    if stiffness and ms.bodyList:
        out["stiffness"] = moorpy_stiffness(ms, tol=tol, repeats=repeats)
    return out


def moorpy_reference(data: dict[str, Any], repeats: int = 5) -> dict[str, Any]:
    """MoorPy's answer on a system problem dictionary: :func:`moorpy_system_from_dict`
    then :func:`moorpy_reference_of_system` (its keys; units there).

    Parameters
    ----------
    data : dict
        The system problem (our frame, SI).
    repeats : int
        Runs for each median wall time.
    """
    return moorpy_reference_of_system(moorpy_system_from_dict(data), repeats)
