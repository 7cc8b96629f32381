"""The fast statics paths give the answers of the paths they replace (no timing here: the
benchmarks measure speed, ``cable-ocp bench sweep`` and ``cable-ocp bench accuracy``).

* The Jacobian assembled per collocation interval (cable_ocp.statics.newton) against
  CasADi's own differentiation of the whole, expanded residual.
* The sweep (polynomial predictor, buffered Newton) against a sweep written here with
  CasADi's Newton ``rootfinder`` from the previous solution, as the solver did before.
* Newton-first cold solves against IPOPT cold solves, and the fallback to IPOPT where
  Newton's line search stalls.
* The on-disk function cache: bit-identical results, a real second process that loads
  instead of building, corrupt, truncated or foreign entries rebuilt, never used, an
  unusable folder skipped, and the folder kept to its size.
* The catenary parameter by Newton's method against the bracketing search it replaced.
* ``cable-ocp bench sweep --json -``: the JSON alone on stdout, with the tracked keys.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from cable_ocp.scene import load_scene
from cable_ocp.statics import cache as disk_cache
from cable_ocp.statics.catenary import catenary_parameter, catenary_parameter_bracketed
from cable_ocp.statics.formulation import Formulation
from cable_ocp.statics.newton import jacobian_functions
from cable_ocp.statics.solver import StaticsSolver, sweep

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
DEZOYSA = PROBLEMS / "dezoysa_sea_buggy.toml"
OFF = {"solver.error_estimate": False, "solver.refine": False}


@pytest.mark.parametrize("name, grounded, method", [
    ("dezoysa_sea_buggy.toml", False, "collocation"),    # componentwise drag, fixed length
    ("berteaux_mooring.toml", False, "collocation"),     # free length (tension prescribed)
    ("mooring_clump_buoy.toml", True, "collocation"),    # 3 segments, 2 bodies, seabed
    ("bielanski_tow.toml", False, "collocation"),        # bending stiffness (8 states/node)
    ("extreme/slack_touchdown.toml", True, "collocation"),  # touchdown, fixed length
    ("berteaux_mooring.toml", False, "multiple_shooting"),  # RK4 steps as blocks
    ("extreme/slack_touchdown.toml", True, "multiple_shooting"),
])
def test_block_jacobian_equals_the_expanded_residuals(name: str, grounded: bool,
                                                      method: str) -> None:
    """The Jacobian assembled from the intervals' own small Jacobians (for collocation by
    the chain rule through the right-hand side's Jacobian) equals CasADi's
    differentiation of the whole residual expanded to SX, entry by entry and in sparsity,
    at a random point (1e-13 relative: the same derivatives, summed in another order)."""
    scene = load_scene(PROBLEMS / name, {"solver.method": method})
    solver = StaticsSolver(scene, intervals=4, grounded=grounded)
    coll = solver.coll
    n_p = coll.n_p  # the formulation's parameters and the interval widths
    gj, _ = jacobian_functions(coll.blocks, coll.n_w, n_p)
    ref = coll.residual.expand()
    ws, ps = ca.SX.sym("w", coll.n_w), ca.SX.sym("p", n_p)
    g = ref(ws, ps)
    full = ca.Function("full", [ws, ps], [g, ca.jacobian(g, ws)])
    rng = np.random.default_rng(3)
    w = 0.5 + rng.random(coll.n_w)
    p = solver.params()
    if method == "collocation":  # intervals of unequal widths
        p[-coll.mesh.n_intervals:] *= 0.5 + rng.random(coll.mesh.n_intervals)
    g1, j1 = gj(w, p)
    g2, j2 = full(w, p)
    assert j1.sparsity() == j2.sparsity()
    scale = float(ca.norm_inf(j2))
    assert float(ca.norm_inf(j1 - j2)) <= 1e-13 * scale
    assert float(ca.norm_inf(g1 - g2)) <= 1e-13 * max(1.0, float(ca.norm_inf(g2)))


def test_sweep_matches_a_rootfinder_sweep() -> None:
    """The De Zoysa psi0 sweep (19 angles, 40 intervals) with the polynomial predictor and
    the buffered Newton gives the end forces of a sweep written here the way the solver
    did it before: CasADi's Newton rootfinder (CSparse) on the expanded residual, each
    point from the previous solution, on the mesh of the sweep's point (its mesh points
    follow the drag's kinks). Both stop at a scaled residual of 1e-10; the forces agree to
    1e-9 relative (the conditioning of the collocated system)."""
    base = load_scene(DEZOYSA, {"solver.intervals": 40, **OFF})
    angles = np.arange(0.0, 181.0, 10.0)
    sols = sweep(base, "layout.psi0_deg", angles, error_estimate=False)
    assert all(s.converged for s in sols)

    solver = StaticsSolver(base)
    rf = ca.rootfinder("rf", "newton", solver.coll.residual.expand(), {
        "linear_solver": "csparse", "abstol": 1e-10, "abstolStep": 1e-14, "max_iter": 30,
        "error_on_fail": False})
    coll, scale = solver.coll, solver.form.scales.force
    w = None
    for angle, sol in zip(angles, sols, strict=True):
        scene = base.with_overrides({"layout.psi0_deg": float(angle)})
        if w is None:
            w = solver.solve(scene)._unknowns[1]
        p = solver.params(scene, mesh=sol._unknowns[2])
        w = np.asarray(rf(w, p)).reshape(-1)
        assert rf.stats()["success"]
        force_a = w[3:6] * scale  # +T(0) of the first node, N
        last = (coll.mesh.n_nodes - 1) * coll.nx
        force_b = -w[last + 3: last + 6] * scale
        ref = max(np.max(np.abs(force_a)), np.max(np.abs(force_b)))
        assert np.max(np.abs(sol.force_a - force_a)) <= 1e-9 * ref
        assert np.max(np.abs(sol.force_b - force_b)) <= 1e-9 * ref
    # the predictor is used: every point after the first two starts from it
    assert all(s.diagnostics["start"] == "warm" for s in sols[1:])


@pytest.mark.parametrize("name", [
    "dezoysa_sea_buggy.toml", "berteaux_mooring.toml", "mooring_clump_buoy.toml",
    "chucheepsakul_top_tension.toml", "extreme/reversing_current.toml",
    "extreme/very_soft.toml"])
def test_cold_newton_lands_on_the_ipopt_solution(name: str) -> None:
    """On shipped scenes the Newton-first cold solve (line search from the catenary or
    straight guess) converges by itself and lands on the solution IPOPT finds from the
    same guess: end forces and length to 1e-8 relative (both stop at a scaled residual of
    1e-10; Berteaux's second, 15 km solution is not picked up)."""
    scene = load_scene(PROBLEMS / name, OFF)
    newton = StaticsSolver(scene).solve()
    ipopt = StaticsSolver(scene, cold="ipopt").solve()
    assert newton.converged and ipopt.converged, (newton.message, ipopt.message)
    assert newton.diagnostics["solver"] == "newton (line search)"
    assert newton.diagnostics["solver"] != ipopt.diagnostics["solver"]
    ref = max(np.max(np.abs(ipopt.force_a)), np.max(np.abs(ipopt.force_b)))
    assert np.max(np.abs(newton.force_a - ipopt.force_a)) <= 1e-8 * ref
    assert np.max(np.abs(newton.force_b - ipopt.force_b)) <= 1e-8 * ref
    assert abs(newton.length - ipopt.length) <= 1e-8 * ipopt.length


def test_cold_newton_falls_back_to_ipopt() -> None:
    """A neutrally buoyant cable held by drag alone, from a straight guess: Newton's line
    search stalls (the guess's tension is far from the drag-borne one), the solver says
    so and IPOPT solves it; the answer is IPOPT's own (same forces to 1e-8)."""
    scene = load_scene(PROBLEMS / "extreme" / "neutrally_buoyant.toml", OFF)
    sol = StaticsSolver(scene).solve()
    assert sol.success, sol.message
    how = sol.diagnostics["solver"]
    assert how.startswith("newton failed") and "ipopt" in how, how
    ref = StaticsSolver(scene, cold="ipopt").solve()
    scale = np.max(np.abs(ref.force_a))
    assert np.max(np.abs(sol.force_a - ref.force_a)) <= 1e-8 * scale


def _entries(folder: Path) -> list[Path]:
    return sorted(folder.glob("*" + disk_cache.SUFFIX))


def test_cached_functions_give_bit_identical_results(cache_folder: Path) -> None:
    """A solver whose functions come from the cache (its block functions deserialised,
    the rest assembled from them) gives the very same bits as the one that built them,
    warm and cold."""
    scene = load_scene(DEZOYSA, {"solver.intervals": 8, **OFF})
    built = StaticsSolver(scene)
    assert built.build_source == "built" and len(_entries(cache_folder)) == 1
    loaded = StaticsSolver(scene)
    assert loaded.build_source == "disk cache"
    a, b = built.solve(), loaded.solve()
    assert np.array_equal(a.position, b.position)
    assert np.array_equal(a.tension_vector, b.tension_vector)
    near = scene.with_overrides({"layout.psi0_deg": 95.0})
    a2, b2 = built.solve(near, warm_start=a), loaded.solve(near, warm_start=b)
    assert np.array_equal(a2.tension_vector, b2.tension_vector)
    w, p = a._unknowns[1], built.params(mesh=a._unknowns[2])
    for f in (0, 1):
        assert np.array_equal(np.asarray(built._gj(w, p)[f].nonzeros()),
                              np.asarray(loaded._gj(w, p)[f].nonzeros()))


def test_a_second_process_loads_instead_of_building(cache_folder: Path) -> None:
    """A real second Python process with the same cache folder loads the functions (and
    says so) and returns the same bits as this process."""
    scene = load_scene(DEZOYSA, {"solver.intervals": 6, **OFF})
    first = StaticsSolver(scene)
    sol = first.solve()
    code = (
        "import json, sys\n"
        "from cable_ocp.scene import load_scene\n"
        "from cable_ocp.statics.solver import StaticsSolver\n"
        f"sc = load_scene({str(DEZOYSA)!r}, {{'solver.intervals': 6, "
        "'solver.error_estimate': False, 'solver.refine': False})\n"
        "sv = StaticsSolver(sc)\n"
        "s = sv.solve()\n"
        "print(json.dumps({'source': sv.build_source, "
        "'t': [float(x).hex() for x in s.tension_vector.ravel()]}))\n")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=env, timeout=300, check=True)
    data = json.loads(out.stdout.strip().splitlines()[-1])
    assert data["source"] == "disk cache"
    assert data["t"] == [float(x).hex() for x in sol.tension_vector.ravel()]


