"""Standard mooring line types from a nominal diameter: MoorPy's property scaling laws.

The laws and coefficients are MoorPy's (v1.3.0): ``moorpy/helpers.py`` ``getLineProps``
(the formulas) and ``loadLineProps`` (the defaults of missing coefficients), with the
coefficient table ``moorpy/library/MoorProps_default.yaml`` (``lineProps``). With d the
nominal diameter in m (MoorPy's ``getLineProps`` takes it in mm, ``dnommm``, and divides by
1000 before every formula; its coefficients are per m), the yaml keys give

* mass per length  m = ``mass_d2`` d^2  (kg/m, in air);
* MBL = ``MBL_0`` + ``MBL_d`` d + ``MBL_d2`` d^2 + ``MBL_d3`` d^3  (N);
* EA = ``EA_0`` + ``EA_d`` d + ``EA_d2`` d^2 + ``EA_d3`` d^3 + ``EA_MBL`` MBL  (N, the
  quasi-static stiffness; MoorPy's dynamic ``EAd_MBL``, ``EAD_LM`` are not used here);
* cost = ``cost_0`` + ``cost_d`` d + ``cost_d2`` d^2 + ``cost_d3`` d^3 + ``cost_mass`` m
  + ``cost_EA`` EA + ``cost_MBL`` MBL  (per m, in the yaml's "$": the default table states
  no price year);
* volume-equivalent diameter d_vol = ``dvol_dnom`` d, or, where the table gives a material
  ``density`` instead, ``dvol_dnom`` = sqrt(``mass_d2`` / ``density`` 4 / pi), so that
  m = density pi d_vol^2 / 4;
* ``Cd``, ``Cd_ax``, ``Ca``, ``Ca_ax`` as given; a key missing from the table is 0
  (``loadLineProps``'s default; ``dvol_dnom``'s default is 1).

The yaml's comments say the chain EA coefficients are taken from DNV-OS-E301 (2013), the drag
coefficients are "based on DNV-OS-E301 adjusted for use with volumetric diameter", and the
added-mass coefficients are based on Bureau Veritas NR 493 (2021-07). Chain coefficients are
for R4 grade.

Drag conventions: ``Cd`` acts on the volume-equivalent diameter (MoorPy ``line.py`` current
load ``0.5 rho Cd d_vol``) as our ``normal_drag`` does. ``Cd_ax`` acts on the perimeter
pi d_vol: MoorPy's current load (``line.py``: ``0.5*rho*CdAx*np.pi*d_vol``) and MoorDyn
(``source/Line.cpp``, tangential drag ``Cdt * pi * d``) both multiply it by pi, which is our
``tangential_drag`` convention (``physics/drag.py``: 1/2 rho C_t pi D), so C_dt = ``Cd_ax``
with no conversion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cable_ocp.errors import CableOCPError


@dataclass(frozen=True)
class LineProps:
    """The properties of one standard line type at one nominal diameter.

    Attributes
    ----------
    material : str
        The standard's name (one of the canonical names of :data:`STANDARDS`).
    nominal_diameter : float
        Nominal diameter, m.
    diameter : float
        Volume-equivalent diameter, m (MoorPy's ``d_vol``, MoorDyn's ``Diam``).
    mass_per_length : float
        Mass per length in air, kg/m.
    axial_stiffness : float
        EA, N: the quasi-static stiffness MoorPy uses.
    mbl : float
        Minimum breaking load, N.
    normal_drag : float
        C_dn (-), on the diameter (MoorPy and MoorDyn ``Cd``).
    tangential_drag : float
        C_dt (-), on the perimeter pi * diameter (MoorPy and MoorDyn ``CdAx``, which both
        apply on pi d: equal).
    added_mass : float
        C_an (-) (MoorPy ``Ca``).
    tangential_added_mass : float
        C_at (-) (MoorPy ``CaAx``).
    cost_per_length : float
        Cost per length, "$"/m of MoorPy's default table (no price year stated there).
    source : str
        One line: where the coefficients come from.
    """

    material: str
    nominal_diameter: float
    diameter: float
    mass_per_length: float
    axial_stiffness: float
    mbl: float
    normal_drag: float
    tangential_drag: float
    added_mass: float
    tangential_added_mass: float
    cost_per_length: float
    source: str


#: MoorProps_default.yaml ``lineProps``, key for key (SI, d in m); {our name: (yaml name, coefs)}
_TABLE: dict[str, tuple[str, dict[str, float]]] = {
    "studless_chain": ("chain", {  # R4 grade studless chain
        "mass_d2": 20.0e3, "EA_d3": -3.93e7, "EA_d2": 85.6e9,
        "MBL_d3": -2.19e9, "MBL_d2": 1.21e9, "MBL_d": 9.11e2, "dvol_dnom": 1.80,
        "cost_mass": 2.585, "Cd": 1.333, "Cd_ax": 0.639, "Ca": 1.0, "Ca_ax": 0.5}),
    "studlink_chain": ("chain_studlink", {  # R4 grade studlink chain
        "mass_d2": 21.9e3, "EA_d2": 88.0e9,
        "MBL_d3": -2.19e9, "MBL_d2": 1.21e9, "MBL_d": 9.11e2, "dvol_dnom": 1.89,
        "cost_mass": 2.585, "Cd": 1.376, "Cd_ax": 0.741, "Ca": 1.0, "Ca_ax": 0.5}),
    "wire_rope": ("wire", {
        "mass_d2": 5293.0, "dvol_dnom": 1.18, "MBL_d2": 1022e6, "EA_d2": 97.1e9,
        "Cd": 1.021, "cost_MBL": 1.2e-05}),
    "polyester": ("polyester", {
        "mass_d2": 679.0, "MBL_d2": 308e6, "EA_MBL": 14.0, "density": 1380.0,
        "cost_MBL": 2.3e-05, "Cd": 2.021, "Ca": 1.1, "Ca_ax": 0.15}),
    "nylon": ("nylon", {
        "mass_d2": 585.0, "MBL_d3": 230e6, "MBL_d2": 207e6, "EA_MBL": 5.0, "density": 1140.0,
        "cost_MBL": 4.29e-05, "Cd": 1.979, "Ca": 1.1, "Ca_ax": 0.15}),
    "hmpe": ("hmpe", {
        "mass_d2": 496.0, "MBL_d3": 651e6, "MBL_d2": 580e6, "EA_MBL": 56.0, "density": 975.0,
        "Cd": 1.988, "Ca": 1.1, "Ca_ax": 0.15, "cost_MBL": 1.4e-04}),
}

#: MoorPy's own material names, accepted as aliases
ALIASES: dict[str, str] = {yaml: ours for ours, (yaml, _) in _TABLE.items() if yaml != ours}

#: every accepted name: the canonical names, then MoorPy's names for them
STANDARDS: tuple[str, ...] = (*_TABLE, *ALIASES)

#: accepted nominal diameters, m (beyond 0.5 m MoorPy's chain MBL cubic turns down to 0)
DIAMETER_RANGE: tuple[float, float] = (0.001, 0.5)

_SOURCE = ("MoorPy 1.3.0 moorpy/library/MoorProps_default.yaml lineProps.{key} with "
           "moorpy/helpers.py getLineProps")


def _canonical(standard: str) -> str:
    """Our name of ``standard`` (a canonical name or a MoorPy alias)."""
    if isinstance(standard, str):
        key = standard.strip().lower()
        if key in _TABLE:
            return key
        if key in ALIASES:
            return ALIASES[key]
    names = ", ".join(repr(s) for s in _TABLE)
    aliases = ", ".join(f"{a!r} -> {c!r}" for a, c in ALIASES.items())
    raise CableOCPError(f"line type standard = {standard!r} is unknown; valid: {names} "
                        f"(MoorPy's names also accepted: {aliases})")


def _checked_diameter(nominal_diameter: float) -> float:
    """``nominal_diameter`` as a float in :data:`DIAMETER_RANGE`, else a CableOCPError."""
    lo, hi = DIAMETER_RANGE
    ok = isinstance(nominal_diameter, (int, float)) and not isinstance(nominal_diameter, bool)
    d = float(nominal_diameter) if ok else math.nan
    if not (lo <= d <= hi):
        hint = ""
        if ok and hi < d <= 1000 * hi:
            hint = f" (a value in mm? {d:g} mm = {d / 1000:g} m)"
        raise CableOCPError(
            f"line type nominal_diameter = {nominal_diameter!r} is invalid: it is in m, "
            f"between {lo:g} and {hi:g} m (typical mooring lines: 0.01-0.3 m){hint}")
    return d


def standard_line_type(standard: str, nominal_diameter: float) -> LineProps:
    """The properties of a standard line type at a nominal diameter (MoorPy's laws).

    Parameters
    ----------
    standard : str
        One of :data:`STANDARDS`: "studless_chain" (alias "chain"), "studlink_chain"
        ("chain_studlink"), "wire_rope" ("wire"), "polyester", "nylon", "hmpe".
    nominal_diameter : float
        Nominal diameter, m (0.001-0.5 m accepted; typical 0.01-0.3 m).

    Returns
    -------
    LineProps
        Every property of the type; the formulas are those of the module docstring
        (MoorPy ``helpers.py`` ``getLineProps`` on ``MoorProps_default.yaml``).

    Raises
    ------
    CableOCPError
        An unknown standard (the message lists the valid ones) or a diameter outside
        0.001-0.5 m (e.g. one given in mm).
    """
    name = _canonical(standard)
    d = _checked_diameter(nominal_diameter)
    yaml_key, coefs = _TABLE[name]

    def c(key: str) -> float:
        return coefs.get(key, 0.0)

    mass = c("mass_d2") * d**2
    mbl = c("MBL_0") + c("MBL_d") * d + c("MBL_d2") * d**2 + c("MBL_d3") * d**3
    ea = c("EA_0") + c("EA_d") * d + c("EA_d2") * d**2 + c("EA_d3") * d**3 + c("EA_MBL") * mbl
    cost = (c("cost_0") + c("cost_d") * d + c("cost_d2") * d**2 + c("cost_d3") * d**3
            + c("cost_mass") * mass + c("cost_EA") * ea + c("cost_MBL") * mbl)
    if "density" in coefs:
        dvol_dnom = math.sqrt((c("mass_d2") / c("density")) * (4 / math.pi))
    else:
        dvol_dnom = coefs.get("dvol_dnom", 1.0)
    return LineProps(material=name, nominal_diameter=d, diameter=dvol_dnom * d,
                     mass_per_length=mass, axial_stiffness=ea, mbl=mbl,
                     normal_drag=c("Cd"), tangential_drag=c("Cd_ax"), added_mass=c("Ca"),
                     tangential_added_mass=c("Ca_ax"), cost_per_length=cost,
                     source=_SOURCE.format(key=yaml_key))
