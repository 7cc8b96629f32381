"""The lumped-mass model's static start for an anchored, sagging line, and silence.

A line with both ends fixed that sags (a catenary between two points at the same height)
used to fail its static start: the statics solution interpolated at the nodes has chords
shorter than the stretched segments (the arc's curvature), so every segment starts slack,
the Newton matrix has no transverse stiffness and is singular (scipy warned with
``MatrixRankWarning``). The library must neither fail there nor warn anywhere.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from cable_ocp.dynamics import simulate
from cable_ocp.numerics.linalg import solve_sparse

SAG = """
[environment]
water_depth = 100.0
water_density = 1025.0

[cable]
length = 120.0
diameter = 0.03
weight_in_water = 20.0
axial_stiffness = 1.0e7
normal_drag = 1.2
tangential_drag = 0.01
mass_per_length = 3.0
added_mass_coefficient = 1.0

[end_a]
position = [0.0, 0.0, 50.0]

[end_b]
position = [100.0, 0.0, 50.0]

[top_motion]
heave_amplitude = 0.5
heave_frequency = 0.5
ramp_time = 4.0

[simulation]
model = "lumped3d"
duration = 2.0
time_step = 0.05
segments = 20
"""


def test_solve_sparse_singular_is_none_without_warning() -> None:
    """A singular matrix gives None (the caller's failed status), not a warning or NaN."""
    a = sp.csc_matrix(np.array([[1.0, 0.0], [0.0, 0.0]]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert solve_sparse(a, np.array([1.0, 1.0])) is None
        x = solve_sparse(sp.csc_matrix(np.diag([2.0, 4.0])), np.array([1.0, 1.0]))
    assert x is not None
    np.testing.assert_allclose(x, [0.5, 0.25], rtol=1e-15)  # exact in binary


def test_anchored_sagging_line_starts_static_and_is_silent(tmp_path: Path) -> None:
    """Both ends fixed, sagging: the static start converges, nothing warns, and the start
    is the discrete chain's equilibrium, checked here from the node positions alone.

    Independent check (not the model's Newton residual): at rest, with no current, a
    lumped chain's nodes carry only the segment tensions EA (|d_j| / l - 1) along d_j and
    the nodal weights (half of each adjacent segment's w l), so the horizontal tension
    component is the same in every segment and the vertical one steps by w l at each
    interior node. Tolerances: 1e-6 of the tension (Newton stops at 1e-9 of the force
    scale; positions in float64 give strains to ~1e-12 / 1e-4 of the static strain). The
    discrete chain lies within O((l / L)^2) of the statics solver's catenary: the largest
    node shift is reported and bounded by 0.1 m (3.8 cm seen at 20 segments of 6 m).
    """
    path = tmp_path / "sag.toml"
    path.write_text(SAG, encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning (MatrixRankWarning too) fails
        r = simulate(path)
    assert r.status == "solved", r.message
    start = r.diagnostics["start"]
    assert start["converged"], start
    assert start["max_node_shift_m"] < 0.1
    pos = r.node_positions[0]
    ea, w, ell = 1.0e7, 20.0, 120.0 / 20
    d = np.diff(pos, axis=0)
    length = np.linalg.norm(d, axis=1)
    tension = ea * (length / ell - 1.0)
    assert np.all(tension > 0.0)
    horizontal = tension * d[:, 0] / length
    vertical = tension * d[:, 2] / length
    scale = float(np.max(tension))
    assert np.ptp(horizontal) < 1e-6 * scale
    np.testing.assert_allclose(np.diff(vertical), w * ell, atol=1e-6 * scale)
    # the symmetric catenary: the lowest point midway, the ends' vertical forces each
    # carry half of the total weight (to the same tolerance)
    assert vertical[-1] == pytest.approx(0.5 * w * 120.0 - 0.5 * w * ell, abs=1e-6 * scale)


# --------------------------------------------------------------------------------------
# compiling to C: every missing piece falls back to the interpreted function
# --------------------------------------------------------------------------------------

def _small_function():  # noqa: ANN202 - a casadi Function
    import casadi as ca

    x = ca.SX.sym("x", 2)
    return ca.Function("robust_probe", [x], [ca.sin(x) * x[0]])


@pytest.mark.parametrize("case", ["missing_cc", "no_cc_on_path", "unwritable_dir",
                                  "cache_off"])
def test_compile_falls_back_to_interpreted(case: str, tmp_path: Path,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    """No C compiler (``CC`` names a missing program, or none on the PATH), a cache
    directory that cannot be created (below a regular file: fails for root too), or
    ``CABLE_OCP_CACHE=0``: ``compile_function`` returns the function itself, silently."""
    from cable_ocp.numerics.compile import compile_function

    fn = _small_function()
    monkeypatch.delenv("CABLE_OCP_CACHE", raising=False)
    monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(tmp_path / "cache"))
    if case == "missing_cc":
        monkeypatch.setenv("CC", str(tmp_path / "nonexistent-cc"))
    elif case == "no_cc_on_path":
        monkeypatch.delenv("CC", raising=False)
        monkeypatch.setenv("PATH", str(tmp_path / "empty-bin"))
    elif case == "unwritable_dir":
        blocker = tmp_path / "a_file"
        blocker.write_text("not a directory", encoding="utf-8")
        monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(blocker / "cache"))
    else:
        monkeypatch.setenv("CABLE_OCP_CACHE", "0")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = compile_function(fn, "-O2")
    assert out is fn
    assert not (tmp_path / "cache").exists() or not any((tmp_path / "cache").iterdir())


def test_run_without_compiler_gives_the_same_numbers(tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    """``run(compile="step")`` with no compiler reports ``compiled == "none"`` and gives the
    interpreted run's numbers (the same CasADi graph: equal to 1e-12 m, rounding only)."""
    from cable_ocp.dynamics.lumped import LumpedMassModel
    from cable_ocp.dynamics.lumped_params import UnitParams, uniform_params
    from cable_ocp.dynamics.lumped_run import run

    monkeypatch.setenv("CC", str(tmp_path / "nonexistent-cc"))
    monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(tmp_path / "cache"))
    p = uniform_params(40.0, 4, axial_stiffness=1.0e6, diameter=0.02, mass_per_length=1.0,
                       weight_in_water=8.0, top_position=[0.0, 0.0, 100.0],
                       unit=UnitParams(mass=50.0, weight_in_water=400.0))
    m = LumpedMassModel(p)
    xg = np.zeros((4, 3))
    xg[:, 0] = 0.5  # off the vertical: a pendulum swing
    xg[:, 2] = 60.0 + p.node_arc_length[:-1]
    a = run(m, xg.reshape(-1), None, 1.0, 0.05, compile="step")
    b = run(m, xg.reshape(-1), None, 1.0, 0.05, compile=False)
    assert a.compiled == "none" and a.success and b.success
    np.testing.assert_allclose(a.positions, b.positions, rtol=0, atol=1e-12)
    assert float(np.ptp(a.positions[:, 0, 0])) > 1e-3  # it moved: the check is not vacuous


#: the model's CasADi functions, each built on first use
_LAZY = ("forces", "external_forces", "mass_matrix", "tensions", "nodes", "node_velocities",
         "segment_tension", "top_force", "energy", "static_stiffness", "ends", "mass_blocks",
         "stepper", "_static_fj", "_symbols", "_top_vel", "_a_vel")


def test_model_builds_each_function_on_first_use() -> None:
    """The constructor builds no CasADi function (a modal analysis needs three of them, a
    run a few more): each is built on first use and kept on the instance (the same object
    on the next use); the modes of a pendulum line then build only what they use."""
    import casadi as ca

    from cable_ocp.dynamics.lumped import LumpedMassModel
    from cable_ocp.dynamics.lumped_params import UnitParams, uniform_params

    p = uniform_params(40.0, 4, axial_stiffness=1.0e6, diameter=0.02, mass_per_length=1.0,
                       weight_in_water=8.0, top_position=[0.0, 0.0, 100.0],
                       unit=UnitParams(mass=50.0, weight_in_water=400.0))
    m = LumpedMassModel(p)
    assert not set(_LAZY) & set(vars(m))
    assert not any(isinstance(v, ca.Function) for v in vars(m).values())
    f = m.forces
    assert m.forces is f
    assert set(_LAZY) & set(vars(m)) == {"forces", "_symbols", "_top_vel"}
    xg = np.zeros((4, 3))
    xg[:, 2] = 60.0 + p.node_arc_length[:-1]
    x, info = m.static_equilibrium(xg.reshape(-1))
    assert info["converged"]
    m.modes(x, 2)
    assert "stepper" not in vars(m) and "energy" not in vars(m)