@pytest.mark.parametrize("damage", ["truncate", "flip payload", "flip header", "garbage",
                                    "foreign entry"])
def test_a_damaged_entry_is_rebuilt_never_used(cache_folder: Path, damage: str) -> None:
    """Truncated, bit-flipped (payload or key), garbage, or another scene's entry under
    this scene's name: the checks fail before anything is deserialised, the functions are
    rebuilt (the same answer as before), and the entry is rewritten and valid again."""
    scene = load_scene(DEZOYSA, {"solver.intervals": 4, **OFF})
    ref = StaticsSolver(scene).solve()
    (entry,) = _entries(cache_folder)
    raw = entry.read_bytes()
    if damage == "truncate":
        entry.write_bytes(raw[: len(raw) // 2])
    elif damage == "flip payload":
        i = len(raw) - 100
        entry.write_bytes(raw[:i] + bytes([raw[i] ^ 0x01]) + raw[i + 1:])
    elif damage == "flip header":
        i = raw.index(b"role") + 1
        entry.write_bytes(raw[:i] + bytes([raw[i] ^ 0x20]) + raw[i + 1:])
    elif damage == "garbage":
        entry.write_bytes(os.urandom(len(raw)))
    else:  # a valid entry of another structure (Berteaux) written under this name
        StaticsSolver(load_scene(PROBLEMS / "berteaux_mooring.toml",
                                 {"solver.intervals": 4, **OFF}))
        other = [e for e in _entries(cache_folder) if e != entry]
        entry.write_bytes(other[0].read_bytes())
    again = StaticsSolver(scene)
    assert again.build_source == "built"
    sol = again.solve()
    assert np.array_equal(sol.tension_vector, ref.tension_vector)
    assert StaticsSolver(scene).build_source == "disk cache"  # rewritten


def test_cache_switch_location_and_key(tmp_path: Path, monkeypatch: pytest.MonkeyPatch
                                       ) -> None:
    """CABLE_OCP_CACHE=0 writes nothing; without CABLE_OCP_CACHE_DIR the folder is
    $XDG_CACHE_HOME/cable_ocp; end values (parameters) share an entry, a change of
    structure (the drag law) gets its own."""
    monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(tmp_path / "off"))
    monkeypatch.setenv("CABLE_OCP_CACHE", "0")
    scene = load_scene(DEZOYSA, {"solver.intervals": 4, **OFF})
    assert StaticsSolver(scene).build_source == "built"
    assert disk_cache.cache_dir() is None and not (tmp_path / "off").exists()
    monkeypatch.delenv("CABLE_OCP_CACHE")
    monkeypatch.delenv("CABLE_OCP_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    folder = disk_cache.cache_dir()
    assert folder == tmp_path / "xdg" / "cable_ocp"
    StaticsSolver(scene)
    turned = scene.with_overrides({"layout.psi0_deg": 10.0})
    assert StaticsSolver(turned).build_source == "disk cache"
    assert len(_entries(folder)) == 1
    other = scene.with_overrides({"cable.drag_law": "vector"})
    assert StaticsSolver(other).build_source == "built"
    assert len(_entries(folder)) == 2


def test_an_unusable_cache_folder_is_skipped_silently(tmp_path: Path,
                                                      monkeypatch: pytest.MonkeyPatch
                                                      ) -> None:
    """CABLE_OCP_CACHE_DIR under a regular file (no folder can be made there, even as
    root, unlike a read-only folder) or in a read-only folder: nothing raised, the
    functions built, the answer that of a solver without a cache (bit-identical); a
    folder that does not exist yet is created and filled."""
    scene = load_scene(DEZOYSA, {"solver.intervals": 4, **OFF})
    monkeypatch.setenv("CABLE_OCP_CACHE", "0")
    ref = StaticsSolver(scene).solve()
    monkeypatch.delenv("CABLE_OCP_CACHE")
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder")
    read_only = tmp_path / "read_only"
    read_only.mkdir()
    read_only.chmod(0o555)
    try:
        for folder in (blocker / "cache", blocker, read_only):
            monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(folder))
            solver = StaticsSolver(scene)
            assert solver.build_source == "built"
            sol = solver.solve()
            assert sol.success and np.array_equal(sol.tension_vector, ref.tension_vector)
            if folder is not read_only or not os.access(read_only, os.W_OK):
                assert StaticsSolver(scene).build_source == "built"  # nothing stored
        assert blocker.read_text() == "not a folder"
    finally:
        read_only.chmod(0o755)
    fresh = tmp_path / "new" / "nested" / "cache"
    monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(fresh))
    assert StaticsSolver(scene).build_source == "built"
    assert len(_entries(fresh)) == 1
    assert StaticsSolver(scene).build_source == "disk cache"


