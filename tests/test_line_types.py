"""Standard line types (physics/line_types.py) against MoorPy's getLineProps and by hand."""

from __future__ import annotations

import math

import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.physics import drag
from cable_ocp.physics.line_types import (
    ALIASES,
    STANDARDS,
    LineProps,
    standard_line_type,
)

#: our name -> MoorPy's material name in MoorProps_default.yaml
MOORPY_NAME = {"studless_chain": "chain", "studlink_chain": "chain_studlink",
               "wire_rope": "wire", "polyester": "polyester", "nylon": "nylon", "hmpe": "hmpe"}
CANONICAL = tuple(MOORPY_NAME)


def test_standards_are_the_canonical_names_then_moorpys() -> None:
    assert STANDARDS == (*CANONICAL, "chain", "chain_studlink", "wire")
    assert ALIASES == {"chain": "studless_chain", "chain_studlink": "studlink_chain",
                       "wire": "wire_rope"}
    assert standard_line_type("chain", 0.1) == standard_line_type("studless_chain", 0.1)


@pytest.mark.parametrize("standard", CANONICAL)
def test_equals_moorpys_getlineprops(standard: str) -> None:
    """Same formulas on the same coefficients: equal to rounding (1e-12 relative; the sums
    are in the same order, a few ulps at most)."""
    helpers = pytest.importorskip("moorpy.helpers")
    table = helpers.loadLineProps("default")
    for d in (0.02, 0.1, 0.25):
        ours = standard_line_type(standard, d)
        mp = helpers.getLineProps(d * 1000.0, MOORPY_NAME[standard], lineProps=table)
        pairs = {"diameter": "d_vol", "mass_per_length": "m", "axial_stiffness": "EA",
                 "mbl": "MBL", "cost_per_length": "cost", "normal_drag": "Cd",
                 "tangential_drag": "CdAx", "added_mass": "Ca", "tangential_added_mass": "CaAx",
                 "nominal_diameter": "d_nom"}
        for field, key in pairs.items():
            assert getattr(ours, field) == pytest.approx(mp[key], rel=1e-12, abs=0.0), \
                (standard, d, field)


def test_studless_chain_by_hand() -> None:
    """MoorProps_default.yaml lineProps.chain at d = 0.1 m, by hand:
    mass 20.0e3 * 0.01 = 200 kg/m (0.0200 d_mm^2 kg/m: 0.02 * 100^2);
    MBL -2.19e9 * 1e-3 + 1.21e9 * 1e-2 + 911 * 0.1 = -2.19e6 + 12.1e6 + 91.1 = 9 910 091.1 N;
    EA -3.93e7 * 1e-3 + 85.6e9 * 1e-2 = -39 300 + 856e6 = 855 960 700 N;
    cost 2.585 $/kg * 200 kg/m = 517 $/m; d_vol 1.80 * 0.1 = 0.18 m.
    Tolerance 1e-12: a few roundings of sums of exact-ish decimals."""
    p = standard_line_type("studless_chain", 0.1)
    assert p.mass_per_length == pytest.approx(200.0, rel=1e-12)
    assert p.mass_per_length == pytest.approx(0.0200 * 100.0**2, rel=1e-12)
    assert p.mbl == pytest.approx(9_910_091.1, rel=1e-12)
    assert p.axial_stiffness == pytest.approx(855_960_700.0, rel=1e-12)
    assert p.cost_per_length == pytest.approx(517.0, rel=1e-12)
    assert p.diameter == pytest.approx(0.18, rel=1e-12)
    assert (p.normal_drag, p.tangential_drag, p.added_mass, p.tangential_added_mass) == \
        (1.333, 0.639, 1.0, 0.5)
    assert "MoorProps_default.yaml lineProps.chain" in p.source


def test_fibre_rope_by_hand() -> None:
    """lineProps.polyester at 0.2 m: MBL 308e6 * 0.04 = 12.32e6 N, EA = 14 MBL = 172.48e6 N,
    cost 2.3e-5 * MBL = 283.36 $/m; nylon at 0.2 m: MBL 230e6 * 0.008 + 207e6 * 0.04
    = 1.84e6 + 8.28e6 = 10.12e6 N, EA = 5 MBL = 50.6e6 N (1e-12: rounding only)."""
    p = standard_line_type("polyester", 0.2)
    assert p.mbl == pytest.approx(12.32e6, rel=1e-12)
    assert p.axial_stiffness == pytest.approx(172.48e6, rel=1e-12)
    assert p.cost_per_length == pytest.approx(283.36, rel=1e-12)
    n = standard_line_type("nylon", 0.2)
    assert n.mbl == pytest.approx(10.12e6, rel=1e-12)
    assert n.axial_stiffness == pytest.approx(50.6e6, rel=1e-12)


