"""The statics Newton kernel compiled to C (``solver.compile = "auto"``) gives the answers
of the interpreted kernel, loads a cached library without generating code, and falls back
to the interpreted kernel, silently, when it cannot compile (no timing here: ``cable-ocp
bench sweep`` measures the speed).

The compiled kernel factorises the Jacobian by a sparse LU whose factors and pivot order
are kept (cable_ocp.numerics.sparse_lu), the interpreted one by CSparse's LU at every step: Newton
steps equal to rounding. Warm solves with the compiled kernel take chord steps
(cable_ocp.statics.newton.chord_newton), checked here against full Newton. Coarse meshes
keep the C compilations short (about half a second each).
"""

from __future__ import annotations

from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import compile as cc
from cable_ocp.numerics import sparse_lu
from cable_ocp.scene import load_scene
from cable_ocp.statics import newton as nw
from cable_ocp.statics.solver import StaticsSolver, sweep

DEZOYSA = Path(__file__).resolve().parents[1] / "problems" / "dezoysa_sea_buggy.toml"
OFF = {"solver.error_estimate": False, "solver.refine": False, "solver.intervals": 12}

needs_cc = pytest.mark.skipif(cc.c_compiler() is None, reason="no C compiler")


def test_compile_key_is_checked() -> None:
    """``solver.compile`` defaults to "never"; another word is a CableOCPError naming the
    key and the valid values."""
    assert load_scene(DEZOYSA).solver.compile == "never"
    assert load_scene(DEZOYSA, {"solver.compile": "auto"}).solver.compile == "auto"
    with pytest.raises(CableOCPError, match=r'solver.compile = .*"never", "auto"'):
        load_scene(DEZOYSA, {"solver.compile": "yes"})


@needs_cc
def test_compiled_step_equals_the_interpreted_step(cache_folder: Path) -> None:
    """At a point off the solution, the compiled residual equals the interpreted one to
    1e-14 relative (the same operations) and the compiled Newton step (sparse LU, factors
    kept) the interpreted one (CSparse's LU) to 1e-9 relative (two factorisations of one
    matrix: their rounding times the condition number of the collocated Jacobian, ~1e5
    here); a chord step from the kept factors equals the compiled Newton step exactly."""
    scene = load_scene(DEZOYSA, OFF)
    plain = StaticsSolver(scene)
    fast = StaticsSolver(scene.with_overrides({"solver.compile": "auto"}))
    assert fast.compiled and not plain.compiled
    w = plain.solve()._unknowns[1]
    w = w * (1.0 + 1e-3 * np.random.default_rng(5).standard_normal(w.size))
    p = plain.params(mesh=plain.mesh)
    g1, d1 = plain._kernel.step(w, p)
    g2, d2 = fast._kernel.step(w, p)
    assert np.max(np.abs(g2 - g1)) <= 1e-14 * np.max(np.abs(g1))
    assert np.max(np.abs(d2 - d1)) <= 1e-9 * np.max(np.abs(d1))
    assert np.array_equal(fast._kernel.g(w, p), g2)
    assert np.array_equal(fast._kernel.chord_step(g2), d2)


def _jacobian(solver: StaticsSolver, shift: float) -> ca.DM:
    """The collocated Jacobian at the solution shifted by ``shift`` (scaled unknowns)."""
    w = solver.solve()._unknowns[1] + shift
    return solver._gj(w, solver.params())[1]


def _superlu_step(jac: ca.DM, nz: np.ndarray, b: np.ndarray) -> np.ndarray:
    """-A^-1 b by SciPy's SuperLU (an independent sparse LU) for the nonzeros ``nz`` of
    ``jac``'s sparsity."""
    import scipy.sparse as sps
    import scipy.sparse.linalg as spl

    sp = jac.sparsity()
    a = sps.csc_matrix((nz, np.asarray(sp.row()), np.asarray(sp.colind())), shape=sp.shape)
    return -spl.splu(a).solve(b)


