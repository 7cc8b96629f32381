"""What mooring engineers read first (docs/statics.md, "Outputs" and "Line stiffness").

Checks, each against an independent result:

* end angles: Wang, Cheong & Chucheepsakul (1993), Table 1 ("Present study": 36.3 deg at
  Berteaux's anchor, 90.2 deg at the buoy), and the closed-form catenary's end angles
  atan(V/H), also for a line turned about z and for the same line given from the other end;
* the stiffness K[i][j] = dF_i/dx_j at the fixed ends: against the elastic catenary's
  closed-form flexibility (its span equations, differentiated by hand below), and against
  central finite differences of full nonlinear solves on a 2D catenary, on De Zoysa's
  line in 3D current at psi0 = 90 deg, on a multi-segment mooring with seabed contact,
  clump and buoy, and on Berteaux's free-length line (its length then held);
* the JSON fields (strict JSON, null where a value does not exist) and the summary rows
  (a unit in every row, '-' for a missing value).

Finite differences: step h = 0.01 m, compared to 1e-5 of the largest |K|. The central
difference's truncation error is h^2/6 |d^3F/dx^3|: measured on these scenes it is
1.5e-3 to 2.6e-3 of max|K| at h = 1 m and falls as h^2 (1.5e-5 .. 2.6e-5 at 0.1 m), so
about 3e-7 at 0.01 m. The solves stop at a scaled residual below solver.tolerance = 1e-10:
a force error of at most ~1e-10 of the force scale (1e4 .. 1e6 N), i.e. below 5e-3 N/m
after dividing by 2h, which is below 1e-5 of max|K| on every scene here (max|K| >= 38
N/m). Both errors sit 30x below the tolerance; a wrong term, sign or held quantity shows
at the percent level.
"""

from __future__ import annotations

import copy
import io
import json
import math
from contextlib import redirect_stdout
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import fsolve

from cable_ocp.cli import main
from cable_ocp.report import statics_summary
from cable_ocp.scene import load_scene, scene_from_dict
from cable_ocp.statics.solver import StaticsSolver, solve

FD_STEP = 0.01  # m
FD_RTOL = 1e-5  # of max|K|; see the module docstring

# an elastic catenary in still water, no seabed: anchor (end_a) 20 m above z = 0, fairlead
# (end_b) 400 m away and 100 m higher; the line dips below the anchor (V_a < 0)
W, L, EA = 500.0, 430.0, 1.0e8  # N/m, m, N
X, Z = 400.0, 100.0  # m
CATENARY = {
    "environment": {"water_depth": 150.0, "water_density": 1025.0, "gravity": 9.81},
    "cable": {"length": L, "diameter": 0.1, "weight_in_water": W, "axial_stiffness": EA},
    "end_a": {"position": [0.0, 0.0, 20.0]},
    "end_b": {"position": [X, 0.0, 20.0 + Z]},
}


# -- independent references ---------------------------------------------------------------

def elastic_catenary() -> tuple[float, float, float]:
    """Horizontal tension H and vertical tension components V_a, V_b (N, positive up) at
    the ends of the elastic catenary CATENARY (Irvine 1981, Cable Structures, ch. 1):

        x = H L/EA + (H/w) [asinh(V_b/H) - asinh(V_a/H)]
        z = L (V_a + V_b) / (2 EA) + (sqrt(H^2 + V_b^2) - sqrt(H^2 + V_a^2)) / w

    with V_a = V_b - w L, solved for (H, V_b)."""
    def span(v: np.ndarray) -> np.ndarray:
        h, vb = v
        va = vb - W * L
        x = h * L / EA + h / W * (math.asinh(vb / h) - math.asinh(va / h))
        z = L * (va + vb) / (2 * EA) + (math.hypot(h, vb) - math.hypot(h, va)) / W
        return np.array([x - X, z - Z])

    h, vb = fsolve(span, [1e5, 0.7 * W * L], xtol=1e-14)
    assert np.max(np.abs(span(np.array([h, vb])))) < 1e-9
    return float(h), float(vb - W * L), float(vb)


