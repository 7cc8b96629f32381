"""Mutation pass over hand-picked, meaningful mutations (not collected by pytest).

Usage (from the repository root)::

    python tests/mutation/run.py                 # every mutation, table at the end
    python tests/mutation/run.py --list          # the mutations, no run
    python tests/mutation/run.py --only NAME ... # some of them (names or area: physics, ...)
    python tests/mutation/run.py --baseline      # first run every test subset unmutated
    python tests/mutation/run.py --markdown      # the table as Markdown (docs/testing.md)
    python tests/mutation/run.py --only NAME --tests tests/x.py::test_y   # one test only

Each mutation is one small wrong change to the code (file, exact old text, new text), a
one-line description and the test subset that should notice it. The runner copies the
tracked tree once into a temporary directory, and for each mutation edits the copy, runs
``python -m pytest -x -q`` on the subset there (``PYTHONPATH`` = the copy, so the copy's
``cable_ocp`` is the one imported; checked before the first run), restores the file, and
reports **killed** (a test failed: which one), **survived** (the subset passed) or
**timeout** (counted as killed, reported separately). A mutation whose old text is not
found exactly once is reported as **stale**: the list must follow the code.

Why a script and not mutmut or cosmic-ray: the suite is slow (minutes; single tests of
seconds) on a 2-core machine, and the interesting bugs are the physics and control slips an
engineer makes (a dropped factor, a sign, an index off by the delay), not the operator swaps
those tools generate by the thousand, most of them in option parsing or error messages.
Hand-picked mutations with targeted subsets give a meaningful pass in about an hour; the
list is reviewed and extended with each issue (docs/testing.md).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


@dataclass(frozen=True)
class Mutation:
    """One mutation: ``old`` (exactly once in ``file``) replaced by ``new``."""

    name: str
    area: str
    file: str
    old: str
    new: str
    tests: tuple[str, ...]
    description: str


# -- test subsets -------------------------------------------------------------------------
EXTREME_REF = "tests/test_extreme.py::test_extreme_scene_against_independent_shooting"
STATICS = ("tests/test_physics.py", "tests/test_statics_closed_form.py", EXTREME_REF,
           "tests/test_statics_seeds.py", "tests/test_baseline_huang.py",
           "tests/test_seabed.py", "tests/test_segments.py")
SEABED = ("tests/test_seabed.py", EXTREME_REF, "tests/test_segments.py",
          "tests/test_statics_seeds.py")
TOWED = ("tests/test_towed.py",)
HEAVE = ("tests/heave/test_plant.py", "tests/heave/test_discrete.py", "tests/heave/test_sea.py",
         "tests/heave/test_stochastic.py", "tests/heave/test_lqr.py",
         "tests/heave/test_mpc.py", "tests/heave/test_simulate.py")
HEAVE_SIM = ("tests/heave/test_simulate.py", "tests/heave/test_examples.py")

PHYS, FORM, COLL, HEAVE_A = "physics", "statics/formulation", "statics/collocation", "heave"

MUTATIONS: tuple[Mutation, ...] = (
    # -- physics/ ---------------------------------------------------------------------------
    Mutation("drag-vector-normal-keeps-tangential", PHYS, "cable_ocp/physics/drag.py",
             "un = u - ca.dot(u, t) * t", "un = u", STATICS,
             "vector law: the normal flow is not stripped of its tangential part"),
    Mutation("drag-tangential-no-perimeter", PHYS, "cable_ocp/physics/drag.py",
             "ct = 0.5 * rho * tangential_drag * math.pi * diameter",
             "ct = 0.5 * rho * tangential_drag * diameter", STATICS,
             "tangential drag on D instead of the wetted perimeter pi D"),
    Mutation("drag-componentwise-drops-binormal", PHYS, "cable_ocp/physics/drag.py",
             "comp = smooth_abs(ub, delta) * ub * eb + smooth_abs(un, delta) * un * en",
             "comp = smooth_abs(un, delta) * un * en", STATICS,
             "componentwise law: the e_b component of the normal flow is lost"),
    Mutation("drag-componentwise-en-flipped", PHYS, "cable_ocp/physics/drag.py",
             "n = ca.cross(t, b)", "n = ca.cross(b, t)", STATICS,
             "componentwise law: e_n = e_b x t instead of t x e_b"),
    Mutation("drag-vertical-blend-swapped", PHYS, "cable_ocp/physics/drag.py",
             "return w * comp + (1.0 - w) * _normal_vector_law(u, t, delta)",
             "return (1.0 - w) * comp + w * _normal_vector_law(u, t, delta)", STATICS,
             "vertical blend weights swapped (vector law away from vertical)"),
    Mutation("smooth-abs-delta-not-squared", PHYS, "cable_ocp/physics/smooth.py",
             "return ca.sqrt(u * u + delta * delta)", "return ca.sqrt(u * u + delta)",
             STATICS, "smooth modulus sqrt(u^2 + delta) instead of sqrt(u^2 + delta^2)"),
    Mutation("current-profile-not-clamped", PHYS, "cable_ocp/physics/current.py",
             "seg = ca.fmin(ca.fmax(z - knots[k], 0.0), knots[k + 1] - knots[k])",
             "seg = ca.fmax(z - knots[k], 0.0)", STATICS,
             "current profile extrapolated beyond each knot instead of piecewise linear"),
    Mutation("current-ignores-ramp-scale", PHYS, "cable_ocp/physics/current.py",
             "return scale * ca.vertcat(ux, uy, 0)", "return ca.vertcat(ux, uy, 0)",
             ("tests/test_extreme.py",), "the current ramp's scale is ignored"),
    Mutation("seabed-friction-sign", PHYS, "cable_ocp/physics/seabed.py",
             "return w * e[2] + seabed.friction * w * float(normal(seabed)[2])",
             "return w * e[2] - seabed.friction * w * float(normal(seabed)[2])", SEABED,
             "seabed friction raises the tension towards the anchor"),
    Mutation("seabed-grounded-integral-sign", PHYS, "cable_ocp/physics/seabed.py",
             "return ca.if_else(k > 0, t_td * g_eff - 0.5 * k * g_eff * g_eff,",
             "return ca.if_else(k > 0, t_td * g_eff + 0.5 * k * g_eff * g_eff,", SEABED,
             "stretch of the grounded part integrates the wrong tension"),
    Mutation("seabed-normal-slope-sign", PHYS, "cable_ocp/physics/seabed.py",
             "[-math.sin(a) * math.cos(h), -math.sin(a) * math.sin(h), math.cos(a)]",
             "[math.sin(a) * math.cos(h), math.sin(a) * math.sin(h), math.cos(a)]", SEABED,
             "sloping seabed: normal tilted the wrong way"),
    # -- statics/formulation.py ---------------------------------------------------------------
    Mutation("drag-stretch-factor-dropped", FORM, "cable_ocp/statics/formulation.py",
             "            f = f + stretch * fd", "            f = f + fd", STATICS,
             "drag per stretched length not scaled by (1 + T/EA) (deep_water)"),
    Mutation("position-stretch-dropped", FORM, "cable_ocp/statics/formulation.py",
             "drho = lam * stretch * t\n", "drho = lam * t\n", STATICS,
             "dr/ds without Hooke's stretch (inextensible geometry)"),
    Mutation("weight-sign", FORM, "cable_ocp/statics/formulation.py",
             "        # loads per unstretched length, N/m\n"
             "        f = ca.vertcat(0, 0, -cab.weight_in_water)",
             "        # loads per unstretched length, N/m\n"
             "        f = ca.vertcat(0, 0, cab.weight_in_water)", STATICS,
             "weight in water acts upwards"),
    Mutation("end-force-sign", FORM, "cable_ocp/statics/formulation.py",
             "sign = -1.0 if at_a else 1.0", "sign = 1.0 if at_a else -1.0", STATICS,
             "prescribed end loads applied with the wrong sign"),
    Mutation("current-height-unscaled", FORM, "cable_ocp/statics/formulation.py",
             "u = current_velocity(env.current, sc.length * rho_[2], cscale)",
             "u = current_velocity(env.current, rho_[2], cscale)", STATICS,
             "current profile evaluated at the scaled height"),
    Mutation("touchdown-stretch-dropped", FORM, "cable_ocp/statics/formulation.py",
             "dist = g + sc.force / cab.axial_stiffness * grounded_tension_integral(tmag, k, g)",
             "dist = g + 0.0 * grounded_tension_integral(tmag, k, g)", SEABED,
             "grounded part not stretched"),
    Mutation("touchdown-not-tangent", FORM, "cable_ocp/statics/formulation.py",
             "res.append(ca.dot(tau, ca.DM(n)))", "res.append(ca.dot(tau, ca.DM(n)) - 0.01 * tmag)",
             SEABED, "lift-off at 0.6 deg to the seabed instead of tangent"),
    Mutation("tension-residual-unsquared", FORM, "cable_ocp/statics/formulation.py",
             "return ca.dot(x[3:6], x[3:6]) - tension * tension",
             "return ca.dot(x[3:6], x[3:6]) - tension", STATICS,
             "prescribed end tension compared with |T|^2"),
    Mutation("body-drag-no-half", FORM, "cable_ocp/statics/formulation.py",
             "load = load + 0.5 * env.water_density * body.drag_coefficient",
             "load = load + env.water_density * body.drag_coefficient",
             ("tests/test_segments.py", "tests/test_towed.py"),
             "a body's drag 1/2 rho C_d A |U| U without the 1/2"),
    Mutation("beam-moment-sign", FORM, "cable_ocp/statics/formulation.py",
             "stretch * (t[2] * tau[0] - t[0] * tau[2])",
             "stretch * (t[0] * tau[2] - t[2] * tau[0])", TOWED,
             "bending: shear enters the moment equation with the wrong sign"),
    Mutation("force-scale-x10", FORM, "cable_ocp/statics/formulation.py",
             "fref = max(abs(c.weight_in_water) for c in self.lines) * ell",
             "fref = max(abs(c.weight_in_water) for c in self.lines) * ell * 10.0",
             STATICS, "force scale 10x larger (scaling only)"),
    # -- statics/collocation.py ---------------------------------------------------------------
    Mutation("collocation-derivative-times-h", COLL, "cable_ocp/statics/collocation.py",
             "ca.mtimes(xcols, ca.DM(cmat[:, j].tolist())) / h",
             "ca.mtimes(xcols, ca.DM(cmat[:, j].tolist())) * h",
             STATICS, "collocation derivative scaled by h instead of 1/h"),
    Mutation("lagrange-end-weight", COLL, "cable_ocp/statics/collocation.py",
             "dvec[j] = np.prod([(1.0 - pts[m])", "dvec[j] = np.prod([(0.5 - pts[m])", STATICS,
             "interval end state from the polynomial at mid-interval"),
    Mutation("grounded-length-not-subtracted", COLL, "cable_ocp/statics/collocation.py",
             "lam = w[self.i_lam] if self.free_length else p[P_LENGTH] - g",
             "lam = w[self.i_lam] if self.free_length else p[P_LENGTH]", SEABED,
             "suspended length of a grounded single cable = the whole length"),
    Mutation("segment-grounded-length-not-subtracted", COLL,
             "cable_ocp/statics/collocation.py",
             "lam, dlam = lam - z[-1], -1.0", "lam, dlam = lam, 0.0", SEABED,
             "interval blocks (single cable, first segment): grounded length not taken off"),
    Mutation("joint-load-sign", COLL, "cable_ocp/statics/collocation.py",
             "x_start[3:6] - (x_prev[3:6] - load)", "x_start[3:6] - (x_prev[3:6] + load)",
             ("tests/test_segments.py",), "point body load applied with the wrong sign"),
    Mutation("node-s-ignores-grounded", COLL, "cable_ocp/statics/collocation.py",
             "return g + sig * (length - g)", "return sig * length", SEABED,
             "arc length of the suspended nodes ignores the grounded part"),
    Mutation("mesh-order-swapped", COLL, "cable_ocp/statics/collocation.py",
             'return 2 * self.degree if self.scheme == "legendre" else 2 * self.degree - 1',
             'return 2 * self.degree - 1 if self.scheme == "legendre" else 2 * self.degree',
             STATICS + ("tests/test_statics_convergence.py",),
             "nominal orders of Gauss-Legendre and Radau swapped"),
    # -- heave/ -------------------------------------------------------------------------------
    Mutation("mpc-applied-newest-command", HEAVE_A, "cable_ocp/heave/mpc.py",
             "c[n] = 1.0\n                return c, 0.0",
             "c[n + d - 1] = 1.0\n                return c, 0.0", HEAVE,
             "limit rows use the newest buffered command, not the applied one"),
    Mutation("kalman-intensity-one", HEAVE_A, "cable_ocp/heave/stochastic.py",
             "QN = np.array([[WHITE_NOISE_INTENSITY]])", "QN = np.array([[1.0]])", HEAVE,
             "Kalman filter's process-noise intensity 1 instead of pi"),
    Mutation("sea-noise-variance-doubled", HEAVE_A, "cable_ocp/heave/simulate.py",
             "Qd = discretize_noise(A, G, WHITE_NOISE_INTENSITY, h_sim)",
             "Qd = discretize_noise(A, G, 2 * WHITE_NOISE_INTENSITY, h_sim)", HEAVE,
             "simulated sea driven with twice the noise variance"),
    Mutation("nmpc-constructor-raises", HEAVE_A, "cable_ocp/heave/mpc.py",
             "        s = mpc.settings\n        p = mpc.plant\n",
             "        raise RuntimeError('mutant')\n        s = mpc.settings\n"
             "        p = mpc.plant\n", HEAVE,
             "the IPOPT MPC cannot be built"),
    Mutation("nmpc-rk4-model-raises", HEAVE_A, "cable_ocp/heave/mpc.py",
             "(6.3), RK4 with 2 substeps.\"\"\"\n",
             "(6.3), RK4 with 2 substeps.\"\"\"\n        raise RuntimeError('mutant')\n", HEAVE,
             "the IPOPT MPC's nonlinear-unit model (6.3) cannot be built"),
    Mutation("nmpc-quadratic-damping-sign", HEAVE_A, "cable_ocp/heave/mpc.py",
             "corr = (p.b * xd - bnl * xd * cs.sqrt(xd**2 + 1e-6)) / p.a",
             "corr = (p.b * xd + bnl * xd * cs.sqrt(xd**2 + 1e-6)) / p.a", HEAVE,
             "IPOPT MPC: quadratic damping (6.3) drives instead of damps"),
    Mutation("nmpc-keeps-linear-damping", HEAVE_A, "cable_ocp/heave/mpc.py",
             "corr = (p.b * xd - bnl * xd * cs.sqrt(xd**2 + 1e-6)) / p.a",
             "corr = (-bnl * xd * cs.sqrt(xd**2 + 1e-6)) / p.a", HEAVE,
             "IPOPT MPC: (6.3) adds to the linear damping instead of replacing it"),
    Mutation("mpc-terminal-cost-dropped", HEAVE_A, "cable_ocp/heave/mpc.py",
             "Qk = self.P if k == N else Qz", "Qk = Qz", HEAVE,
             "MPC's terminal weight = stage weight, not the DARE solution"),
    Mutation("mpc-speed-row-sign", HEAVE_A, "cable_ocp/heave/mpc.py",
             "add(k, K * (cz - eu), K * cu, s.speed_max)",
             "add(k, K * (cz + eu), K * cu, s.speed_max)", HEAVE,
             "winch speed row K (v + u) instead of K (v - u)"),
    Mutation("mpc-stroke-rows-start-late", HEAVE_A, "cable_ocp/heave/mpc.py",
             "for k in range(1, N + 1):\n                add(k, eu, 0.0, s.stroke_max)",
             "for k in range(2, N + 1):\n                add(k, eu, 0.0, s.stroke_max)", HEAVE,
             "stroke limit not imposed at the first predicted sample"),
    Mutation("mpc-tension-limit-sign", HEAVE_A, "cable_ocp/heave/mpc.py",
             "smin = (s.tension_min - s.static_tension) / kc",
             "smin = (s.static_tension - s.tension_min) / kc", HEAVE,
             "tension limit turned into a stretch floor above the static value"),
    Mutation("mpc-command-rate-sign", HEAVE_A, "cable_ocp/heave/mpc.py",
             "add(k, np.zeros(nz), 1.0, s.command_rate_max, cp=-1.0)",
             "add(k, np.zeros(nz), 1.0, s.command_rate_max, cp=1.0)", HEAVE,
             "command-rate row limits u0_k + u0_{k-1}"),
    Mutation("plant-stretch-output-sign", HEAVE_A, "cable_ocp/heave/plant.py",
             "C = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]])",
             "C = np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 0.0]])", HEAVE,
             "cable stretch x0 + u + x instead of x0 + u - x"),
    Mutation("plant-taylor-delay-coefficient", HEAVE_A, "cable_ocp/heave/plant.py",
             "A = np.array([[0.0, 1.0], [-2.0 / tau**2, -2.0 / tau]])",
             "A = np.array([[0.0, 1.0], [-2.0 / tau**2, -1.0 / tau]])", HEAVE,
             "Taylor delay model (6.13) with the wrong damping term"),
    Mutation("discrete-delay-fraction", HEAVE_A, "cable_ocp/heave/discrete.py",
             "tp = tau - (d - 1) * h", "tp = tau - d * h", HEAVE,
             "ZOH with delay: one sample too little delay"),
    Mutation("discrete-cost-missing-h", HEAVE_A, "cable_ocp/heave/discrete.py",
             "Rz = W[n:, n:] + R * h", "Rz = W[n:, n:] + R", HEAVE,
             "sampled command cost R instead of R h (undelayed)"),
    Mutation("discrete-noise-intensity-ignored", HEAVE_A, "cable_ocp/heave/discrete.py",
             "M[:n, n:] = W * G @ G.T", "M[:n, n:] = G @ G.T", HEAVE,
             "sampled noise covariance ignores the intensity"),
    Mutation("variance-without-pi", HEAVE_A, "cable_ocp/heave/stochastic.py",
             "return float(WHITE_NOISE_INTENSITY * (C @ P @ C.T)[0, 0])",
             "return float((C @ P @ C.T)[0, 0])", HEAVE,
             "output variance P11 without the factor pi (two-sided reading)"),
    Mutation("sea-thesis-constant", HEAVE_A, "cable_ocp/heave/sea.py",
             "THESIS_S0_FACTOR = 1.8861", "THESIS_S0_FACTOR = 1.9861", HEAVE,
             "shaping filter (6.22) constant misprinted"),
    Mutation("lqr-crossing-phase-sign", HEAVE_A, "cable_ocp/heave/lqr.py",
             "t0 = (-np.angle(z)) % (2 * np.pi) / wc", "t0 = (np.angle(z)) % (2 * np.pi) / wc",
             HEAVE, "delay margin from the conjugate phase"),
    Mutation("sim-quadratic-damping-unsigned", HEAVE_A, "cable_ocp/heave/simulate.py",
             "damp = bq * s[1] * abs(s[1]) if quad else b * s[1]",
             "damp = bq * s[1] * s[1] if quad else b * s[1]", HEAVE_SIM,
             "simulated (6.3) unit: b x'^2 instead of b |x'| x'"),
    Mutation("sim-delay-one-fine-step-short", HEAVE_A, "cable_ocp/heave/simulate.py",
             "nring = nd_fine + 1", "nring = nd_fine", HEAVE_SIM,
             "simulated delay one fine step (0.01 s) short"),
    Mutation("sim-lqg-buffer-not-reset", HEAVE_A, "cable_ocp/heave/simulate.py",
             "xh[self.n :] = z[self.n :]", "pass", HEAVE_SIM,
             "LQG estimate of its own past commands not reset to the known values"),
)


def _copy_tree(dst: Path) -> None:
    """Copy the git-tracked files of the working tree (as they are now) into ``dst``."""
    out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True,
                         capture_output=True).stdout.decode()
    for rel in filter(None, out.split("\0")):
        src = ROOT / rel
        if not src.is_file():
            continue
        target = dst / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, target)


def _pytest(tree: Path, tests: tuple[str, ...], timeout: float) -> tuple[str, str, float]:
    """Run the subset in ``tree``; return (status, first failing test, seconds)."""
    env = dict(os.environ, PYTHONPATH=str(tree), PYTHONDONTWRITEBYTECODE="1")
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "-rf",
           *tests]
    t0 = time.perf_counter()
    try:
        res = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True,
                             timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout", "", time.perf_counter() - t0
    dt = time.perf_counter() - t0
    if res.returncode == 0:
        return "survived", "", dt
    m = re.search(r"^(?:FAILED|ERROR) (\S+)", res.stdout, re.M)
    who = m.group(1) if m else f"pytest exit {res.returncode}"
    return "killed", who, dt


def _check_imports(tree: Path) -> None:
    env = dict(os.environ, PYTHONPATH=str(tree))
    out = subprocess.run([sys.executable, "-c", "import cable_ocp; print(cable_ocp.__file__)"],
                         cwd=tree, env=env, capture_output=True, text=True, check=True)
    if not Path(out.stdout.strip()).resolve().is_relative_to(tree.resolve()):
        raise SystemExit(f"the copy is not what gets imported: {out.stdout.strip()}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="+", default=None,
                    help="mutation names or areas (physics, statics/formulation, "
                         "statics/collocation, heave)")
    ap.add_argument("--list", action="store_true", help="list the mutations and exit")
    ap.add_argument("--baseline", action="store_true",
                    help="first run every selected subset on the unmutated copy")
    ap.add_argument("--timeout", type=float, default=900.0, help="per mutation, s")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    ap.add_argument("--tests", nargs="+", default=None,
                    help="run these tests instead of each mutation's subset")
    args = ap.parse_args(argv)
    muts = [m for m in MUTATIONS
            if args.only is None or m.name in args.only or m.area in args.only]
    if args.only and not muts:
        raise SystemExit(f"no mutation matches {args.only}")
    if args.list:
        for m in muts:
            print(f"{m.name:40s} {m.area:20s} {m.file}\n    {m.description}\n"
                  f"    tests: {' '.join(m.tests)}")
        return 0
    rows = []
    with tempfile.TemporaryDirectory(prefix="cable_ocp_mut_") as tmp:
        tree = Path(tmp)
        _copy_tree(tree)
        _check_imports(tree)
        if args.baseline:
            for tests in dict.fromkeys(m.tests for m in muts):
                st, who, dt = _pytest(tree, tests, args.timeout)
                ok = "passes" if st == "survived" else f"FAILS ({st} {who})"
                print(f"baseline {' '.join(tests)}: {ok} ({dt:.0f} s)", flush=True)
                if st != "survived":
                    raise SystemExit("the unmutated code fails its subset: fix that first")
        for m in muts:
            path = tree / m.file
            text = path.read_text()
            if text.count(m.old) != 1:
                rows.append((m, "stale", f"old text found {text.count(m.old)} times", 0.0))
                print(f"{m.name}: stale", flush=True)
                continue
            path.write_text(text.replace(m.old, m.new))
            try:
                st, who, dt = _pytest(tree, tuple(args.tests or m.tests), args.timeout)
            finally:
                path.write_text(text)
            rows.append((m, st, who, dt))
            print(f"{m.name}: {st} {who} ({dt:.0f} s)", flush=True)
    print()
    if args.markdown:
        print("| mutation | area | result | first failing test | s |")
        print("|---|---|---|---|---|")
        for m, st, who, dt in rows:
            print(f"| `{m.name}` | {m.area} | {st} | {who.replace('|', '/')} | {dt:.0f} |")
    else:
        for m, st, who, dt in rows:
            print(f"{m.name:40s} {m.area:20s} {st:9s} {dt:6.0f} s  {who}")
    n_kill = sum(st in ("killed", "timeout") for _, st, _, _ in rows)
    print(f"\n{n_kill}/{len(rows)} killed; survivors: "
          f"{', '.join(m.name for m, st, _, _ in rows if st == 'survived') or 'none'}")
    return 0 if all(st != "stale" for _, st, _, _ in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
