"""The inverse problem of Huang (1992), section 6.4 (2): the cable and unit parameters that give
an identified design model ``a``, ``b``.

004 6.4 (2): "The system identification method allows the determination of a and b provided
that the particulars of cable and subsea unit are given. The reverse problem demands the
ability to specify all particulars of the cable/subsea unit system once a and b are
prescribed."

**The forward map** (:func:`design_coefficients`). The identification (6.2.3,
:mod:`cable_ocp.heave.identify_cable`) is a simulation and a fit; what it finds is, to the
accuracy docs/heave.md measures (``a`` within 0.3 % of ``1 / omega_1^2`` for every excitation,
``b`` of (6.3) within 5 %), the first axial mode of the line with the unit as a tip mass:

* ``M = m + m_a`` (unit mass and added mass in heave), ``mu`` the cable's mass per length (with
  its tangential added mass), ``L`` the length, ``EA`` the axial stiffness;
* ``beta tan beta = mu L / M`` (the rod fixed at the moving top, the tip mass at the unit),
  ``omega_1 = (beta / L) sqrt(EA / mu)`` and **a = 1 / omega_1^2** (s^2);
* the mode ``phi(s) = sin(beta s / L) / sin(beta)`` (1 at the unit), its modal mass
  ``M_1 = M + mu int phi^2 ds`` and stiffness ``K_1 = M_1 omega_1^2``;
* the quadratic drag projected on the mode: the unit's ``0.5 rho C_d A`` and the line's
  tangential ``0.5 rho C_t pi d int phi^3 ds`` (:func:`cable_ocp.physics.drag.body_drag_factor`,
  :func:`~cable_ocp.physics.drag.line_drag_factors`), and **b_q = c_q / K_1** (s^2/m), the
  ``b`` of (6.3);
* the linear ``b`` of (6.2) is not a property of the system alone: it is the equivalent linear
  damping of that drag at the unit's velocity, ``sqrt(8 / pi) sigma_v c_q`` for a Gaussian
  velocity of standard deviation ``sigma_v`` (m/s), which must then be given (docs/heave.md:
  the identified linear ``b`` varies fivefold between excitations), plus the line's material
  damping ``T = EA e + c e'`` on the mode, ``c int phi'^2 ds``; over ``K_1``:
  ``b = (c int phi'^2 ds + sqrt(8 / pi) sigma_v c_q) / K_1`` (s).

(6.3) has no linear term: where the material damping is not small against the drag (the 113 m
line of 6.3.6 at its 0.17 m excitation), the identification lumps it into ``b_q`` and the map's
``b_q`` is low (docs/heave.md).

**The inverse** (:func:`solve_parameters`): given data (``a``, and ``b_quadratic`` or ``b``
with ``velocity_std``), the chosen unknowns among :data:`PARAMETERS` and every other parameter
known, Gauss-Newton (Levenberg-Marquardt, :func:`scipy.optimize.least_squares`) on the
logarithms of the unknowns (they are positive), on the relative residuals of the data.
Identifiability is checked before and after: more unknowns than data raise
:class:`NotIdentifiableError`; so does a Jacobian of rank below the number of unknowns
(parameters that enter only in a combination, e.g. ``unit_mass`` and ``added_mass``, which
enter only as their sum ``M``), naming the unknowns. A solve that does not reach the data
returns its status ``"failed"`` with the residual, never a solution.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy import optimize

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.drag import body_drag_factor, line_drag_factors
from cable_ocp.scene.heave import INVERSE_UNKNOWNS

__all__ = ["DATA", "PARAMETERS", "InverseResult", "LineParameters", "NotIdentifiableError",
           "design_coefficients", "from_dynamic_scene", "solve_parameters"]

#: the parameters that can be unknowns (attributes of :class:`LineParameters`)
PARAMETERS = INVERSE_UNKNOWNS
#: the data that can be given
DATA = ("a", "b_quadratic", "b")

#: relative residual below which the data are reached
TOLERANCE = 1e-9
#: smallest singular value of the scaled Jacobian, relative to the largest, of an
#: identifiable set of unknowns
RANK_TOLERANCE = 1e-6


class NotIdentifiableError(CableOCPError):
    """The data do not determine the unknowns (too few data, or unknowns that enter only in a
    combination); the message names them."""


@dataclass(frozen=True)
class LineParameters:
    """The particulars of a line and unit (SI).

    Attributes
    ----------
    length : float
        Unstretched length, m.
    axial_stiffness : float
        EA, N.
    mass_per_length : float
        Mass per length (with its tangential added mass), kg/m.
    unit_mass, added_mass : float
        Unit mass and its added mass in heave, kg.
    unit_drag : float
        The unit's drag coefficient times its projected area ``C_d A``, m^2.
    tangential_drag : float
        The line's tangential drag coefficient ``C_t`` (on ``pi d``), -.
    diameter : float
        Cable diameter, m.
    axial_damping : float
        The line's material damping ``c`` of ``T = EA e + c e'``, N s.
    water_density : float
        kg/m^3.
    """

    length: float
    axial_stiffness: float
    mass_per_length: float
    unit_mass: float
    added_mass: float = 0.0
    unit_drag: float = 0.0
    tangential_drag: float = 0.0
    diameter: float = 0.0
    axial_damping: float = 0.0
    water_density: float = 1025.0

    def as_dict(self) -> dict[str, float]:
        """Every parameter by name."""
        return {k: float(getattr(self, k)) for k in self.__dataclass_fields__}


def from_dynamic_scene(scene: Any) -> LineParameters:
    """The parameters of a dynamics scene's line (one segment) and unit (its heave axis).

    Parameters
    ----------
    scene : cable_ocp.scene.dynamics.DynamicScene
        The cable scene (e.g. ``problems/dynamics/huang_6_2_6.toml``).
    """
    st = scene.statics
    if len(scene.cable) != 1 or st.segments:
        raise CableOCPError("the inverse problem takes a line of one segment; this scene has "
                            f"{max(len(scene.cable), len(st.segments or ()))}")
    seg, u, c = scene.cable[0], scene.unit, st.cable
    rho = st.environment.water_density
    mu = seg.mass_per_length + seg.tangential_added_mass_coefficient * rho * math.pi \
        * c.diameter**2 / 4.0
    return LineParameters(length=float(scene.length), axial_stiffness=c.axial_stiffness,
                          mass_per_length=mu, unit_mass=u.mass, added_mass=u.added_mass[2],
                          unit_drag=u.drag_coefficient[2] * u.drag_area[2],
                          tangential_drag=c.tangential_drag, diameter=c.diameter,
                          axial_damping=seg.axial_damping, water_density=rho)


def _beta(ratio: float) -> float:
    """The root in (0, pi/2) of ``beta tan beta = ratio`` (``ratio = mu L / M > 0``)."""
    f = lambda x: x * math.tan(x) - ratio  # noqa: E731
    hi = math.pi / 2 * (1.0 - 1e-15)
    return float(optimize.brentq(f, 0.0, hi, xtol=1e-15, rtol=1e-15, maxiter=200))


def design_coefficients(p: LineParameters, velocity_std: float | None = None
                        ) -> dict[str, float]:
    """The forward map (module docstring): ``a`` (s^2), ``b_quadratic`` (s^2/m), ``omega_1``
    (rad/s), ``b_material`` (s, the material damping's part of the linear ``b``), and with
    ``velocity_std`` (m/s) the linear ``b`` (s).

    Parameters
    ----------
    p : LineParameters
        The line and unit.
    velocity_std : float, optional
        The unit's velocity standard deviation for the linear ``b``, m/s.
    """
    for k in ("length", "axial_stiffness", "mass_per_length", "unit_mass"):
        if not getattr(p, k) > 0:
            raise CableOCPError(f"{k} = {getattr(p, k)!r}: must be > 0")
    L, mu = p.length, p.mass_per_length
    M = p.unit_mass + p.added_mass
    beta = _beta(mu * L / M)
    w1 = beta / L * math.sqrt(p.axial_stiffness / mu)
    sb = math.sin(beta)
    int_phi2 = L * (1.0 - math.sin(2 * beta) / (2 * beta)) / (2 * sb**2)
    int_phi3 = L * (2.0 / 3.0 - math.cos(beta) + math.cos(beta) ** 3 / 3.0) / (beta * sb**3)
    K1 = (M + mu * int_phi2) * w1**2
    _, kt = line_drag_factors(p.water_density, p.diameter, 0.0, p.tangential_drag)
    cq = body_drag_factor(p.water_density, 1.0, p.unit_drag) + kt * int_phi3
    int_dphi2 = beta**2 * (1.0 + math.sin(2 * beta) / (2 * beta)) / (2 * L * sb**2)
    b_mat = p.axial_damping * int_dphi2 / K1
    out = {"a": 1.0 / w1**2, "b_quadratic": cq / K1, "omega_1": w1, "b_material": b_mat}
    if velocity_std is not None:
        out["b"] = b_mat + math.sqrt(8.0 / math.pi) * velocity_std * out["b_quadratic"]
    return out


@dataclass(frozen=True)
class InverseResult:
    """The parameters found for given data.

    Attributes
    ----------
    status : str
        ``"solved"`` (the data reached to :data:`TOLERANCE`) or ``"failed"``.
    message : str
        What happened.
    parameters : LineParameters
        The parameters (the unknowns as found; meaningful only when solved).
    unknowns : dict
        The unknowns' values by name (SI).
    data, achieved : dict
        The data given and the forward map's values at the parameters.
    relative_residual : float
        Largest ``|achieved / data - 1|``.
    singular_values : numpy.ndarray
        Of the Jacobian of the relative data in the log-unknowns at the solution.
    iterations : int
        Function evaluations of the solver.
    """

    status: str
    message: str
    parameters: LineParameters
    unknowns: dict
    data: dict
    achieved: dict
    relative_residual: float
    singular_values: np.ndarray = field(repr=False)
    iterations: int

    def as_json(self) -> dict[str, Any]:
        """The result as JSON-ready values."""
        return {"status": self.status, "message": self.message, "unknowns": self.unknowns,
                "parameters": self.parameters.as_dict(), "data": self.data,
                "achieved": self.achieved, "relative_residual": self.relative_residual,
                "singular_values": [float(s) for s in self.singular_values],
                "iterations": self.iterations}


def _check(data: dict[str, float], unknowns: tuple[str, ...], velocity_std: float | None
           ) -> None:
    for k in data:
        if k not in DATA:
            raise CableOCPError(f"datum {k!r} is unknown; valid: {', '.join(DATA)}")
        if not (math.isfinite(data[k]) and data[k] > 0):
            raise CableOCPError(f"{k} = {data[k]!r}: must be finite and > 0")
    if "b" in data and velocity_std is None:
        raise CableOCPError("the linear b of (6.2) needs velocity_std (m/s, the unit's "
                            "velocity standard deviation): b = b_material + sqrt(8/pi) "
                            "sigma_v b_q")
    if "b" in data and "b_quadratic" in data:
        raise CableOCPError("give b or b_quadratic, not both: with velocity_std one follows "
                            "from the other")
    for k in unknowns:
        if k not in PARAMETERS:
            raise CableOCPError(f"unknown {k!r} is not a parameter; valid: "
                                f"{', '.join(PARAMETERS)}")
    if len(set(unknowns)) != len(unknowns):
        raise CableOCPError(f"unknowns {list(unknowns)}: each may be named once")
    if not unknowns:
        raise CableOCPError("no unknowns given; name one or more of " + ", ".join(PARAMETERS))
    if len(unknowns) > len(data):
        raise NotIdentifiableError(
            f"{len(unknowns)} unknowns ({', '.join(unknowns)}) from {len(data)} datum/data "
            f"({', '.join(data)}): not identifiable; fix {len(unknowns) - len(data)} of them "
            "(give their values) or give more data")


def solve_parameters(data: dict[str, float], unknowns: tuple[str, ...] | list[str],
                     known: LineParameters, *, velocity_std: float | None = None
                     ) -> InverseResult:
    """The unknowns that give the data, every other parameter as ``known`` (module docstring).

    Parameters
    ----------
    data : dict
        ``{"a": s^2, "b_quadratic": s^2/m}``, or ``"b"`` (s) with ``velocity_std``.
    unknowns : sequence of str
        Names among :data:`PARAMETERS`; their values in ``known`` are the starting guess.
    known : LineParameters
        The known parameters and the guess of the unknowns.
    velocity_std : float, optional
        The unit's velocity standard deviation for a linear ``b``, m/s.

    Raises
    ------
    NotIdentifiableError
        More unknowns than data, or unknowns the data cannot separate (rank-deficient
        Jacobian).
    """
    data = {k: float(v) for k, v in data.items()}
    unknowns = tuple(unknowns)
    _check(data, unknowns, velocity_std)
    keys = tuple(data)
    target = np.array([data[k] for k in keys])
    x0 = np.array([getattr(known, k) for k in unknowns], dtype=float)
    if not np.all(x0 > 0):
        raise CableOCPError("the guess of every unknown must be > 0: "
                            + ", ".join(f"{k} = {v!r}" for k, v in zip(unknowns, x0, strict=True)))

    def params(y: np.ndarray) -> LineParameters:
        return replace(known, **{k: float(v) for k, v in zip(unknowns, np.exp(y), strict=True)})

    def resid(y: np.ndarray) -> np.ndarray:
        d = design_coefficients(params(y), velocity_std)
        return np.array([d[k] for k in keys]) / target - 1.0

    def singular(y: np.ndarray) -> np.ndarray:
        J = _jacobian(resid, y)
        return np.linalg.svd(J, compute_uv=False)

    y0 = np.log(x0)
    _rank_or_raise(singular(y0), unknowns, keys, "at the guess")
    sol = optimize.least_squares(resid, y0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
    p = params(sol.x)
    sv = singular(sol.x)
    _rank_or_raise(sv, unknowns, keys, "at the solution")
    ach = design_coefficients(p, velocity_std)
    achieved = {k: ach[k] for k in keys}
    res = float(np.max(np.abs(resid(sol.x))))
    ok = res <= TOLERANCE
    msg = (f"the data reached to {res:.2g} (relative)" if ok else
           f"no parameters reach the data: the closest leave a relative residual {res:.3g} "
           f"(> {TOLERANCE:g}); the unknowns stopped at the values given")
    return InverseResult("solved" if ok else "failed", msg, p,
                         {k: float(getattr(p, k)) for k in unknowns}, data, achieved, res, sv,
                         int(sol.nfev))


def _jacobian(f: Any, y: np.ndarray) -> np.ndarray:
    """Central differences in the log-unknowns (step 1e-6: the map is smooth, its values to
    ~1e-15, so the error is ~1e-10)."""
    h = 1e-6
    cols = []
    for i in range(y.size):
        e = np.zeros_like(y)
        e[i] = h
        cols.append((f(y + e) - f(y - e)) / (2 * h))
    return np.column_stack(cols)


def _rank_or_raise(sv: np.ndarray, unknowns: tuple[str, ...], keys: tuple[str, ...],
                   where: str) -> None:
    if sv.size < len(unknowns) or sv[-1] <= RANK_TOLERANCE * sv[0]:
        raise NotIdentifiableError(
            f"the data ({', '.join(keys)}) do not separate the unknowns "
            f"({', '.join(unknowns)}) {where}: the Jacobian's singular values "
            f"{', '.join(f'{s:.3g}' for s in sv)} (rank < {len(unknowns)}): they enter only "
            "in a combination" + (" (unit_mass and added_mass only as their sum M)"
                                  if {"unit_mass", "added_mass"} <= set(unknowns) else "")
            + "; fix one of them")