def catenary_stiffness() -> np.ndarray:
    """dF_b/dx_b (N/m) of CATENARY in closed form. The flexibility J = d(x, z)/d(H, V_b)
    at fixed L, by hand from the span equations above (S = sqrt(H^2 + V^2)):

        dx/dH   = L/EA + [asinh(V_b/H) - asinh(V_a/H) - V_b/S_b + V_a/S_a] / w
        dx/dV_b = (H/w) (1/S_b - 1/S_a)  =  dz/dH
        dz/dV_b = L/EA + (V_b/S_b - V_a/S_a) / w

    The force on the fairlead is F_b = (-H, 0, -V_b), so dF_b/d(x, z) = -J^-1. Out of
    the plane, a sideways step dy turns the line about the anchor: F_y = -H dy / X."""
    h, va, vb = elastic_catenary()
    sa, sb = math.hypot(h, va), math.hypot(h, vb)
    jac = np.array([
        [L / EA + (math.asinh(vb / h) - math.asinh(va / h) - vb / sb + va / sa) / W,
         h / W * (1 / sb - 1 / sa)],
        [h / W * (1 / sb - 1 / sa), L / EA + (vb / sb - va / sa) / W]])
    kxz = -np.linalg.inv(jac)
    return np.array([[kxz[0, 0], 0.0, kxz[0, 1]],
                     [0.0, -h / X, 0.0],
                     [kxz[1, 0], 0.0, kxz[1, 1]]])


def fd_stiffness(solver: StaticsSolver, scene, base, end: str, columns=(0, 1, 2)
                 ) -> np.ndarray:
    """Central differences of full Newton solves (warm-started from ``base``) with the
    position of ``end`` moved by +-FD_STEP along each axis in ``columns`` (NaN elsewhere)."""
    attr = f"end_{end}"
    k = np.full((3, 3), math.nan)
    for j in columns:
        forces = []
        for sign in (1.0, -1.0):
            pos = list(getattr(scene, attr).position)
            pos[j] += sign * FD_STEP
            moved = replace(scene, **{attr: replace(getattr(scene, attr), position=tuple(pos))})
            sol = solver.solve(moved, warm_start=base, error_estimate=False)
            assert sol.converged, sol.message
            forces.append(sol.force_a if end == "a" else sol.force_b)
        k[:, j] = (forces[0] - forces[1]) / (2 * FD_STEP)
    return k


def assert_fd(k: np.ndarray, k_fd: np.ndarray) -> None:
    """Every finite entry of k_fd equals k within FD_RTOL of max|K|."""
    scale = float(np.nanmax(np.abs(k)))
    ok = np.isfinite(k_fd)
    np.testing.assert_allclose(k[ok], k_fd[ok], rtol=0, atol=FD_RTOL * scale)


@pytest.fixture(scope="module")
def catenary():
    scene = scene_from_dict(CATENARY)
    solver = StaticsSolver(scene)
    sol = solver.solve(error_estimate=False)
    assert sol.success, sol.message
    return scene, solver, sol


# -- end angles and tensions --------------------------------------------------------------

def test_berteaux_end_angles_table1(problems):
    """Wang, Cheong & Chucheepsakul (1993), Table 1, "Present study": phi = 36.3 deg at
    the anchor (end_a), 90.2 deg at the buoy (end_b, the cable leans back past vertical).
    Printed to 0.1 deg: a value that rounds to them is within 0.05 deg."""
    sol = solve(load_scene(problems / "berteaux_mooring.toml"))
    assert sol.success, sol.message
    assert sol.angle_to_horizontal_deg("a") == pytest.approx(36.3, abs=0.05)
    assert sol.angle_to_horizontal_deg("b") == pytest.approx(90.2, abs=0.05)
    assert sol.angle_to_horizontal_deg("b") > 90.0  # leaning back, not 89.8
    ends = sol.to_dict()
    assert ends["end_b"]["tension_N"] == pytest.approx(11146.6, rel=1e-9)  # prescribed
    assert ends["end_a"]["tension_N"] == pytest.approx(np.linalg.norm(sol.force_a), rel=1e-12)
    assert ends["end_a"]["angle_to_horizontal_deg"] == sol.angle_to_horizontal_deg("a")