@needs_cc
def test_sparse_lu_solves_like_superlu(cache_folder: Path) -> None:
    """The kept LU factors solve a collocated Jacobian like SciPy's SuperLU to 1e-10
    relative (both partial-pivoting LUs of a matrix of condition ~1e5: their rounding
    differs by ~1e-11), for several right-hand sides from one factorisation; the next
    Jacobian of a Newton iteration is refactorised on the kept pivot order (no second
    analysis) and solved as well; a singular matrix gives non-finite steps."""
    solver = StaticsSolver(load_scene(DEZOYSA, OFF))
    jac = _jacobian(solver, 1e-2)
    lu = sparse_lu.SparseLU(jac.sparsity())
    rng = np.random.default_rng(2)
    for shift in (1e-2, 3e-3):
        nz = np.asarray(_jacobian(solver, shift).nonzeros()).ravel()
        lu.nz[:] = nz
        lu.factor()
        for _ in range(3):
            b = rng.standard_normal(solver.coll.n_w)
            ref = _superlu_step(jac, nz, b)
            assert np.max(np.abs(lu.newton_step(b) - ref)) <= 1e-10 * np.max(np.abs(ref))
    assert lu.analyses == 1
    lu.nz[:] = 0.0
    lu.factor()
    assert not np.all(np.isfinite(lu.newton_step(np.ones(solver.coll.n_w))))