def test_meshes_share_the_interval_functions(cache_folder: Path) -> None:
    """The interval functions do not depend on the number of intervals (the widths are
    parameters): the N/2 and N/4 solvers of the error estimate load the entry the N
    solver stored, and solve to the same residual tolerance."""
    scene = load_scene(DEZOYSA, {"solver.intervals": 16, **OFF})
    assert StaticsSolver(scene).build_source == "built"
    for n in (8, 4):
        coarse = StaticsSolver(scene, intervals=n)
        assert coarse.build_source == "disk cache"
        assert coarse.solve().success
    assert len(_entries(cache_folder)) == 1


def test_the_cache_keeps_to_its_size(cache_folder: Path, monkeypatch: pytest.MonkeyPatch
                                     ) -> None:
    """The least recently used entries go when the folder would exceed MAX_BYTES (an
    entry of an older version, never read again, among them), the newest always stays,
    and an entry above MAX_ENTRY_BYTES is not written (the solve is unaffected)."""
    import time

    cache_folder.mkdir(parents=True)
    stale = cache_folder / ("0" * 40 + "-newton" + disk_cache.SUFFIX)
    stale.write_bytes(b"x" * 1000)  # an old entry: its mtime is the oldest
    os.utime(stale, (time.time() - 3600, time.time() - 3600))
    # three structures (the interval functions do not depend on the number of intervals,
    # the smoothing enters them), entries of nearly the same size
    scenes = [load_scene(DEZOYSA, {"solver.smoothing": v, **OFF}) for v in (1e-5, 2e-5, 3e-5)]
    StaticsSolver(scenes[0])
    (first,) = [e for e in _entries(cache_folder) if e != stale]
    size = first.stat().st_size
    # room for two interval-function entries, not three, nor two and the stale one
    monkeypatch.setattr(disk_cache, "MAX_BYTES", int(2.5 * size))
    for sc in scenes[1:]:
        time.sleep(0.01)  # distinct modification times
        StaticsSolver(sc)
    kept = _entries(cache_folder)
    assert len(kept) == 2 and first not in kept and stale not in kept
    assert StaticsSolver(scenes[2]).build_source == "disk cache"  # the newest stayed
    assert StaticsSolver(scenes[0]).build_source == "built"  # the oldest went
    monkeypatch.setattr(disk_cache, "MAX_ENTRY_BYTES", size // 2)
    other = load_scene(DEZOYSA, {"solver.smoothing": 4e-5, **OFF})
    before = set(_entries(cache_folder))
    sol = StaticsSolver(other).solve()
    assert sol.success and set(_entries(cache_folder)) == before  # nothing written


def test_sweep_past_a_refined_point() -> None:
    """A sweep whose points are refined to different meshes (De Zoysa from 10 intervals
    with error estimates: 140 deg needs 80 intervals, its neighbours 40) extrapolates only
    through solutions of one mesh (it raised a broadcasting error before), and every
    point equals its own single solve to the accuracy asked (1e-6 relative, the
    scene's solver.accuracy, in the end forces)."""
    from cable_ocp.statics.solver import solve_collocation

    base = load_scene(DEZOYSA, {"solver.intervals": 10})
    angles = [110.0, 120.0, 130.0, 140.0, 150.0]
    sols = sweep(base, "layout.psi0_deg", angles, error_estimate=True)
    assert len({s.s.shape for s in sols}) > 1  # the case: meshes differ along the sweep
    for angle, sol in zip(angles, sols, strict=True):
        assert sol.converged, sol.message
        alone = solve_collocation(base.with_overrides({"layout.psi0_deg": angle}))
        ref = np.max(np.abs(alone.force_a))
        assert np.max(np.abs(sol.force_a - alone.force_a)) <= 2e-6 * ref


def test_catenary_parameter_matches_the_bracketing_search() -> None:
    """Newton's method on log(sinh(u)/u) gives the catenary parameter of the bracketing
    search it replaced in the free-length guess (1e-9 relative: both solve
    2a sinh(h/2a) = sqrt(L^2 - v^2), ill-conditioned as L nears the chord), from a nearly
    taut to a very slack cable, and satisfies that equation to 1e-12."""
    for h, v in [(1280.0, 2600.0), (229.0, 183.0), (100.0, -50.0), (10.0, 0.0)]:
        chord = math.hypot(h, v)
        for length in chord * (1.0 + np.geomspace(1e-6, 50.0, 25)):
            a = catenary_parameter(h, v, float(length))
            assert abs(a - catenary_parameter_bracketed(h, v, float(length))) <= 1e-9 * a
            target = math.sqrt(length * length - v * v)
            assert abs(2 * a * math.sinh(h / (2 * a)) - target) <= 1e-12 * target


def test_free_length_guess_unchanged_on_berteaux() -> None:
    """The faster free-length guess keeps Berteaux's short-cable branch (about 2.9 km,
    the catenary through both ends with 11.1466 kN at the buoy; the physical solution is
    3013 m with the current) and its end tension equals the prescribed one to 1e-9."""
    from cable_ocp.statics.initial_guess import free_length_guess

    scene = load_scene(PROBLEMS / "berteaux_mooring.toml")
    length = free_length_guess(scene)
    assert 2600.0 < length < 3500.0
    h, v = 1280.0, 2600.0
    a = catenary_parameter_bracketed(h, v, length)
    x0 = h / 2 - a * math.asinh(v / (2 * a * math.sinh(h / (2 * a))))
    tension = scene.cable.weight_in_water * a * math.cosh((h - x0) / a)
    assert abs(tension - 11146.6) <= 1e-9 * 11146.6
    assert Formulation(scene).scales.force > 0


def test_bench_sweep_json_alone_on_stdout(capsys: pytest.CaptureFixture[str]) -> None:
    """``bench sweep --json -`` prints only the JSON envelope, with the tracked keys at its
    top level (as ``bench-heave --json -`` puts its rows there). A short run (10
    intervals, one repeat, no second process); the only number checked is the agreement
    with solve_bvp, a method that shares no code with collocation: the end force within
    1e-4 of the largest (10 intervals of degree 3 are good to ~1e-6 here, solve_bvp to
    its 1e-8 tolerance). No timing is checked."""
    from cable_ocp.cli import main

    rc = main(["bench", "sweep", "--intervals", "10", "--repeats", "1", "--no-subprocess",
               "--quiet", "--json", "-"])
    out = capsys.readouterr().out
    assert rc == 0
    data = json.loads(out)  # the whole of stdout is one JSON document
    assert data["status"] == "ok"
    for key in ("warm_median_ms", "warm_iterations_median", "sweep_total_ms",
                "solve_bvp_median_ms", "max_rel_difference"):
        assert isinstance(data[key], (int, float)) and math.isfinite(data[key]), key
        assert data[key] >= 0, key
    assert data["warm_iterations_median"] >= 1
    assert data["max_rel_difference"] <= 1e-4