def test_end_angles_closed_form_catenary(catenary):
    """End angles atan2(V, H) and tensions hypot(H, V) of the closed-form catenary, for
    the line as given, turned by 130 deg about z (the angle follows the chord, not +x),
    and given from the fairlead (end_a above, descending: negative angles). The solved
    end forces match the closed form to ~1e-12 relative, so 1e-7 deg is loose."""
    h, va, vb = elastic_catenary()
    scene, _, sol = catenary
    angle_a, angle_b = math.degrees(math.atan2(va, h)), math.degrees(math.atan2(vb, h))
    assert angle_a < 0  # the line dips below the anchor
    assert sol.angle_to_horizontal_deg("a") == pytest.approx(angle_a, abs=1e-7)
    assert sol.angle_to_horizontal_deg("b") == pytest.approx(angle_b, abs=1e-7)
    assert sol.end_tension("a") == pytest.approx(math.hypot(h, va), rel=1e-10)
    assert sol.end_tension("b") == pytest.approx(math.hypot(h, vb), rel=1e-10)

    turned = copy.deepcopy(CATENARY)
    c, s = math.cos(math.radians(130.0)), math.sin(math.radians(130.0))
    turned["end_b"]["position"] = [c * X, s * X, 20.0 + Z]
    sol_t = solve(scene_from_dict(turned))
    assert sol_t.angle_to_horizontal_deg("a") == pytest.approx(angle_a, abs=1e-7)
    assert sol_t.angle_to_horizontal_deg("b") == pytest.approx(angle_b, abs=1e-7)

    flipped = copy.deepcopy(CATENARY)
    flipped["end_a"], flipped["end_b"] = CATENARY["end_b"], CATENARY["end_a"]
    sol_f = solve(scene_from_dict(flipped))
    assert sol_f.angle_to_horizontal_deg("a") == pytest.approx(-angle_b, abs=1e-7)
    assert sol_f.angle_to_horizontal_deg("b") == pytest.approx(-angle_a, abs=1e-7)


# -- stiffness ------------------------------------------------------------------------------

def test_stiffness_closed_form_catenary(catenary):
    """K at the fairlead against the closed-form elastic catenary (1e-8 relative: the
    collocation reproduces the catenary's end forces to ~1e-12 here), and the sign
    convention: moving the fairlead away from the anchor (+x), sideways (+y) or up (+z)
    makes its force, which points back and down, more negative: a negative diagonal.
    In still water without a seabed the line only sees the relative position of its
    ends and F_a + F_b = -(weight), so K at the anchor equals K at the fairlead."""
    _, _, sol = catenary
    ref = catenary_stiffness()
    kb, ka = sol.stiffness("b"), sol.stiffness("a")
    np.testing.assert_allclose(kb, ref, rtol=0, atol=1e-8 * np.abs(ref).max())
    np.testing.assert_allclose(ka, ref, rtol=0, atol=1e-8 * np.abs(ref).max())
    assert np.all(np.diag(kb) < 0)
    h, _, _ = elastic_catenary()
    assert kb[1, 1] == pytest.approx(-h / X, rel=1e-8)


def test_stiffness_multiple_shooting_closed_form():
    """The same sensitivities through the multiple-shooting transcription (RK4, order 4
    on 40 intervals: its end forces are ~1e-9 off the closed form, so 1e-7)."""
    data = copy.deepcopy(CATENARY)
    data["solver"] = {"method": "multiple_shooting"}
    sol = StaticsSolver(scene_from_dict(data)).solve(error_estimate=False)
    assert sol.success, sol.message
    ref = catenary_stiffness()
    for end in "ab":
        np.testing.assert_allclose(sol.stiffness(end), ref, rtol=0,
                                   atol=1e-7 * np.abs(ref).max())


def test_stiffness_fd_catenary(catenary):
    """Both ends of the 2D catenary against central differences of full solves."""
    scene, solver, sol = catenary
    for end in "ab":
        assert_fd(sol.stiffness(end), fd_stiffness(solver, scene, sol, end))


def test_stiffness_fd_dezoysa_3d_current(problems):
    """De Zoysa's line at psi0 = 90 deg (current across the line, componentwise drag: a
    full 3D matrix with no symmetry) against central differences, at both ends."""
    scene = load_scene(problems / "dezoysa_sea_buggy.toml", {"layout.psi0_deg": 90.0})
    solver = StaticsSolver(scene)
    sol = solver.solve(error_estimate=False)
    assert sol.success, sol.message
    np.testing.assert_allclose(sol.force_a, [1579.9, 3388.9, 1140.1], atol=0.06)
    for end in "ab":
        k = sol.stiffness(end)
        assert np.abs(k - k.T).max() > 1e-2 * np.abs(k).max()  # drag: not symmetric
        assert_fd(k, fd_stiffness(solver, scene, sol, end))