@needs_cc
def test_a_broken_sparse_lu_helper_is_built_again(cache_folder: Path) -> None:
    """A helper library in the cache folder that does not load (here cut to 100 bytes) is
    removed and built again, never trusted: the next process has a working helper, which
    solves a 2x2 system exactly. (A new process: this one keeps the library it loaded.)"""
    import subprocess
    import sys

    assert sparse_lu.available()
    (lib,) = cache_folder.glob("cable_ocp_sparse_lu_*.so")
    cut = lib.with_suffix(".cut")
    cut.write_bytes(lib.read_bytes()[:100])
    cut.replace(lib)  # a new file: the loaded library's pages stay intact
    code = ("import numpy as np, casadi as ca\n"
            "from cable_ocp.numerics import sparse_lu\n"
            "lu = sparse_lu.SparseLU(ca.sparsify(ca.DM([[0.0, 2.0], [4.0, 1.0]])).sparsity())\n"
            "lu.nz[:] = [4.0, 2.0, 1.0]\n"  # compressed columns: (1,0), (0,1), (1,1)
            "lu.factor()\n"
            "print(lu.newton_step(np.array([2.0, 9.0])).tolist())\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert out.stdout.strip() == "[-2.0, -1.0]"
    assert lib.stat().st_size > 100


def _lu_of(a: np.ndarray) -> sparse_lu.SparseLU:
    """A SparseLU for the pattern of the dense matrix ``a``, its values loaded."""
    import scipy.sparse as sps

    csc = sps.csc_matrix(a)
    lu = sparse_lu.SparseLU(ca.DM(csc).sparsity())
    lu.nz[:] = csc.data
    return lu


@needs_cc
def test_sparse_lu_recovers_after_a_singular_matrix(cache_folder: Path) -> None:
    """A matrix singular to rounding (SuperLU keeps a last pivot of ~1e-16, the
    refactorisation refuses it: non-finite steps) does not leave the next, well
    conditioned matrix of the pattern with non-finite steps: it is solved on the kept
    order to 1e-14 (condition ~3). Found by an independent review."""
    a = np.array([[-0.03604073417938528, -0.39888843329431256, 0.567840036747218],
                  [-0.14835256394579072, -0.6878616792037651, 0.8785185223884],
                  [0.7271923850578366, 1.0, -0.679676633510859]])
    b = np.array([[2.0, 1.0, 0.5], [1.0, 3.0, 1.0], [0.5, 1.0, 4.0]])
    lu = _lu_of(a)
    lu.factor()
    assert not np.all(np.isfinite(lu.newton_step(np.ones(3))))
    lu.nz[:] = _lu_of(b).nz
    lu.factor()
    ref = -np.linalg.solve(b, np.ones(3))
    assert np.max(np.abs(lu.newton_step(np.ones(3)) - ref)) <= 1e-14 * np.max(np.abs(ref))


@needs_cc
def test_sparse_lu_refuses_growth_on_the_kept_order(cache_folder: Path) -> None:
    """The pivot threshold alone lets entries grow by ~1/0.0101 per column: a banded
    matrix with a border column whose kept order meets 8 pivots of 0.0101 in a row (each
    passes the 0.01 test) would grow U to ~1e16 and lose every digit (condition 85). The
    growth check refuses it and the matrix is analysed again: the answer equals
    numpy's to 1e-12. Found by an independent review."""
    n = 200

    def banded(small: float, k: int) -> np.ndarray:
        m = np.diag(np.full(n, 5.0)) + np.diag(np.full(n - 1, -1.0), -1)
        m[n - k - 1:n - 1, n - k - 1:n - 1] += np.diag(np.full(k, small - 5.0))
        m[:, -1] = 1.0
        m[-1, -1] = 5.0
        return m

    lu = _lu_of(banded(5.0, 0))
    lu.factor()
    bad = banded(0.0101, 8)
    lu.nz[:] = _lu_of(bad).nz
    lu.factor()
    assert lu.analyses == 2
    rhs = np.random.default_rng(0).standard_normal(n)
    ref = -np.linalg.solve(bad, rhs)
    assert np.max(np.abs(lu.newton_step(rhs) - ref)) <= 1e-12 * np.max(np.abs(ref))


@needs_cc
def test_sparse_lu_refuses_a_nan_below_the_pivot(cache_folder: Path) -> None:
    """A NaN entry under a pivot, followed by a finite one in the same column, is not
    lost: the step is non-finite (as numpy's would be), also for a right-hand side that
    does not touch that column. Found by an independent review."""
    g = np.array([[4.0, 0.0, 0.0], [2.0, 4.0, 1.0], [1.0, 1.0, 4.0]])
    lu = _lu_of(g)
    lu.factor()
    lu.nz[1] = np.nan  # A[1, 0], with A[2, 0] = 1 after it in column 0
    lu.factor()
    assert not np.all(np.isfinite(lu.newton_step(np.array([0.0, 1.0, 1.0]))))


@needs_cc
def test_sparse_lu_pattern_is_the_fill_of_its_pivot_order(cache_folder: Path) -> None:
    """The kept patterns of L and U are the fill of Gaussian elimination in the kept
    pivot order, from the structure alone: equal to the nonzeros of a dense LU without
    pivoting of P A Q with random values on A's pattern (SciPy's own L and U leave out
    entries that happen to be zero, which a later matrix may need)."""
    solver = StaticsSolver(load_scene(DEZOYSA, OFF))
    jac = _jacobian(solver, 1e-2)
    lu = sparse_lu.SparseLU(jac.sparsity())
    lu.nz[:] = np.asarray(jac.nonzeros()).ravel()
    lu.factor()
    n = jac.size1()
    sp = jac.sparsity()
    a = np.zeros((n, n))
    a[np.asarray(sp.row()), np.repeat(np.arange(n), np.diff(sp.colind()))] = \
        np.random.default_rng(6).uniform(1.0, 2.0, sp.nnz())
    m = np.zeros((n, n))
    m[lu._pinv] = a  # row i of A is row pinv[i] of P A
    m = m[:, lu._q]  # column j of P A Q is column q[j]
    for k in range(n - 1):  # no pivoting: L below the diagonal, U on and above
        m[k + 1:, k] /= m[k, k]
        m[k + 1:, k + 1:] -= np.outer(m[k + 1:, k], m[k, k + 1:])
    low = {(int(i), j) for j in range(n)
           for i in lu._li[lu._lp[j]:lu._lp[j + 1]] if i != j}
    up = {(int(i), j) for j in range(n) for i in lu._ui[lu._up[j]:lu._up[j + 1]]}
    fill = set(zip(*(x.tolist() for x in np.nonzero(m)), strict=True))
    assert low == {(i, j) for i, j in fill if i > j}
    upper = {(i, j) for i, j in fill if i <= j}
    assert up >= upper
    assert up - upper <= {(j, j) for j in range(n)}  # a diagonal kept even if zero


@needs_cc
def test_sparse_lu_refuses_a_failed_pivot(cache_folder: Path) -> None:
    """A kept pivot made 1e-4 of its value is refused by the pivot threshold and the
    matrix analysed again (measured without the threshold: accepted, U grows 2.5e3x,
    below the growth check's limit, error 1.2e-14 instead of 3e-15); the answer equals
    SuperLU's to 1e-10 relative."""
    solver = StaticsSolver(load_scene(DEZOYSA, OFF))
    jac = _jacobian(solver, 1e-2)
    nz = np.asarray(jac.nonzeros()).ravel()
    lu = sparse_lu.SparseLU(jac.sparsity())
    lu.nz[:] = nz
    lu.factor()
    sp = jac.sparsity()
    rows = np.asarray(sp.row())
    cols = np.repeat(np.arange(jac.size2()), np.diff(sp.colind()))
    # the entry of A that is the first pivot: column q[0], the row that P maps to row 0
    first = np.flatnonzero((cols == lu._q[0]) & (lu._pinv[rows] == 0))[0]
    bad = nz.copy()
    bad[first] *= 1e-4
    lu.nz[:] = bad
    lu.factor()
    assert lu.analyses == 2
    b = np.random.default_rng(3).standard_normal(solver.coll.n_w)
    ref = _superlu_step(jac, bad, b)
    assert np.max(np.abs(lu.newton_step(b) - ref)) <= 1e-10 * np.max(np.abs(ref))


@needs_cc
@pytest.mark.parametrize("angle", [20.0, 90.0, 130.0])
def test_chord_newton_converges_to_the_newton_solution(cache_folder: Path,
                                                       angle: float) -> None:
    """From the solution 10 degrees away (a warm start with a scaled residual ~1e-1),
    chord steps reach max|G| <= 1e-10 (the residual re-evaluated here by the interpreted
    G) with fewer factorisations than steps, at the point full Newton reaches from the
    same start to 1e-9 relative (both iterates are within the 1e-10 residual tolerance;
    the Jacobian's condition number ~1e5 bounds their distance by ~1e-9 of the solution)
    and to 1e-12 relative after one full Newton step from each (quadratic convergence:
    both polished to rounding)."""
    base = load_scene(DEZOYSA, {**OFF, "solver.compile": "auto"})
    solver = StaticsSolver(base)
    assert solver.compiled
    prev = solver.solve(base.with_overrides({"layout.psi0_deg": angle - 10.0}))
    scene = base.with_overrides({"layout.psi0_deg": angle})
    p = solver.params(scene, mesh=prev._unknowns[2])  # on the mesh of the start
    w0 = prev._unknowns[1]
    assert np.max(np.abs(np.asarray(solver.coll.residual(w0, p)))) > 1e-3  # a real warm start
    chord = nw.chord_newton(solver._kernel, w0, p, 1e-10)
    full = nw.newton(solver._kernel, w0, p, 1e-10)
    assert chord.success and full.success
    assert chord.factorizations < chord.iterations
    g = np.asarray(StaticsSolver(load_scene(DEZOYSA, OFF)).coll.residual(chord.w, p))
    assert np.max(np.abs(g)) <= 1e-10
    scale = np.max(np.abs(full.w))
    assert np.max(np.abs(chord.w - full.w)) <= 1e-9 * scale
    polished = [w + solver._kernel.step(w, p)[1] for w in (chord.w, full.w)]
    assert np.max(np.abs(polished[0] - polished[1])) <= 1e-12 * scale


@needs_cc
def test_chord_refactorises_and_falls_back_on_poor_contraction(
        cache_folder: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A contraction demand no step can meet (1e-300) makes every step a new
    factorisation (factorisations >= steps: full Newton, here with backtracking from the
    previous angle's solution, whose full step does not decrease max|G|); from a start
    far from any solution (3x the unknowns of another layout) chord_newton gives up
    within 3 steps (success False) and the solver's warm path finishes with the damped
    Newton from there; with the usual step limit the warm solve from that far start lands
    on the cold solution's forces within 1e-9 relative."""
    base = load_scene(DEZOYSA, {**OFF, "solver.compile": "auto"})
    solver = StaticsSolver(base)
    scene = base.with_overrides({"layout.psi0_deg": 60.0})
    start = solver.solve(base.with_overrides({"layout.psi0_deg": 50.0}))
    w0 = start._unknowns[1]
    p = solver.params(scene, mesh=start._unknowns[2])  # on the mesh of the start
    strict = nw.chord_newton(solver._kernel, w0, p, 1e-10, contraction=1e-300)
    assert strict.success and strict.factorizations >= strict.iterations

    far = solver.solve(base.with_overrides({"layout.psi0_deg": 180.0}))
    far_w = 3.0 * far._unknowns[1]  # no longer near any solution
    gave_up = nw.chord_newton(solver._kernel, far_w, p, 1e-10, max_iter=3)
    assert not gave_up.success
    calls = []
    real = nw.newton

    def spy(*args: object, **kwargs: object) -> nw.NewtonResult:
        calls.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr("cable_ocp.statics.line_solver.newton", spy)
    monkeypatch.setattr("cable_ocp.statics.line_solver.NEWTON_MAX_STEPS", 3)
    res = solver._newton(far_w, p, warm=True)
    assert calls  # the chord steps gave up within 3 steps: damped Newton took over
    assert "chord steps stopped" in res.message
    cold = StaticsSolver(load_scene(DEZOYSA, {**OFF, "layout.psi0_deg": 60.0})).solve()
    monkeypatch.setattr("cable_ocp.statics.line_solver.NEWTON_MAX_STEPS", 30)
    sol = solver.solve(scene, warm_start=far)
    assert sol.success
    ref = np.max(np.abs(cold.force_a))
    assert np.max(np.abs(sol.force_a - cold.force_a)) <= 1e-9 * ref


@needs_cc
def test_interpreted_warm_solves_take_chord_steps(cache_folder: Path,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    """The interpreted kernel keeps LU factors from its first warm solve on: its warm
    solves from its own solutions take chord steps (fewer factorisations than steps; cold
    solves keep CasADi's CSparse step) and land on the end forces of Newton steps from
    the same start (the helper unavailable: a factorisation per step) to 1e-9 relative
    (both stop at a scaled residual of 1e-10)."""
    base = load_scene(DEZOYSA, OFF)
    first, scene = base.with_overrides({"layout.psi0_deg": 50.0}), \
        base.with_overrides({"layout.psi0_deg": 60.0})
    chord_solver = StaticsSolver(base)
    start = chord_solver.solve(first)
    assert start.success and not chord_solver._kernel.can_chord  # cold: no LU kept
    a = chord_solver.solve(scene, warm_start=start)
    assert chord_solver._kernel.can_chord and not chord_solver.compiled
    assert a.success and a.diagnostics["factorizations"] < a.iterations
    monkeypatch.setattr(sparse_lu, "available", lambda: False)
    newton_solver = StaticsSolver(base)
    b = newton_solver.solve(scene, warm_start=newton_solver.solve(first))
    assert not newton_solver._kernel.can_chord
    assert b.success and b.diagnostics["factorizations"] >= b.iterations
    ref = np.max(np.abs(b.force_a))
    assert np.max(np.abs(a.force_a - b.force_a)) <= 1e-9 * ref


@needs_cc
def test_the_chord_diagnostic_says_what_ran(cache_folder: Path) -> None:
    """``diagnostics["chord"]`` is there when chord steps ran (a warm point of a sweep on
    the default mesh: "converged") and absent when they did not (the moving "tracking"
    mesh takes Newton steps, with the compiled kernel, which could take chord steps).
    Found by an independent review."""
    base = load_scene(DEZOYSA, {**OFF, "solver.degree": 4, "solver.compile": "auto"})
    kept = sweep(base, "layout.psi0_deg", [80.0, 90.0], error_estimate=False)
    assert kept[1].diagnostics.get("chord") == "converged"
    moving = sweep(base.with_overrides({"solver.mesh": "tracking"}), "layout.psi0_deg",
                   [80.0, 90.0], error_estimate=False)
    assert moving[1].success and "chord" not in moving[1].diagnostics


@needs_cc
def test_compiled_sweep_matches_the_interpreted_sweep(cache_folder: Path) -> None:
    """The psi0 sweep with the compiled kernel gives the end forces of the interpreted
    sweep (itself checked against CasADi's rootfinder in test_statics_speed.py) to 1e-9
    relative: both stop at a scaled residual of 1e-10, and the collocated system's
    conditioning turns that into ~1e-10 relative in the forces."""
    base = load_scene(DEZOYSA, OFF)
    angles = np.arange(0.0, 181.0, 30.0)
    plain = sweep(base, "layout.psi0_deg", angles, error_estimate=False)
    fast = sweep(base.with_overrides({"solver.compile": "auto"}), "layout.psi0_deg", angles,
                 error_estimate=False)
    assert all(s.diagnostics["compiled"] for s in fast)
    assert not any(s.diagnostics["compiled"] for s in plain)
    for a, b in zip(plain, fast, strict=True):
        assert a.status == b.status
        ref = max(np.max(np.abs(a.force_a)), np.max(np.abs(a.force_b)))
        assert np.max(np.abs(b.force_a - a.force_a)) <= 1e-9 * ref
        assert np.max(np.abs(b.force_b - a.force_b)) <= 1e-9 * ref


@needs_cc
def test_a_cached_library_is_loaded_without_generating_code(
        cache_folder: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A second solver of the same structure and mesh loads the compiled libraries by
    their key: with C code generation made to fail, it is still compiled. A new mesh needs
    new code: its generation fails, and the solver falls back to the interpreted kernel
    silently and still solves (to the forces of the compiled solver within 1e-9, as
    above)."""
    scene = load_scene(DEZOYSA, {**OFF, "solver.compile": "auto"})
    first = StaticsSolver(scene)
    assert first.compiled
    assert any(cache_folder.glob("GJ_*.so"))

    def broken(*args: object, **kwargs: object) -> None:
        raise RuntimeError("code generation is not available")

    monkeypatch.setattr(ca, "CodeGenerator", broken)
    again = StaticsSolver(scene)
    assert again.compiled
    other = StaticsSolver(scene, intervals=14)
    assert not other.compiled
    s1, s2 = first.solve(), other.solve()
    assert s1.success and s2.success
    assert not s2.diagnostics["compiled"]


@pytest.mark.parametrize("case", ["missing_cc", "cache_off"])
def test_without_a_compiler_the_interpreted_kernel_runs(
        case: str, cache_folder: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """``CC`` naming a missing program, or ``CABLE_OCP_CACHE=0``: ``solver.compile =
    "auto"`` runs the interpreted kernel, silently, with bit-identical results (the very
    functions of ``"never"``), and writes no library."""
    if case == "missing_cc":
        monkeypatch.setenv("CC", str(cache_folder.parent / "nonexistent-cc"))
    else:
        monkeypatch.setenv("CABLE_OCP_CACHE", "0")
    scene = load_scene(DEZOYSA, OFF)
    auto = StaticsSolver(scene.with_overrides({"solver.compile": "auto"}))
    assert not auto.compiled
    s1, s2 = StaticsSolver(scene).solve(), auto.solve()
    assert s2.success and not s2.diagnostics["compiled"]
    assert np.array_equal(s1.force_a, s2.force_a) and np.array_equal(s1.force_b, s2.force_b)
    assert not list(cache_folder.glob("*.so"))


@needs_cc
def test_compile_function_by_key(cache_folder: Path) -> None:
    """``compile_function`` with a key: the builder runs once (the second call loads the
    library without building), the result equals the interpreted function's to rounding
    (1e-14 relative: the same operations, compiled; libm may round differently)."""
    calls = []

    def build() -> ca.Function:
        calls.append(1)
        x = ca.SX.sym("x", 3)
        return ca.Function("probe_key", [x], [ca.sin(x) * x[0] + ca.exp(x[1])])

    f1 = cc.compile_function(build, key="probe v1", name="probe_key")
    f2 = cc.compile_function(build, key="probe v1", name="probe_key")
    assert cc.is_compiled(f1) and cc.is_compiled(f2)
    assert len(calls) == 1
    x = np.array([0.3, -1.2, 2.5])
    ref = np.asarray(build()(x)).ravel()
    assert np.allclose(np.asarray(f2(x)).ravel(), ref, rtol=1e-14, atol=0)


@needs_cc
@pytest.mark.parametrize("name, key, values, method", [
    ("berteaux_mooring.toml", "end_b.tension", [11146.6, 11400.0, 11700.0], "collocation"),
    ("berteaux_mooring.toml", "end_b.tension", [11146.6, 11400.0], "multiple_shooting"),
    pytest.param("mooring_clump_buoy.toml", "end_b.position",
                 [[680.0, 0.0, 140.0], [690.0, 0.0, 140.0], [700.0, 0.0, 140.0]],
                 "collocation", marks=pytest.mark.slow),  # ~20 s: compiles the contact solvers
])
def test_compiled_warm_solves_on_other_structures(cache_folder: Path, name: str, key: str,
                                                  values: list, method: str) -> None:
    """A free length (a bounded unknown), multiple shooting, and three segments with
    seabed contact: a session of warm solves with the compiled kernel gives the statuses,
    lengths and end forces of the interpreted session to 1e-8 relative (both stop at a
    scaled residual of 1e-10; the free length and touchdown add to the conditioning)."""
    path = Path(__file__).resolve().parents[1] / "problems" / name
    from cable_ocp.statics.solver import SolveSession

    out = {}
    for mode in ("never", "auto"):
        base = load_scene(path, {"solver.error_estimate": False, "solver.refine": False,
                                 "solver.intervals": 16, "solver.method": method,
                                 "solver.compile": mode})
        session = SolveSession(error_estimate=False)
        out[mode] = [session.solve(base.with_overrides({key: v})) for v in values]
    assert any(s.diagnostics.get("compiled") for s in out["auto"])
    for a, b in zip(out["never"], out["auto"], strict=True):
        assert a.status == b.status and a.converged
        ref = max(np.max(np.abs(a.force_a)), np.max(np.abs(a.force_b)))
        assert np.max(np.abs(b.force_a - a.force_a)) <= 1e-8 * ref
        assert np.max(np.abs(b.force_b - a.force_b)) <= 1e-8 * ref
        assert abs(b.length - a.length) <= 1e-8 * a.length