@pytest.mark.parametrize("standard,density", [("studless_chain", 7850.0),
                                              ("studlink_chain", 7850.0),
                                              ("wire_rope", 4875.5)])
def test_metal_volume_diameter_is_the_density_one(standard: str, density: float) -> None:
    """The yaml's dvol_dnom (1.80, 1.89, 1.18) "assumes" 7850 kg/m^3 steel (4875.5 for wire):
    m = density pi d_vol^2 / 4 gives d_vol/d = sqrt(4 mass_d2 / (pi density)) = 1.8011,
    1.8847, 1.1757. Tolerance 0.5 %: the yaml's 2-decimal ratios are 0.06 %, 0.28 % and
    0.37 % above these (studlink's 1.89 is not the rounding of 1.8847, which is 1.88); a
    wrong ratio or density (1.9, steel for wire) is off by >= 0.8 %."""
    p = standard_line_type(standard, 0.1)
    d_vol = math.sqrt(4 * p.mass_per_length / (math.pi * density))
    assert p.diameter == pytest.approx(d_vol, rel=5e-3)


@pytest.mark.parametrize("standard,density", [("polyester", 1380.0), ("nylon", 1140.0),
                                              ("hmpe", 975.0)])
def test_fibre_volume_diameter_holds_the_density_exactly(standard: str, density: float) -> None:
    """Fibre ropes: d_vol from the yaml's density, so the displaced mass rho_fibre pi
    d_vol^2 / 4 is the mass per length (1e-12: one sqrt and its square)."""
    for d in (0.05, 0.2):
        p = standard_line_type(standard, d)
        assert density * math.pi * p.diameter**2 / 4 == pytest.approx(p.mass_per_length,
                                                                      rel=1e-12)


def test_tangential_drag_is_cdax_on_the_perimeter() -> None:
    """MoorPy's current load (line.py: 0.5 rho CdAx pi d_vol |U_q| U_q) and MoorDyn's
    tangential drag (Line.cpp: Cdt pi d) put CdAx on pi d, which is our C_t on pi D: the
    yaml's Cd_ax = 0.639 (studless) is our tangential_drag unchanged, and the axial force
    per length from our drag law equals MoorPy's expression (1e-12: same product)."""
    p = standard_line_type("studless_chain", 0.12)
    assert p.tangential_drag == 0.639
    rho, u = 1025.0, 0.7
    moorpy_force = 0.5 * rho * 0.639 * math.pi * p.diameter * u * u
    _, k_t = drag.line_drag_factors(rho, p.diameter, p.normal_drag, p.tangential_drag)
    assert k_t * u * u == pytest.approx(moorpy_force, rel=1e-12)


def test_lineprops_is_frozen() -> None:
    p = standard_line_type("hmpe", 0.1)
    assert isinstance(p, LineProps)
    with pytest.raises(AttributeError):
        p.mbl = 0.0  # type: ignore[misc]


def test_unknown_standard_lists_the_valid_ones() -> None:
    with pytest.raises(CableOCPError) as err:
        standard_line_type("wire6", 0.1)
    msg = str(err.value)
    assert "'wire6'" in msg
    for name in (*CANONICAL, *ALIASES):
        assert repr(name) in msg


@pytest.mark.parametrize("bad", [0.0, -0.1, math.nan, math.inf, 2.0, 1e-4, "0.1", None, True])
def test_bad_diameter_says_metres_and_range(bad: object) -> None:
    with pytest.raises(CableOCPError) as err:
        standard_line_type("polyester", bad)  # type: ignore[arg-type]
    msg = str(err.value)
    assert "nominal_diameter" in msg and repr(bad) in msg
    assert "in m" in msg and "0.01-0.3 m" in msg


def test_a_diameter_in_mm_is_named() -> None:
    with pytest.raises(CableOCPError, match=r"mm\? 76 mm = 0.076 m"):
        standard_line_type("chain", 76)