def test_stiffness_fd_seabed_contact_segments(problems):
    """A chain-wire-chain mooring with a clump, a buoy, a current at 20 deg and 147 m of
    chain on the seabed (touchdown formulation, three segments): the fairlead's K and the
    anchor's x, y columns against central differences; the anchor's z column is null
    (lifting a grounded anchor is one-sided: no derivative) and its z row is 0 (a flat
    seabed carries the vertical load of the grounded chain)."""
    scene = load_scene(problems / "mooring_clump_buoy.toml")
    free = StaticsSolver(scene).solve(error_estimate=False)
    solver = StaticsSolver(scene, grounded=True)
    sol = solver.solve(warm_start=free, error_estimate=False)
    assert sol.success and sol.grounded_length > 100.0, sol.message
    kb = sol.stiffness("b")
    assert_fd(kb, fd_stiffness(solver, scene, sol, "b"))
    ka = sol.stiffness("a")
    assert np.all(np.isnan(ka[:, 2])) and np.all(np.isfinite(ka[:, :2]))
    assert "z column is null" in sol.stiffness_note("a")
    assert_fd(ka, fd_stiffness(solver, scene, sol, "a", columns=(0, 1)))
    np.testing.assert_allclose(ka[2, :2], 0.0, atol=1e-9 * np.abs(ka[:2, :2]).max())
    data = sol.to_dict()
    assert data["grounded_length"] == pytest.approx(sol.grounded_length)
    assert data["touchdown"]["grounded_length"] == pytest.approx(sol.grounded_length)
    assert [row[2] for row in data["end_a"]["stiffness_N_per_m"]] == [None, None, None]
    json.dumps(data, allow_nan=False)


def test_stiffness_free_length_holds_the_length(problems):
    """Berteaux's line has a prescribed top tension and a free length; its stiffness holds
    the unstretched length it solved for (the line as installed). Checked against central
    differences of solves of the same line given its length (no tension prescribed)."""
    scene = load_scene(problems / "berteaux_mooring.toml")
    solver = StaticsSolver(scene)
    sol = solver.solve(error_estimate=False)
    assert sol.success, sol.message
    raw = copy.deepcopy(scene.raw)
    raw["cable"]["length"] = sol.length
    del raw["end_b"]["tension"]
    fixed = scene_from_dict(raw)
    fsolver = StaticsSolver(fixed)
    fsol = fsolver.solve(warm_start=sol, error_estimate=False)
    assert fsol.success, fsol.message
    np.testing.assert_allclose(fsol.force_b, sol.force_b, rtol=0, atol=1e-7 * 11146.6)
    assert "unstretched length held" in sol.stiffness_note("b")
    for end in "ab":
        assert_fd(sol.stiffness(end), fd_stiffness(fsolver, fixed, fsol, end))
        # the length-given solve has the same stiffness from its own sensitivities
        np.testing.assert_allclose(fsol.stiffness(end), sol.stiffness(end), rtol=0,
                                   atol=1e-6 * np.abs(sol.stiffness(end)).max())


def test_stiffness_null_cases(problems, catenary):
    """None (null in JSON) with a reason: at a free end (a towed body), for a baseline
    method (no solver sensitivities), and for a failed solve."""
    hanging = copy.deepcopy(CATENARY)  # a weight hanging from end_b on 100 m of line
    hanging["cable"]["length"] = 100.0
    hanging["end_a"] = {"force": [0.0, 0.0, -5000.0]}
    hanging["end_b"] = {"position": [0.0, 0.0, 120.0]}
    towed = solve(scene_from_dict(hanging))
    assert towed.success, towed.message
    assert towed.stiffness("a") is None
    assert "not fully fixed" in towed.stiffness_note("a")
    assert towed.to_dict()["end_a"]["stiffness_N_per_m"] is None
    # end_b: the line with its weight moves along with the fixed end (still water)
    np.testing.assert_allclose(towed.stiffness("b"), 0.0, atol=1e-9)
    assert "prescribed force" in towed.stiffness_note("b")

    data = copy.deepcopy(CATENARY)
    data["solver"] = {"method": "solve_bvp"}
    base = solve(scene_from_dict(data))
    assert base.success, base.message
    for end in "ab":
        assert base.stiffness(end) is None
        assert "solve_bvp" in base.stiffness_note(end)
    rows = _summary_rows(statics_summary(base))
    assert rows["end_a stiffness"].startswith("- (not available for method solve_bvp")
    assert "nan" not in statics_summary(base).lower()

    _, _, sol = catenary
    failed = replace(sol, status="failed")
    assert failed.stiffness("b") is None
    assert "did not converge" in failed.stiffness_note("b")


