"""The closed-form catenary line (cable_ocp.statics.catenary_line) against the collocation
line, MoorPy's catenary and central differences of its own forces."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import cable_ocp as co
from cable_ocp.scene import End, Seabed
from cable_ocp.statics.catenary_line import solve_catenary_line, solve_catenary_scene
from tests.mooring.test_equilibrium import spar_dict

W = 162.0 * 9.81 - 1025.0 * 9.81 * math.pi * 0.162**2 / 4  # the spar's chain, N/m
EA = 6.93331350e8
L = 902.2

# (span X, height Z, length, EA, friction, contact): suspended, grounded without and with
# friction, friction exhausting the grounded tension (anchor force zero), inextensible
CASES = {
    "suspended": (600.0, 300.0, 700.0, EA, 0.0, True),
    "grounded": (800.0, 250.0, L, EA, 0.0, True),
    "friction": (800.0, 250.0, L, EA, 0.5, True),
    "slack_anchor": (700.0, 250.0, L, EA, 1.0, True),
    "inextensible": (800.0, 250.0, L, math.inf, 0.0, True),
}


def _end(x: np.ndarray) -> End:
    return End(position=tuple(float(v) for v in x), force=(None, None, None))


def _scene(x: float, z: float, length: float, ea: float, mu: float):
    """The spar's line L1 as a single-line scene between (0,0,0) and (x, 0, z)."""
    from cable_ocp.scene.system import system_from_dict

    sc = system_from_dict(spar_dict()).lines[0].scene
    cable = replace(sc.cable, length=length, axial_stiffness=ea)
    env = replace(sc.environment, seabed=Seabed(friction=mu))
    return replace(sc, cable=cable, segments=(), environment=env,
                   end_a=_end(np.zeros(3)), end_b=_end(np.array([x, 0.0, z])),
                   solver=replace(sc.solver, intervals=160, refine=False,
                                  error_estimate=False))


@pytest.mark.parametrize("name", list(CASES))
def test_against_collocation(name: str) -> None:
    x, z, length, ea, mu, _ = CASES[name]
    sc = _scene(x, z, length, ea, mu)
    cat = solve_catenary_scene(sc)
    col = co.solve(sc)
    assert cat.status == "solved" and col.status == "solved"
    fc = np.concatenate([cat.force_a, cat.force_b])
    fo = np.concatenate([col.force_a, col.force_b])
    # the collocation on 160 intervals is exact to ~1e-9 relative here; 1e-7 is its
    # discretisation and Newton tolerance with margin
    assert np.max(np.abs(fc - fo)) <= 1e-7 * np.max(np.abs(fo))
    kc, ko = cat.end_jacobian(), col.end_jacobian()
    assert np.array_equal(np.isnan(kc), np.isnan(ko))
    m = np.isfinite(ko)
    # 1e-6 of the largest entry: the collocation's sensitivities to its mesh
    assert np.max(np.abs(kc[m] - ko[m])) <= 1e-6 * np.max(np.abs(ko[m]))
    assert abs(cat.grounded_length - col.grounded_length) <= 1e-6 * length
    if name == "slack_anchor":
        assert np.all(cat.force_a == 0.0)


@pytest.mark.parametrize("name", list(CASES))
def test_against_moorpy_and_differences(name: str) -> None:
    x, z, length, ea, mu, contact = CASES[name]
    sol = solve_catenary_line(length, W, ea, [0, 0, 0], [x, 0, z], friction=mu,
                              contact=contact)
    assert sol.success
    k = sol.end_jacobian()
    guess = (sol.diagnostics["horizontal_tension"], sol.diagnostics["vertical_force"])

    def forces(p: np.ndarray) -> np.ndarray:
        s = solve_catenary_line(length, W, ea, p[:3], p[3:], friction=mu, contact=contact,
                                guess=guess)
        return np.concatenate([s.force_a, s.force_b])

    p0, step = np.array([0.0, 0.0, 0.0, x, 0.0, z]), 1e-3
    fd = np.column_stack([(forces(p0 + step * e) - forces(p0 - step * e)) / (2 * step)
                          for e in np.eye(6)])
    m = np.isfinite(k)
    # central differences: truncation O(step^2) ~1e-10 relative, rounding ~1e-10
    assert np.max(np.abs(k[m] - fd[m])) <= 1e-6 * np.max(np.abs(k[m]))
    assert np.all(np.isnan(k[:, 2])) == (sol.grounded_length > 0)
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    fah, fav, fbh, fbv, info = catenary(x, z, length, ea, W, CB=mu, Tol=1e-13, MaxIter=500)
    ours = np.array([sol.force_a[0], sol.force_a[2], sol.force_b[0], sol.force_b[2]])
    # MoorPy solves the same closed form: both to ~1e-13
    assert np.allclose(ours, [fah, fav, fbh, fbv], rtol=0, atol=1e-9 * abs(fbv))
    # MoorPy's stiffnessB is -dF_b/dx_b in the plane
    kb = k[3:, 3:][np.ix_([0, 2], [0, 2])]
    assert np.max(np.abs(kb + info["stiffnessB"])) <= 1e-9 * np.max(np.abs(kb))
    assert abs(sol.grounded_length - info["LBot"]) <= 1e-9 * length


def test_edge_cases_fail_with_a_message() -> None:
    vert = solve_catenary_line(L, W, EA, [0, 0, 0], [0, 0, 300.0])
    assert vert.status == "failed" and "X = 0" in vert.message
    short = solve_catenary_line(100.0, W, math.inf, [0, 0, 0], [90.0, 0, 50.0])
    assert short.status == "failed" and "too short" in short.message