# -- JSON and summary ---------------------------------------------------------------------

def _summary_rows(text: str) -> dict[str, str]:
    """Label -> value of the summary table (two spaces separate them)."""
    pairs = (line.split("  ", 1) for line in text.splitlines() if "  " in line)
    return {k.strip(): v.strip() for k, v in pairs}


def _strict_loads(text: str) -> dict:
    def reject(name: str) -> None:
        raise AssertionError(f"non-strict JSON constant {name}")

    return json.loads(text, parse_constant=reject)


def test_cli_json_fields_and_summary(problems, capsys):
    """`cable-ocp solve --json -`: the new fields, strict JSON; then the summary table."""
    path = str(problems / "dezoysa_sea_buggy.toml")
    buf = io.StringIO()
    with redirect_stdout(buf):
        rc = main(["solve", path, "--json", "-", "--quiet"])
    assert rc == 0
    data = _strict_loads(buf.getvalue())
    assert data["grounded_length"] == 0.0
    prof = data["profile"]
    t = np.array([prof["tension_x"], prof["tension_y"], prof["tension_z"]]).T
    np.testing.assert_allclose(np.linalg.norm(t, axis=1), prof["tension"], rtol=1e-12)
    # T(0) is the force on end_a; -T(L) the force on end_b
    np.testing.assert_allclose(t[0], data["end_a"]["force"], rtol=1e-12)
    np.testing.assert_allclose(-t[-1], data["end_b"]["force"], rtol=1e-12)
    for end in ("end_a", "end_b"):
        e = data[end]
        assert e["tension_N"] == pytest.approx(np.linalg.norm(e["force"]), rel=1e-12)
        assert -180.0 < e["angle_to_horizontal_deg"] <= 180.0
        k = np.array(e["stiffness_N_per_m"], dtype=float)
        assert k.shape == (3, 3) and np.all(np.isfinite(k)) and np.all(np.diag(k) < 0)
        assert "held" in e["stiffness_note"]

    rc = main(["solve", path])
    assert rc == 0
    text = capsys.readouterr().out
    assert "nan" not in text.lower()
    rows = _summary_rows(text)
    assert rows["end_a angle to horizontal"].endswith(" deg")
    assert rows["end_a tension"].endswith(" N")
    assert rows["grounded length"] == "0.0000 m"
    for c in "xyz":
        assert rows[f"end_b stiffness dF{c}/d(x, y, z)"].endswith(") N/m")
    a = data["end_a"]
    assert rows["end_a angle to horizontal"] == f"{a['angle_to_horizontal_deg']:.3f} deg"
    assert rows["end_a tension"] == f"{a['tension_N']:.2f} N"


def test_one_strict_json_converter_serves_the_results_and_the_cli():
    """The results' ``to_dict()`` and the CLI's ``--json`` text use the same converter:
    numpy values become Python ones, NaN and infinities null, tuples lists, keys strings."""
    from cable_ocp.cli import output
    from cable_ocp.dynamics import result
    from cable_ocp.numerics.jsonable import json_safe

    assert result.json_safe is json_safe
    value = {1: (np.float64(math.nan), np.array([1.5, math.inf]), np.bool_(True)),
             "n": np.int32(3), "f": -math.inf, "s": "text"}
    expect = {"1": [None, [1.5, None], True], "n": 3, "f": None, "s": "text"}
    got = json_safe(value)
    assert got == expect
    assert type(got["1"][2]) is bool and type(got["n"]) is int
    assert json.loads(output.json_text(value)) == expect
