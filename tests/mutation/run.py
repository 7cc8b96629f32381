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
Hand-picked mutations with targeted subsets give a meaningful pass in about 11 minutes; the
list is reviewed and extended with each issue (docs/testing.md).
"""

from __future__ import annotations

import argparse
import importlib.util
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
FIGS = "tests/test_plots_dynamics.py"
STORE = "tests/test_batch_store.py"
INTERRUPT = "tests/test_interrupt.py"
EXTREME_REF = "tests/test_extreme.py::test_extreme_scene_against_independent_shooting"
STATICS = ("tests/test_physics.py", "tests/test_statics_closed_form.py", EXTREME_REF,
           "tests/test_statics_seeds.py", "tests/test_baseline_huang.py",
           "tests/test_seabed.py", "tests/test_segments.py")
SEABED = ("tests/test_seabed.py", EXTREME_REF, "tests/test_segments.py",
          "tests/test_statics_seeds.py")
TOWED = ("tests/test_towed.py",)
LAWS = ("tests/test_physics_laws.py",)
LINE_TYPES = ("tests/test_line_types.py",)
HEAVE = ("tests/heave/test_plant.py", "tests/heave/test_discrete.py", "tests/heave/test_sea.py",
         "tests/heave/test_stochastic.py", "tests/heave/test_lqr.py",
         "tests/heave/test_mpc.py", "tests/heave/test_simulate.py")
SLACK_ST = "tests/heave/test_slack_status.py::test_"
TEXT = "tests/test_text_face.py::test_"
MOORING_CHECKS = "tests/mooring/test_checks.py::test_"
MOORDYN = "tests/test_moordyn_files.py"
HEAVE_SIM = ("tests/heave/test_simulate.py", "tests/heave/test_examples.py",
             "tests/heave/test_closed_loop.py")
# dynamics: whole files where every test is quick, else the non-slow test ids
AXIAL = ("tests/dynamics/test_axial.py", "tests/dynamics/test_axial_huang.py")
_LMP = "tests/dynamics/test_lumped.py::test_"
LUMPED = ("tests/dynamics/test_lumped_modes.py", _LMP + "energy_conserved_in_air",
          _LMP + "bdf2_dissipates_and_midpoint_does_not",
          _LMP + "damped_vertical_run_settles_to_the_statics_solution",
          _LMP + "damped_run_in_current_settles_to_the_discrete_statics",
          _LMP + "vertical_line_equals_axial_model",
          _LMP + "forced_heave_against_viscoelastic_rod_closed_form",
          _LMP + "abrupt_start_at_1256_goes_slack", "tests/dynamics/test_lumped_robust.py")
_PLN = "tests/dynamics/test_planar.py::test_"
PLANAR = tuple(_PLN + t for t in (
    "vertical_case_equals_axial_model", "planar_case_equals_lumped3d",
    "in_plane_modes_equal_lumped3d", "hanging_cable_with_tip_mass_against_bessel",
    "taut_string_frequencies", "energy_conserved_in_air",
    "damped_vertical_run_settles_to_the_statics_solution",
    "damped_run_in_current_settles_to_the_statics_solution",
    "slack_is_detected_where_and_when_the_wave_front_predicts",
    "huang_4_5_5_static_elongation_and_resonant_length", "anchored_catenary_start_and_payout",
    "pendulum_and_spring_modes_use_the_units_added_mass_per_axis")) + (
    "tests/dynamics/test_axial.py::test_payout_wave_against_dalembert",)

PHYS, FORM, COLL, HEAVE_A = "physics", "statics/formulation", "statics/collocation", "heave"
CAT = "statics/catenary"
DYN = "dynamics"
AX_F, LM_F, PL_F, MO_F = ("cable_ocp/dynamics/axial.py", "cable_ocp/dynamics/lumped.py",
                          "cable_ocp/dynamics/planar.py", "cable_ocp/scene/motion.py")
LK_F, LE_F = "cable_ocp/dynamics/lumped_kernel.py", "cable_ocp/dynamics/lumped_equations.py"
_MI = "tests/dynamics/test_model_interface.py::test_"
SLACK_TIME = _MI + "the_slack_time_is_the_end_of_the_first_step_with_a_slack_element"
OUTPUT_GRID = _MI + "the_output_grid_is_every_kth_step_when_the_ratio_is_inexact_in_binary"
ENDS = _MI + "the_end_positions_are_the_top_path_and_the_unit_node"
FAILED_START = _MI + "a_failed_static_start_is_an_empty_failed_history"
CHART = ("tests/dynamics/test_lumped_modes.py::"
         "test_the_deployment_chart_of_a_segmented_line_pays_out_the_top_segment")
BODY = "tests/dynamics/test_lumped.py::test_a_point_body_loads_exactly_its_joints_node"
VL_F = "cable_ocp/dynamics/vertical_line.py"  # the axial models' coefficients
_BT = "tests/dynamics/test_bench_cli.py::test_"
BENCH_MD = _BT + "moordyn_is_driven_consistently_and_compared_on_cable_ocps_force"
BENCH_REF = _BT + "reference_extrapolates_and_every_row_is_compared_with_it"
MP_F, MP_T = "cable_ocp/bench/moorpy_systems.py", "tests/test_moorpy_systems.py::test_"

SYS_EQ = "tests/mooring/test_equilibrium.py"
SYS_CLI = "tests/mooring/test_system_cli.py"

MUTATIONS: tuple[Mutation, ...] = (
    # -- physics/ ---------------------------------------------------------------------------
    Mutation("drag-vector-normal-keeps-tangential", PHYS, "cable_ocp/physics/drag.py",
             "un = u - ca.dot(u, t) * t", "un = u", STATICS,
             "vector law: the normal flow is not stripped of its tangential part"),
    Mutation("drag-tangential-no-perimeter", PHYS, "cable_ocp/physics/drag.py",
             "            0.5 * rho * tangential_drag * math.pi * diameter)",
             "            0.5 * rho * tangential_drag * diameter)", STATICS,
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
             "return scale * ca.vertcat(vx, vy, 0)", "return ca.vertcat(vx, vy, 0)",
             ("tests/test_extreme.py",), "the current ramp's scale is ignored"),
    Mutation("seabed-friction-sign", PHYS, "cable_ocp/physics/seabed.py",
             "return w * e[2] + friction * w * normal_z",
             "return w * e[2] - friction * w * normal_z", SEABED,
             "seabed friction raises the tension towards the anchor"),
    Mutation("seabed-grounded-integral-sign", PHYS, "cable_ocp/physics/seabed.py",
             "return ca.if_else(k > 0, t_td * g_eff - 0.5 * k * g_eff * g_eff,",
             "return ca.if_else(k > 0, t_td * g_eff + 0.5 * k * g_eff * g_eff,", SEABED,
             "stretch of the grounded part integrates the wrong tension"),
    Mutation("seabed-normal-slope-sign", PHYS, "cable_ocp/physics/seabed.py",
             "[-math.sin(a) * math.cos(h), -math.sin(a) * math.sin(h), math.cos(a)]",
             "[math.sin(a) * math.cos(h), math.sin(a) * math.sin(h), math.cos(a)]", SEABED,
             "sloping seabed: normal tilted the wrong way"),
    Mutation("point-drag-no-half", PHYS, "cable_ocp/physics/drag.py",
             "        return half_rho * speed * ca.vertcat(",
             "        return 2.0 * half_rho * speed * ca.vertcat(", LAWS + TOWED,
             "point body: vector-law drag rho C_D S |u| u without the 1/2"),
    Mutation("drag-numpy-tangential-unsigned", PHYS, "cable_ocp/physics/drag.py",
             "return kn * normal + kt * (mod(ut) * ut)[..., None] * t",
             "return kn * normal + kt * (ut * ut)[..., None] * t",
             LAWS + ("tests/test_baseline_huang.py",),
             "numpy line drag (the baselines): tangential u_t^2 instead of |u_t| u_t"),
    Mutation("kernel-drag-jacobian-tangential", PHYS, "cable_ocp/physics/drag.py",
             "* (st + ut * ut / st) * ttt", "* st * ttt", LAWS,
             "kernel form: the tangential drag's Jacobian misses d|u_t|/du_t u_t"),
    Mutation("elasticity-smoothing-not-squared", PHYS, "cable_ocp/physics/elasticity.py",
             "return 0.5 * (u + _sqrt(u * u + slack_smoothing * slack_smoothing))",
             "return 0.5 * (u + _sqrt(u * u + slack_smoothing))", LAWS,
             "no-compression law: sqrt((EA e)^2 + delta_T) (a 0.05 N floor, not 0.005 N)"),
    Mutation("added-mass-projectors-swapped", PHYS, "cable_ocp/physics/added_mass.py",
             "return normal * (ca.SX.eye(3) - tt) + tangential * tt",
             "return normal * tt + tangential * (ca.SX.eye(3) - tt)", LAWS,
             "line added mass (5.2): the normal part along the tangent"),
    Mutation("current-numpy-components-swapped", PHYS, "cable_ocp/physics/current.py",
             "return np.interp(z, knots, ux), np.interp(z, knots, uy)",
             "return np.interp(z, knots, uy), np.interp(z, knots, ux)",
             LAWS + ("tests/test_statics_kinks.py",),
             "numpy current profile: the components swapped"),
    Mutation("line-types-cdax-divided-by-pi", PHYS, "cable_ocp/physics/line_types.py",
             'tangential_drag=c("Cd_ax")', 'tangential_drag=c("Cd_ax") / math.pi', LINE_TYPES,
             "standard line types: MoorPy's CdAx (already on pi d) divided by pi again"),
    Mutation("line-types-chain-mass-coefficient", PHYS, "cable_ocp/physics/line_types.py",
             '"mass_d2": 20.0e3', '"mass_d2": 19.9e3', LINE_TYPES,
             "standard line types: studless chain mass 19.9e3 d^2 instead of the yaml's 20.0e3"),
    Mutation("line-types-fibre-dvol-without-4-over-pi", PHYS, "cable_ocp/physics/line_types.py",
             '(c("mass_d2") / c("density")) * (4 / math.pi)', '(c("mass_d2") / c("density"))',
             LINE_TYPES, "standard line types: fibre d_vol from the density without 4 / pi"),
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
             "u = profile_velocity(sc.length * rho_[2], cur.z, cur.ux, cur.uy, cscale)",
             "u = profile_velocity(rho_[2], cur.z, cur.ux, cur.uy, cscale)", STATICS,
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
             "rho=env.water_density, delta=self.scene.solver.smoothing)",
             "rho=2.0 * env.water_density, delta=self.scene.solver.smoothing)",
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
             "inv_h = 1.0 / h", "inv_h = h",
             STATICS, "collocation derivative scaled by h instead of 1/h"),
    Mutation("lagrange-end-weight", COLL, "cable_ocp/statics/collocation.py",
             "dvec[j] = np.prod([(1.0 - pts[m])", "dvec[j] = np.prod([(0.5 - pts[m])", STATICS,
             "interval end state from the polynomial at mid-interval"),
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
    Mutation("mesh-order-swapped", COLL, "cable_ocp/statics/mesh.py",
             'return 2 * self.degree if self.scheme == "legendre" else 2 * self.degree - 1',
             'return 2 * self.degree - 1 if self.scheme == "legendre" else 2 * self.degree',
             STATICS + ("tests/test_statics_convergence.py",),
             "nominal orders of Gauss-Legendre and Radau swapped"),
    Mutation("seabed-check-ignores-radius", COLL, "cable_ocp/statics/checks.py",
             "if z[i_low] < -max(tol, radius):", "if z[i_low] < -tol:",
             ("tests/test_contract.py::test_a_dip_within_the_cable_radius_warns_and_beyond_it_"
              "fails",), "a centreline within the cable's radius of the seabed plane "
             "reported as below_seabed"),
    Mutation("lu-symbolic-drops-fill", COLL, "cable_ocp/numerics/sparse_lu.py",
             "if (i > j) { if (nl + 1 > cap) return -1; li[nl++] = i; }\n      }\n    }",
             "if (0) { if (nl + 1 > cap) return -1; li[nl++] = i; }\n      }\n    }",
             ("tests/test_statics_compile.py",),
             "the kept LU pattern misses the fill that columns of L spread into later ones"),
    Mutation("lu-refactor-keeps-tiny-pivots", COLL, "cable_ocp/numerics/sparse_lu.py",
             "chk != 0 || !(fabs(piv) >= tau * big) || !(fabs(piv) > 0)", "chk != 0",
             ("tests/test_statics_compile.py",),
             "the refactorisation uses the kept pivot order whatever the pivot's size"),
    Mutation("lu-refactor-ignores-growth", COLL, "cable_ocp/numerics/sparse_lu.py",
             "if (gmax > 0 && umax > gmax * amax)", "if (0)",
             ("tests/test_statics_compile.py",),
             "no growth check on the kept pivot order (threshold pivoting alone)"),
    Mutation("lu-singular-flag-sticky", COLL, "cable_ocp/numerics/sparse_lu.py",
             "            self._singular = False\n            return",
             "            return", ("tests/test_statics_compile.py",),
             "after a singular matrix every later matrix gives non-finite steps"),
    Mutation("interpreted-kernel-never-keeps-lu", COLL, "cable_ocp/statics/line_solver.py",
             "if chord and not self._kernel.can_chord and sparse_lu.available():",
             "if False:", ("tests/test_statics_compile.py",),
             "interpreted warm solves take full Newton steps (no kept LU factors)"),
    Mutation("chord-steps-on-a-moving-mesh", COLL, "cable_ocp/statics/line_solver.py",
             "chord = warm and not moving", "chord = warm",
             ("tests/test_statics_kinks.py",),
             "a tracking mesh is refitted after chord steps instead of moved by Newton"),
    # -- statics/catenary.py and numerics/quadrature.py --------------------------------------
    Mutation("catenary-dz-elastic-sign", CAT, "cable_ocp/statics/catenary.py",
             "dr[:, 2] = -0.5 * (xa + xb) * lin - xt", "dr[:, 2] = 0.5 * (xa + xb) * lin - xt",
             ("tests/test_statics_catenary.py",),
             "elastic catenary: the stretch term of the derived (2.33) with the wrong sign"),
    Mutation("catenary-end-b-force-sign", CAT, "cable_ocp/statics/catenary.py",
             "v[i] = -FLIP[i] * fb - total_load[i] - weight[i]",
             "v[i] = FLIP[i] * fb - total_load[i] - weight[i]",
             ("tests/test_statics_catenary.py",),
             "elastic catenary: a force given at end_b enters (2.40)-(2.42) with the wrong sign"),
    Mutation("touchdown-suspended-length-wrong", CAT, "cable_ocp/statics/catenary.py",
             "ls = math.sqrt(h * h + 2 * h * a)\n        return",
             "ls = math.sqrt(h * h + 3 * h * a)\n        return",
             ("tests/test_statics_catenary.py",),
             "touchdown guess: suspended length of a catenary that does not leave the seabed "
             "horizontally"),
    Mutation("radau-weights-mirrored", CAT, "cable_ocp/numerics/quadrature.py",
             "w[:-1] = (1.0 + x[:-1]) / (n * n * p * p)",
             "w[:-1] = (1.0 - x[:-1]) / (n * n * p * p)", ("tests/test_quadrature.py",),
             "Radau weights of the rule that includes -1, not +1"),
    Mutation("legendre-map-keeps-full-weights", CAT, "cable_ocp/numerics/quadrature.py",
             "return 0.5 * (b - a) * (x + 1.0) + a, 0.5 * (b - a) * w",
             "return 0.5 * (b - a) * (x + 1.0) + a, (b - a) * w",
             ("tests/test_baseline_chucheepsakul.py",),
             "Gauss-Legendre on [a, b]: the weights not scaled by (b - a)/2 (the FEM's "
             "element integrals doubled)"),
    Mutation("batch-chunks-ignore-grid-blocks", "batch", "cable_ocp/batch/study.py",
             "near = [b for b in starts if i + size / 2 <= b <= i + 1.5 * size]",
             "near = []", ("tests/test_batch.py::test_guided_chunks_end_at_grid_blocks",),
             "batch chunks cut across the grid's blocks (two workers build one solver)"),
    Mutation("session-predictor-off", "batch", "cable_ocp/statics/predictor.py",
             "return extrapolate(points, float(v)) if len(points) >= 2 else fallback",
             "return fallback",
             ("tests/test_batch.py::test_solve_session_continuation_predicts_along_a_line",),
             "the continuation predictor never predicts (batch and sweep: plain warm starts)"),
    Mutation("batch-extreme-names-the-other-case", "batch", "cable_ocp/batch/summary.py",
             '"max_at": {k: hi.get(k) for k in keys}', '"max_at": {k: lo.get(k) for k in keys}',
             ("tests/test_batch_face.py::test_extremes_name_the_parameter_values_of_the_extreme_case",),
             "the summary's largest value named with the smallest case's parameter values"),
    Mutation("key-unit-current-speed-lost", "batch", "cable_ocp/scene/units.py",
             '"environment.current.speed": "m/s",', '"environment.current.speed": "",',
             ("tests/test_batch_face.py::test_keys_have_units_and_the_axes_carry_them",),
             "the current speed's unit missing from the key->unit table (axes without it)"),
    Mutation("batch-random-joined-by-lines", "batch", "cable_ocp/plots/batch.py",
             'style = {"linestyle": "None"} if keys[0] in random else {"linestyle": "-"}',
             'style = {"linestyle": "-"}',
             ("tests/test_batch_face.py::test_random_samples_are_drawn_as_points",),
             "random samples joined by lines as if they were a grid"),
    Mutation("heave-batch-plots-passive", "batch", "cable_ocp/plots/batch.py",
             'controlled = [c for c in rms if not c.startswith("passive_")]',
             "controlled = rms",
             ("tests/test_batch_face.py::test_heave_batch_draws_the_controllers_not_the_passive_run",),
             "a heave batch's figure draws the passive run beside the controllers"),
    Mutation("batch-arrays-of-first-case", "batch", "cable_ocp/batch/arrays.py",
             "v = np.asarray(arrays[c].get(name, ()), dtype=float).ravel()",
             "v = np.asarray(arrays[cases[0]].get(name, ()), dtype=float).ravel()",
             ("tests/test_batch_face.py::test_array_store_holds_each_cases_tension_along_the_line",),
             "the netCDF store holds the first case's arrays for every case"),
    Mutation("range-graph-not-interpolated", "batch", "cable_ocp/batch/arrays.py",
             "table[i, inside] = np.interp(grid[inside], x[order], y[order])",
             "table[i, np.isin(grid, x)] = y[np.isin(x, grid)]",
             ("tests/test_batch_face.py::test_range_graph_is_the_envelope_of_the_stored_cases",),
             "the range graph counts a case only at its own nodes (no interpolation between "
             "them: the envelope jumps where the cases' meshes differ)"),
    Mutation("batch-resume-forgets-stored-arrays", "batch", "cable_ocp/batch/study.py",
             "merged = {**{k: v for k, v in old.items() if k in done}, **kept}",
             "merged = dict(kept)",
             ("tests/test_batch_face.py::test_resume_keeps_the_stored_arrays_of_the_cases_it_skips",),
             "a resumed batch's arrays file loses the cases it skipped"),
    Mutation("store-rows-keyed-by-parameters", "batch", "cable_ocp/batch/store.py",
             '        self.done[row["case"]] = row\n        self._append(self.csv_path',
             '        self.done[row["case_id"]] = row\n        self._append(self.csv_path',
             (STORE,), "cases with identical parameters collapse into one row"),
    Mutation("store-json-not-strict", "batch", "cable_ocp/batch/store.py",
             "return json.dumps(json_safe(value), indent=indent, allow_nan=False, default=str)",
             "return json.dumps(value, indent=indent, default=str)", (STORE,),
             "the store writes bare NaN and Infinity"),
    Mutation("store-lock-not-taken", "batch", "cable_ocp/batch/store.py",
             "fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)", "fcntl.flock(fd, fcntl.LOCK_UN)",
             (STORE,), "two batches write to one --out at once"),
    Mutation("store-resume-keeps-stray-rows", "batch", "cable_ocp/batch/store.py",
             "and 0 <= index < len(case_ids) and row.get(\"case_id\") == case_ids[index]",
             "and 0 <= index", (STORE,),
             "a resume keeps a row of a case the batch does not have"),
    Mutation("store-damaged-meta-not-caught", "batch", "cable_ocp/batch/store.py",
             "        except json.JSONDecodeError as exc:\n            why = ",
             "        except KeyError as exc:\n            why = ", (STORE,),
             "a truncated meta file makes --resume an internal error"),
    Mutation("store-problem-digest-not-compared", "batch", "cable_ocp/batch/store.py",
             'if a.get("sha256") != b.get("sha256"):', "if False:", (STORE,),
             "a resume with a changed problem file mixes results"),
    Mutation("store-worker-lost-kept", "batch", "cable_ocp/batch/store.py",
             'elif row["status"] in RETRIED:', 'elif row["status"] in ():', (STORE,),
             "worker_lost rows are kept on --resume, their cases never run again"),
    Mutation("store-append-error-internal", "faults", "cable_ocp/batch/store.py",
             "                os.ftruncate(fd, start)\n            raise _write_error(",
             "                os.ftruncate(fd, start)\n            raise\n            raise "
             "_write_error(", (STORE,), "an append on a full disk exits 3"),
    Mutation("store-half-row-left", "faults", "cable_ocp/batch/store.py",
             "                os.ftruncate(fd, start)\n", "                pass\n", (STORE,),
             "a row half appended on a full disk stays in the JSON lines"),
    Mutation("store-cable-scene-digest-not-compared", "batch", "cable_ocp/batch/store.py",
             '                if fa.get("sha256") != fb.get("sha256"):',
             "                if False:", (STORE,),
             "a resume after the [unit] cable_scene file changed mixes results"),
    Mutation("store-default-out-is-the-stem", "batch", "cable_ocp/batch/store.py",
             'return Path(Path(problem).stem + "_batch")', "return Path(Path(problem).stem)",
             (STORE,), "the default --out lacks _batch (x.toml -> x.csv beside nothing)"),
    # -- heave/ -------------------------------------------------------------------------------
    Mutation("mpc-applied-newest-command", HEAVE_A, "cable_ocp/heave/mpc.py",
             "c[n] = 1.0\n                return c, 0.0",
             "c[n + d - 1] = 1.0\n                return c, 0.0", HEAVE,
             "limit rows use the newest buffered command, not the applied one"),
    Mutation("kalman-intensity-one", HEAVE_A, "cable_ocp/heave/stochastic.py",
             "QN = np.array([[WHITE_NOISE_INTENSITY]])", "QN = np.array([[1.0]])", HEAVE,
             "Kalman filter's process-noise intensity 1 instead of pi"),
    Mutation("sea-noise-variance-doubled", HEAVE_A, "cable_ocp/heave/design_loop.py",
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
             "corr = (p.b * xd - quadratic_drag(bnl, xd, 1e-3)) / p.a",
             "corr = (p.b * xd + quadratic_drag(bnl, xd, 1e-3)) / p.a", HEAVE,
             "IPOPT MPC: quadratic damping (6.3) drives instead of damps"),
    Mutation("nmpc-keeps-linear-damping", HEAVE_A, "cable_ocp/heave/mpc.py",
             "corr = (p.b * xd - quadratic_drag(bnl, xd, 1e-3)) / p.a",
             "corr = (-quadratic_drag(bnl, xd, 1e-3)) / p.a", HEAVE,
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
    Mutation("sim-quadratic-damping-unsigned", HEAVE_A, "cable_ocp/physics/drag.py",
             "mod = abs(u) if isinstance(u, float) else ca.fabs(u)",
             "mod = u if isinstance(u, float) else ca.fabs(u)", HEAVE_SIM,
             "the scalar quadratic law on numbers (the simulated (6.3) unit's damping): "
             "b x'^2 instead of b |x'| x'"),
    Mutation("sim-delay-one-sample-short", HEAVE_A, "cable_ocp/heave/delay.py",
             "applied = self._buf[0]\n        self._buf = np.concatenate([self._buf[1:], [u0]])",
             "self._buf = np.concatenate([self._buf[1:], [u0]])\n        applied = self._buf[0]",
             HEAVE_SIM, "the delay line applies the command one sample (0.05 s) early"),
    Mutation("sim-lqg-buffer-not-reset", HEAVE_A, "cable_ocp/heave/estimators.py",
             "xh[self.n: self.n + self.d] = self.delay.buffer", "pass", HEAVE_SIM,
             "Kalman estimate of its own past commands not reset to the known values"),
    # -- dynamics/ (Huang (1992) ch. 3-5) ------------------------------------------------------
    Mutation("axial-drag-unsigned", PHYS, "cable_ocp/physics/drag.py",
             "    return k * mod * u\n", "    return k * u * u\n", AXIAL,
             "axial: tangential drag k u^2 instead of k |u| u (pushes when the cable rises)"),
    Mutation("axial-unit-weight-missing", DYN, AX_F,
             "f0 = (ten[0] - self.unit_weight - 0.5 * h * (self.w + drag[0])",
             "f0 = (ten[0] - 0.5 * h * (self.w + drag[0])", AXIAL,
             "axial: the unit's weight in water left out of its equation of motion (3.2)"),
    Mutation("axial-unit-added-mass-dropped", DYN, VL_F,
             "unit_mass=unit.virtual_mass[2],", "unit_mass=unit.mass,",
             AXIAL, "axial: the unit's heave added mass left out"),
    Mutation("axial-tangential-added-mass-dropped", DYN, VL_F,
             "mass_per_length=dyn.mass_per_length + dyn.tangential_added_mass_per_length(",
             "mass_per_length=dyn.mass_per_length + 0.0 * dyn.tangential_added_mass_per_length(",
             AXIAL, "axial: the cable's tangential added mass m_at of (3.1) left out"),
    Mutation("axial-advection-velocity-dropped", DYN, AX_F,
             "acc.append((ten[i] - ten[i - 1] - h * (self.w + drag[i])) / (self.mu * h)\n"
             "                       + adv[i] * vy)",
             "acc.append((ten[i] - ten[i - 1] - h * (self.w + drag[i])) / (self.mu * h))",
             AXIAL, "axial: fixed-domain transformation (3.4)-(3.7) without the y L_t/L V_y term"),
    Mutation("axial-advection-position-dropped", DYN, AX_F,
             "dz.append(vel[i] + ref_rate + adv[i] * zy)", "dz.append(vel[i] + ref_rate)",
             AXIAL, "axial: fixed-domain transformation without the y L_t/L Z_y term"),
    Mutation("bench-moordyn-start-of-step-velocity", "bench", "cable_ocp/bench/dynamics.py",
             "v_mean = (np.diff(pos, axis=1) / COUPLING_STEP).T.tolist()",
             "v_mean = np.asarray(motion.map(n_c + 1)(tc[None, :])[1])[:, :-1].T.tolist()",
             (BENCH_MD,), "bench dynamics: MoorDyn given the velocity at the start of each "
             "coupling step, not the one that carries it to the next position"),
    Mutation("bench-moordyn-force-without-inertia", "bench", "cable_ocp/bench/dynamics.py",
             'return np.einsum("nij,nj->ni", node_mass, acceleration) - point_force',
             "return -point_force", (BENCH_MD,),
             "bench dynamics: MoorDyn compared on its force without the top node's inertia "
             "(a different force from cable_ocp's)"),
    Mutation("bench-moordyn-sampled-at-step-end", "bench", "cable_ocp/bench/dynamics.py",
             "t_s = tc[1:] - (0.5 * dtm if stage_time else 0.0)", "t_s = tc[1:]", (BENCH_MD,),
             "bench dynamics: MoorDyn's force stamped at the coupling step's end, not at the "
             "RK2 stage it was evaluated at"),
    Mutation("bench-moordyn-unstretched-start", "bench", "cable_ocp/bench/dynamics.py",
             "{unit_height - depth!r}", "{z_top - cab.length}", (BENCH_MD,),
             "bench dynamics: MoorDyn's unit placed at the unstretched length (its IC solver "
             "then leaves the line far from equilibrium at small dtM)"),
    Mutation("bench-reference-not-extrapolated", "bench", "cable_ocp/bench/dynamics.py",
             "y = y2 + (y2 - y1) / (ratio**2 - 1.0)", "y = y2", (BENCH_REF,),
             "bench dynamics: the reference is the finer run, not Richardson-extrapolated"),
    Mutation("bench-row-against-its-own-model", "bench", "cable_ocp/bench/dynamics.py",
             "top_tension_amplitude_N=amp, error=_error(t, y, ref, duration),",
             "top_tension_amplitude_N=amp, error=_error(t, y, Reference(t, y, amp, {}), "
             "duration),", (BENCH_REF,),
             "bench dynamics: a cable_ocp row compared with itself (no spatial error counted)"),
    Mutation("bench-moorpy-z-not-shifted", "bench", MP_F,
             "pt = ms.addPoint(1, pos - shift)", "pt = ms.addPoint(1, pos)",
             (MP_T + "single_suspended_line_matches_the_elastic_catenary_and_z_is_shifted",),
             "bench moorpy: anchors given to MoorPy in our frame (z from the seabed), not "
             "shifted to its z = 0 at the surface"),
    Mutation("bench-moorpy-axial-drag-without-pi", "bench", MP_F,
             '"CdAx": _num(table, "tangential_drag"',
             '"CdAx": math.pi * _num(table, "tangential_drag"',
             (MP_T + "line_type_is_moorpys_own_table",),
             "bench moorpy: our C_dt (on pi d) multiplied by pi for MoorPy's CdAx (also on pi d)"),
    Mutation("axial-first-sample-with-the-new-top-velocity", DYN, AX_F,
             "first = [np.asarray(v).reshape(-1, 1) for v in post[0](ts[0], xs[:, 0])]",
             "first = [np.asarray(v).reshape(-1, 1) for v in post[1](ts[0], xs[:, 0])]",
             ("tests/dynamics/test_axial.py::"
              "test_first_sample_of_an_abrupt_start_is_the_static_state",),
             "axial: the t = 0 sample of an abrupt start evaluated with the new pay-out and "
             "heave velocity against the resting line (a damping tension it does not carry)"),
    Mutation("axial-modes-unit-mass-missing", DYN, AX_F,
             "mass[0] = self.unit_mass + 0.5 * self.mu * h", "mass[0] = 0.5 * self.mu * h",
             AXIAL, "axial modes: the unit's mass missing from the mass matrix"),
    Mutation("axial-top-tension-inertia-dropped", DYN, AX_F,
             "(self.w + self.mu * a_top + drag_top)", "(self.w + drag_top)", AXIAL,
             "axial: the top tension without the inertia of the top half element"),
    Mutation("axial-static-start-ignored", DYN, AX_F,
             'if self.scene.simulation.start == "unstrained":', "if True:", AXIAL,
             "axial: start = \"static\" starts from the unstretched line"),
    Mutation("axial-slack-threshold-loose", DYN, AX_F,
             "self.slack_tolerance = 1e-9 * (", "self.slack_tolerance = 1e-1 * (", AXIAL,
             "axial: slack reported only below -10 % of the static top tension"),
    Mutation("payout-speed-sign", DYN, MO_F,
             "out = length0 + tm.payout_speed * big_r", "out = length0 - tm.payout_speed * big_r",
             AXIAL + ("tests/dynamics/test_planar.py::test_anchored_catenary_start_and_payout",),
             "pay-out law: a positive speed hauls in"),
    Mutation("heave-phase-cosine", DYN, MO_F,
             "dz = dz + r * tm.heave_amplitude * ca.sin(tm.heave_frequency * t)",
             "dz = dz + r * tm.heave_amplitude * ca.cos(tm.heave_frequency * t)", AXIAL,
             "top heave A cos(w t) instead of A sin(w t) (a jump at t = 0)"),
    Mutation("lumped-node-mass-off-by-one", DYN, LE_F,
             "m[1:] += half\n", "m[:-1] += half\n", LUMPED,
             "lumped: each segment's mass at its lower node instead of half at each end"),
    Mutation("lumped-unit-weight-missing", DYN, LE_F,
             "w[0] += p.unit.weight_in_water", "pass", LUMPED,
             "lumped: the unit's weight in water missing (5.6)"),
    Mutation("lumped-unit-added-mass-dropped", DYN, LE_F,
             "out[0] += p.unit.mass + np.asarray(p.unit.added_mass)", "out[0] += p.unit.mass",
             LUMPED, "lumped: the unit's added mass left out"),
    Mutation("lumped-added-mass-tangential-projector", DYN, LE_F,
             "return 0.5 * projected_added_mass(eet, en, et)",
             "return 0.5 * projected_added_mass(eet, et, en)", LUMPED,
             "lumped step (the kernel's form): added mass (5.2) along the tangent t t^T "
             "instead of I - t t^T"),
    Mutation("lumped-modes-added-mass-tangential-projector", DYN,
             "cable_ocp/physics/added_mass.py",
             "return normal * (ca.SX.eye(3) - tt) + tangential * tt",
             "return normal * tt + tangential * (ca.SX.eye(3) - tt)",
             LUMPED + ("tests/dynamics/test_planar.py::test_in_plane_modes_equal_lumped3d",),
             "lumped modes, statics and plant (physics.added_mass.line_added_mass): added "
             "mass (5.2) along the tangent instead of normal"),
    Mutation("lumped-tension-ea-over-l", DYN, LK_F,
             "segment_tension(d1, ell, ea, c, delta_t,",
             "segment_tension(d1, ell, ea / ell, c, delta_t,", LUMPED,
             "lumped step: segment tension EA/l eps (a spring constant) instead of EA eps"),
    Mutation("lumped-current-ignored", DYN, LK_F,
             "urel = u_c - 0.5 * (va + vb)", "urel = -0.5 * (va + vb)", LUMPED,
             "lumped step: the segments' drag ignores the current"),
    Mutation("lumped-newton-accepts-on-estimate-alone", DYN, LK_F,
             "early = ca.logic_and(check, r_chk <= tol)", "early = check",
             (_LMP + "newton_stop_on_the_contraction_estimate_checks_the_residual",),
             "lumped step: Newton stops on the contraction estimate without checking the "
             "residual at the new iterate"),
    Mutation("lumped-halving-branches-swapped", DYN, LK_F,
             'switch("halving_select", d1, keep, halves,',
             'switch("halving_select", d1, halves, keep,', LUMPED + (
                 _LMP + "newton_step_equals_casadi_rootfinder",),
             "lumped step: two half steps where the whole step converged (and the "
             "unconverged whole step kept)"),
    Mutation("lumped-tangential-drag-unsigned", DYN, "cable_ocp/physics/drag.py",
             "ut * ut + delta * delta) * ut * t\n",
             "ut * ut + delta * delta) * ca.fabs(ut) * t\n", LUMPED,
             "lumped step: tangential drag u_t^2 instead of |u_t| u_t"),
    Mutation("lumped-plant-top-length-frozen", DYN, "cable_ocp/dynamics/lumped_driven.py",
             "lb = self.l_top0 + (par[1] - self.length0)",
             "lb = self.l_top0 + (par[0] - self.length0)",
             ("tests/heave/test_lumped_plant.py::test_vertical_lumped_plant_equals_axial",
              "tests/heave/test_lumped_plant.py::"
              "test_payout_settles_the_unit_by_the_static_elastic_answer"),
             "lumped plant's driven step: the top segment keeps its start length over the "
             "step (the winch's pay-out lost within a step)"),
    Mutation("axial-plant-unit-tension-inertia-dropped", DYN, "cable_ocp/dynamics/driven.py",
             "(model.w + drag + model.mu * acceleration)",
             "(model.w + drag)",
             ("tests/heave/test_planar_plant.py::test_vertical_planar_plant_equals_axial",),
             "axial driven step: the unit's tension without the inertia of the half element "
             "its node carries"),
    Mutation("planar-plant-pull-drag-dropped", DYN, "cable_ocp/dynamics/driven.py",
             "pull = (tens[0] * d0 / ca.norm_2(d0) + drag_half",
             "pull = (tens[0] * d0 / ca.norm_2(d0)",
             ("tests/heave/test_planar_plant.py::test_vertical_planar_plant_equals_axial",),
             "planar driven step: the pull on the unit without the half element's drag"),
    Mutation("axial-thesis-coriolis-sign", DYN, "cable_ocp/dynamics/axial_thesis.py",
             "                -2 * mu * v * y / ell,", "                2 * mu * v * y / ell,",
             AXIAL, "Huang's scheme: the pay-out cross term C = -2 mu v y / l of (3.5) with "
             "the wrong sign"),
    Mutation("lumped-static-start-ignored", DYN, "cable_ocp/dynamics/lumped_scene.py",
             'if scene.simulation.start in ("unstrained", "dropped"):', "if True:", LUMPED,
             "lumped: start = \"static\" starts from the unstretched vertical line"),
    Mutation("planar-unit-drag-no-half", DYN, PL_F,
             "point_drag(u, self.unit_cs, rho=self.rho,",
             "point_drag(u, self.unit_cs, rho=2.0 * self.rho,", PLANAR,
             "planar: the unit's drag rho C_D S |u| u without the 1/2"),
    Mutation("static-unit-current-not-updated", DYN, "cable_ocp/dynamics/static.py",
             "new = solve(static_scene(scene, z), warm_start=sol)",
             "new = solve(static_scene(scene, None), warm_start=sol)",
             ("tests/dynamics/test_scene.py", "tests/dynamics/test_lumped_robust.py"),
             "static start: the unit's drag in a depth-varying current not re-taken at its "
             "solved height"),
    Mutation("planar-current-wrong-component", DYN, PL_F,
             "return ca.repmat(ca.vertcat(self.current.ux[0], 0.0), 1, k)",
             "return ca.repmat(ca.vertcat(self.current.uy[0], 0.0), 1, k)", PLANAR,
             "planar: a uniform current's y component used as the in-plane one"),
    Mutation("planar-added-mass-cross-sign", PHYS, "cable_ocp/physics/added_mass.py",
             "scale * (tangential - normal) * txz", "scale * (normal - tangential) * txz", PLANAR,
             "planar: off-diagonal added mass of (5.2) with the wrong sign"),
    Mutation("planar-advection-velocity-dropped", DYN, PL_F,
             "acc = (v1 - vv0) / dt - self._free_cols(adv * vy)", "acc = (v1 - vv0) / dt",
             PLANAR, "planar: fixed-domain transformation (4.4.3) without the a V_y term"),
    Mutation("planar-unit-x-added-mass-as-z", DYN, PL_F,
             "self.unit_mass = (unit.virtual_mass[0], unit.virtual_mass[2])",
             "self.unit_mass = (unit.virtual_mass[2], unit.virtual_mass[2])",
             PLANAR, "planar: the unit's z added mass used for x too"),
    # -- bookkeeping: numbers the code derives for its own records (issue 21, item 9) ------
    Mutation("surface-tolerance-10x", "bookkeeping", "cable_ocp/statics/checks.py",
             "    if z[i_top] > depth + tol:", "    if z[i_top] > depth + 10.0 * tol:",
             ("tests/test_contract.py::test_the_above_surface_boundary_is_the_stated_tolerance",),
             "the above-surface check 10x looser than its stated tolerance"),
    Mutation("retry-one-attempt-more", "bookkeeping", "cable_ocp/batch/executors.py",
             "        if attempts[crashed.index] >= max_attempts:",
             "        if attempts[crashed.index] > max_attempts:",
             ("tests/test_batch.py::test_a_case_is_tried_exactly_max_attempts_times",),
             "a case that kills its workers is tried max_attempts + 1 times"),
    Mutation("store-keeps-lines-after-a-cut", "bookkeeping", "cable_ocp/batch/store.py",
             "                cut = len(lines) - number + 1\n                break",
             "                cut = len(lines) - number + 1\n                continue",
             ("tests/test_batch.py::test_resume_drops_a_cut_line_and_what_follows",),
             "resume keeps the rows after a line cut short (out of order, not re-run)"),
    Mutation("store-line-not-ended", "bookkeeping", "cable_ocp/batch/store.py",
             'good.append(line if line.endswith("\\n") else line + "\\n")', "good.append(line)",
             ("tests/test_batch.py::test_resume_drops_a_cut_line_and_what_follows",),
             "a kept last line without its newline: the next row is written onto it"),
    Mutation("current-first-knot-not-a-kink", "bookkeeping", "cable_ocp/physics/current.py",
             "slope = np.concatenate([[0.0], np.diff(comp) / np.diff(z), [0.0]])",
             "slope = np.concatenate([np.diff(comp)[:1] / np.diff(z)[:1], np.diff(comp) / "
             "np.diff(z), [0.0]])", ("tests/test_physics_laws.py",),
             "the first knot of a profile that starts above the seabed is not a kink (the "
             "current is constant below it)"),
    Mutation("identify-quadratic-damping-unsigned", HEAVE_A, "cable_ocp/heave/identify.py",
             'damp = b * s[1] if model == "linear" else quadratic_drag(b, s[1])',
             'damp = b * s[1] if model == "linear" else b * s[1] * s[1]',
             ("tests/heave/test_identify.py",),
             "the identification's (6.3) model: b x'^2 instead of b |x'| x'"),
    Mutation("identify-rk4-third-stage-slip", "bookkeeping", "cable_ocp/heave/identify.py",
             "k3 = f(s + dt / 2 * k2, p, xm)", "k3 = f(s + dt / 2 * k1, p, xm)",
             ("tests/heave/test_identify.py::test_the_design_models_integrator_is_fourth_order",),
             "the design model's RK4 takes its third stage from the first (order < 4)"),
    Mutation("chirp-sweeps-half-the-band", "bookkeeping", "cable_ocp/heave/identify_cable.py",
             "x = np.sin(lo * t + 0.5 * (hi - lo) * t**2 / duration)",
             "x = np.sin(lo * t + 0.25 * (hi - lo) * t**2 / duration)",
             ("tests/heave/test_identify.py::test_the_chirp_sweeps_exactly_the_band",),
             "the identification's chirp ends at the middle of its band"),
    Mutation("until-slack-keeps-one-sample-more", "bookkeeping", "cable_ocp/dynamics/result.py",
             "return t < first_time + sample_step * (1.0 - 1e-9)",
             "return t <= first_time + sample_step * (1.0 + 1e-9)", (
                 _MI + "slack_report_words_every_model_alike",
                 _MI + "a_stopped_run_ends_at_the_first_sample_at_or_after_the_slack_time"),
             "a run stopped at slack keeps one output step past a slack time on the sample "
             "grid where its loop computed it (the code before issue 21's fix)"),
    Mutation("axial-slack-time-one-step-early", "bookkeeping", AX_F,
             "ca.if_else(first_slack, tm + dt, t_slack),", "ca.if_else(first_slack, tm, t_slack),",
             (SLACK_TIME,), "axial: the slack time reported is the start of the first slack "
             "step, one step before the first tension <= 0"),
    Mutation("planar-slack-time-one-step-early", "bookkeeping", PL_F,
             "ca.if_else(first, tm + dt, t_slack),", "ca.if_else(first, tm, t_slack),",
             (SLACK_TIME,), "planar: the slack time reported is the start of the first slack "
             "step, one step before the first strain <= 0"),
    Mutation("lumped-slack-time-one-step-early", "bookkeeping",
             "cable_ocp/dynamics/lumped_run.py",
             "slack = (float(tstart[j] + dt * (fc[j] + 1)), int(round(sc[j])))",
             "slack = (float(tstart[j] + dt * fc[j]), int(round(sc[j])))", (SLACK_TIME,),
             "lumped: the slack time reported is the start of the first slack step, one step "
             "before the first strain <= 0"),
    Mutation("output-every-truncated", "bookkeeping", "cable_ocp/scene/dynamic_parts.py",
             "return int(round(self.output_step / self.time_step))",
             "return int(self.output_step / self.time_step)", (OUTPUT_GRID,),
             "steps per output sample truncated: output_step 0.3 s over time_step 0.1 s "
             "(2.9999999999999996) stores every 2nd step"),
    Mutation("steps-truncated", "bookkeeping", "cable_ocp/scene/dynamic_parts.py",
             "return int(round(self.duration / self.time_step))",
             "return int(self.duration / self.time_step)", (OUTPUT_GRID,),
             "integration steps truncated: 1.2 s over 0.1 s (11.999999999999998) runs 11 "
             "steps and drops the last output sample"),
    Mutation("chart-pays-out-the-bottom-segment", "bookkeeping", "cable_ocp/dynamics/modal.py",
             "        top = len(st.segments) - 1\n"
             "        rest = sum(c.length for c in st.segments[:-1])",
             "        top = 0\n"
             "        rest = sum(c.length for c in st.segments[1:])", (CHART,),
             "deployment chart of a segmented line: the length change goes to segment 0 "
             "(end_a's, as if the segments were listed from end_b), not to the top one"),
    Mutation("lumped-body-weight-on-next-node", "bookkeeping", LE_F,
             "w[b.node] += b.weight_in_water", "w[b.node + 1] += b.weight_in_water", (BODY,),
             "lumped: a point body's weight in water acts on the node above its joint"),
    Mutation("library-digest-not-checked", "faults", "cable_ocp/numerics/compile.py",
             "and _elf_complete(lib) and recorded[0] == _sha256(lib))",
             "and _elf_complete(lib))",
             ("tests/test_damaged_cache.py",),
             "a library whose bytes differ from its record is loaded (a flipped bit)"),
    Mutation("compiler-output-not-checked", "faults", "cable_ocp/numerics/compile.py",
             "    if not _elf_complete(part):\n        raise OSError(",
             "    if False:\n        raise OSError(",
             ("tests/test_damaged_cache.py",),
             "a compiler output 8 bytes short is installed"),
    Mutation("heave-interrupt-skips-the-stopped-run", "faults", "cable_ocp/heave/design_loop.py",
             "        for name in runs[stopped:]:", "        for name in runs[stopped + 1:]:",
             ("tests/heave/test_heave_interrupt.py",),
             "a Ctrl-C in a heave run: the controller stopped gets no status (nothing written)"),
    Mutation("heave-cable-interrupt-skips-the-stopped-run", "faults",
             "cable_ocp/heave/cable_compare.py",
             "        for name in runs_of[stopped:]:", "        for name in runs_of[stopped + 1:]:",
             ("tests/heave/test_heave_interrupt.py",),
             "a Ctrl-C in a heave run on the cable: the controller stopped gets no status"),
    Mutation("output-written-in-place", "faults", "cable_ocp/cli/output.py",
             "        replace_atomically(path, write)",
             "        write(path)",
             ("tests/test_full_disk.py",),
             "--json/--csv/--plot write into the target itself: a full disk destroys the "
             "earlier file"),
    Mutation("problem-fifo-opened", "faults", "cable_ocp/scene/files.py",
             "    if not stat.S_ISREG(st.st_mode):",
             "    if stat.S_ISDIR(st.st_mode):",
             ("tests/test_cli.py::test_a_problem_that_is_not_a_regular_file_or_too_large_is_refused",),
             "a FIFO or a device is opened as a problem file"),
    Mutation("interrupted-modes-drops-its-lengths", "faults", "cable_ocp/dynamics/modal.py",
             "        except KeyboardInterrupt:  # the lengths finished so far are the chart\n"
             "            done = i\n            break",
             "        except KeyboardInterrupt:  # the lengths finished so far are the chart\n"
             "            raise",
             ("tests/dynamics/test_cli.py::test_interrupted_modes_lengths_keeps_the_lengths_it_"
              "finished",),
             "an interrupted modes --lengths writes nothing of the lengths it finished"),
    Mutation("interrupted-batch-writes-no-summary", "faults", "cable_ocp/cli/batch.py",
             "        except KeyboardInterrupt:\n            _interrupted_summary(args, store)",
             "        except KeyboardInterrupt:\n            pass",
             ("tests/test_interrupt.py::test_batch_workers_end_with_their_parent",),
             "an interrupted batch writes no --json summary (status interrupted)"),
    Mutation("cable-scene-not-an-input", "faults", "cable_ocp/cli/output.py",
             "            seen.setdefault(os.path.realpath(path), f\"the input {what} {path}\")",
             "            pass",
             ("tests/test_cli.py::test_an_output_onto_the_cable_scene_is_refused",),
             "an output may overwrite the dynamic scene that [unit] cable_scene names"),
    Mutation("readme-sample-stale", "bookkeeping", "README.md",
             "length L                           305.0000 m",
             "length L                           305.0010 m",
             ("tests/test_readme_outputs.py",),
             "a README sample output that a run no longer gives"),
    Mutation("casadi-caught-ctrl-c-is-a-failed-solve", "faults",
             "cable_ocp/numerics/interrupt.py",
             "    if caught or str(stats.get(\"return_status\")) == IPOPT_STOP:",
             "    if str(stats.get(\"return_status\")) == IPOPT_STOP:", (INTERRUPT,),
             "a Ctrl-C that CasADi caught inside IPOPT, without the command line's handler (a "
             "notebook), is a failed solve: footprint retries the direction"),
    Mutation("ctrl-c-while-importing-is-a-traceback", "faults", "cable_ocp/__init__.py",
             "_interrupt.defer_during_launch()\n", "\n", (INTERRUPT,),
             "a Ctrl-C while the command line imports the package prints a traceback"),
    Mutation("batch-worker-outlives-its-parent", "faults", "cable_ocp/batch/executors.py",
             "    _exit_with_parent(parent)\n", "\n", (INTERRUPT,),
             "a batch killed with kill -9 leaves its workers running"),
    Mutation("interrupted-footprint-drops-its-csv", "faults", "cable_ocp/cli/statics.py",
             "partial=interrupted)", "partial=False)", (INTERRUPT,),
             "an interrupted footprint writes no CSV of its finished directions"),
    Mutation("interrupted-simulate-drops-its-csv", "faults", "cable_ocp/cli/dynamics.py",
             "partial=stopped)", "partial=False)", (INTERRUPT,),
             "an interrupted simulate writes no CSV of its finished samples"),
    Mutation("result-top-is-the-next-node", "bookkeeping", "cable_ocp/dynamics/result.py",
             "return cls(top_position=node_positions[:, -1, :].copy(),",
             "return cls(top_position=node_positions[:, -2, :].copy(),", (ENDS,),
             "every model's reported top position is the node below end_b"),
    Mutation("failed-result-one-node-short", "bookkeeping", "cable_ocp/dynamics/result.py",
             "np.zeros((0, elements + 1, 3)), t=np.zeros(0)",
             "np.zeros((0, elements, 3)), t=np.zeros(0)", (FAILED_START,),
             "the empty history of a failed start has one node fewer than the line"),
    Mutation("envelope-min-is-window-max", "plots", "cable_ocp/plots/common.py",
             "    lo = np.fmin.reduceat(y[:-1], starts[:-1])",
             "    lo = np.fmax.reduceat(y[:-1], starts[:-1])", (FIGS,),
             "a long time series' envelope: its lower edge is each window's max"),
    Mutation("long-series-drawn-as-line", "plots", "cable_ocp/plots/common.py",
             "    if len(t) <= max(limit, 2):", "    if True:", (FIGS,),
             "every time series is drawn as a line: 160 wave periods in 550 px, a solid block"),
    Mutation("unit-heave-absolute-z", "plots", "cable_ocp/plots/dynamics.py",
             "    rel = up - up[0]", "    rel = up - 0.0 * up[0]", (FIGS,),
             "the simulate figure draws the unit's absolute z, not z - z_static"),
    Mutation("plan-view-x-y-swapped", "plots", "cable_ocp/plots/dynamics.py",
             'a.plot(r[0, :, 0], r[0, :, 1], color="k"',
             'a.plot(r[0, :, 1], r[0, :, 0], color="k"', (FIGS,),
             "the plan view draws the line at t = 0 with x and y swapped"),
    Mutation("no-excitation-not-warned", "plots", "cable_ocp/dynamics/simulation.py",
             "    if not excited:", "    if False:", (FIGS,),
             "a scene in which nothing moves the line simulates without a warning"),
    Mutation("heave-is-not-excitation", "plots", "cable_ocp/dynamics/simulation.py",
             "    if tm.moves:", "    if tm.horizontal:", (FIGS,),
             "a top that only heaves is taken for no excitation (a wrong warning)"),
    Mutation("axial-modes-all-mode-one", "plots", "cable_ocp/plots/dynamics.py",
             "        a.plot(uk, depth,", "        a.plot(u[0], depth,", (FIGS,),
             "the axial mode figure draws the first mode's shape for every mode"),
    Mutation("titles-not-fitted", "plots", "cable_ocp/plots/common.py",
             "    fit_titles(fig)\n    # whole", "    # whole", (FIGS,),
             "saved figures keep titles wider than the figure (clipped at its edges)"),
    Mutation("system-colour-is-height", "plots", "cable_ocp/plots/system.py",
             "        lc.set_array(_segment_tension(np.asarray(sol.tension, float)))\n"
             "        ax.add_collection(lc)",
             "        lc.set_array(0.5 * (r[:-1, 2] + r[1:, 2]))\n        ax.add_collection(lc)",
             ("tests/test_plots_system.py",),
             "the system's plan view colours the lines by height, not by tension"),
    Mutation("system-heading-is-pitch", "plots", "cable_ocp/plots/system.py",
             'return math.radians(float(body["rotation_deg"][2]))',
             'return math.radians(float(body["rotation_deg"][1]))',
             ("tests/test_plots_system.py",),
             "a body's heading arrow points along its pitch angle, not its yaw"),
    Mutation("system-scale-of-one-line", "plots", "cable_ocp/plots/system.py",
             "    lo, hi = float(min(t.min() for t in tens)), float(max(t.max() for t in tens))",
             "    lo, hi = float(tens[0].min()), float(tens[0].max())",
             ("tests/test_plots_system.py",),
             "the tension colour scale spans the first line only: the others saturate"),
    # -- heave: slack and limits on the cable, the heave tables (issue 22, fault 7, item 12) --
    Mutation("heave-slack-is-not-a-status", HEAVE_A, "cable_ocp/heave/metrics.py",
             'metrics.get("slack_first_time_s"), None, None, status=status',
             "None, None, None, status=status", (SLACK_ST + "short_stiff_line_goes_slack_status_"
                                                  "slack_exit_1",),
             "a run whose line goes slack on the cable stays solved (exit 0)"),
    Mutation("heave-limit-warning-100x", HEAVE_A, "cable_ocp/heave/metrics.py",
             "if value > limit * (1.0 + LIMIT_TOLERANCE)]", "if value > limit * 100.0]",
             (SLACK_ST + "shipped_problem_still_solved_exit_0_with_a_limit_warning",),
             "a controller 5.7x past the command-rate limit gets no warning"),
    Mutation("heave-table-missing-cell-empty", HEAVE_A, "cable_ocp/cli/heave.py",
             "        return MISSING\n    return format(v / scale, spec)",
             "        return ''\n    return format(v / scale, spec)",
             (SLACK_ST + "heave_tables_fit_and_a_failed_row_keeps_its_columns",),
             "a failed controller's row loses its cells (its columns shift)"),
    Mutation("deployment-slack-windows-all", HEAVE_A, "cable_ocp/heave/deployment.py",
             '"slack_windows": sum(1 for v in slack if v > 0)',
             '"slack_windows": sum(1 for v in slack if v >= 0)',
             (SLACK_ST + "deployment_summary_and_table",),
             "the deployment summary counts every window as slack"),
    # -- bookkeeping: the text face (issue 22, items 11, 12) ----------------------------------
    Mutation("progress-pipe-every-100-s", "bookkeeping", "cable_ocp/cli/output.py",
             "if since >= PROGRESS_EVERY_S or", "if since >= 10 * PROGRESS_EVERY_S or",
             (TEXT + "progress_in_a_pipe_writes_a_line_every_10_s_or_10_percent",),
             "in a pipe the progress line comes every 100 s"),
    Mutation("progress-heartbeat-silent", "bookkeeping", "cable_ocp/cli/output.py",
             "        if now - self.last_t >= PROGRESS_EVERY_S:\n            self._write(now)",
             "        if False:\n            self._write(now)",
             (TEXT + "progress_in_a_pipe_says_preparing_through_a_silent_start",),
             "a command that prepares for 37 s before its first step is silent in a pipe"),
    Mutation("progress-bar-zero-columns", "bookkeeping", "cable_ocp/cli/output.py",
             "return cols if cols > 0 else FALLBACK_COLUMNS", "return cols",
             (TEXT + "progress_bar_draws_on_a_terminal_that_reports_0_columns",),
             "a terminal that reports 0 columns gets a bar 0 wide"),
    Mutation("table-ignores-its-width", "bookkeeping", "cable_ocp/numerics/text_table.py",
             "if len(blocks[-1]) > 1 and used + len(_GAP) + widths[i] > width:",
             "if False:",
             (TEXT + "table_fits_100_columns_and_a_failed_row_keeps_its_columns",),
             "a table wider than 100 columns is printed in one block"),
    Mutation("table-keeps-empty-units-line", "bookkeeping", "cable_ocp/numerics/text_table.py",
             "if j == 0 or any(h[i] for i in cols)]",
             "if True]",
             (TEXT + "table_block_without_units_has_no_units_line",),
             "a block without units prints an empty units line"),
    Mutation("summary-numbers-two-digits", "face", "cable_ocp/numerics/export.py",
             '    return f"{v:.6g}"', '    return f"{v:.2g}"',
             ("tests/test_face.py::test_repr_is_a_short_summary_with_the_status_and_key_numbers",),
             "the results' summaries write their key numbers with 2 significant digits"),
    Mutation("statics-repr-is-the-dataclass-repr", "face", "cable_ocp/statics/solution.py",
             "    def __repr__(self) -> str:\n        \"\"\"A few lines: status, length,",
             "    def _unused_repr(self) -> str:\n        \"\"\"A few lines: status, length,",
             ("tests/test_face.py::test_repr_is_a_short_summary_with_the_status_and_key_numbers",),
             "a statics solution prints its arrays again (the 24 kB dataclass repr)"),
    Mutation("netcdf-element-tension-in-kN", "face", "cable_ocp/dynamics/result.py",
             '"element_tension": (("time", "element"), self.segment_tensions, {"units": "N"})',
             '"element_tension": (("time", "element"), self.segment_tensions, {"units": "kN"})',
             ("tests/test_face.py::test_to_xarray_names_dimensions_with_units",),
             "a simulation's element tensions (N) are labelled kN in its Dataset and netCDF"),
    Mutation("batch-xarray-drops-units", "face", "cable_ocp/batch/study.py",
             '            attrs = {"units": unit.rstrip("]")} if unit else {}',
             '            attrs = {}',
             ("tests/test_face.py::test_to_xarray_names_dimensions_with_units",),
             "a batch's Dataset loses the units of its output columns"),
    Mutation("missing-extra-not-named", "face", "cable_ocp/numerics/export.py",
             'f"the optional extra io, {IO_EXTRA}") from None',
             'f"the optional extra io") from None',
             ("tests/test_face.py::test_a_missing_extra_names_the_install",),
             "a missing xarray or pandas is reported without the install command"),
    Mutation("simulation-plot-draws-the-length", "face", "cable_ocp/plots/accessors.py",
             "ax.plot(res.t, res.top_tension, lw=1.2,", "ax.plot(res.t, res.length, lw=1.2,",
             ("tests/test_face.py::test_plot_returns_the_figure_and_the_axes",),
             "SimulationResult.plot(ax=...) draws the length instead of the top tension"),
    Mutation("netcdf-written-in-place", "face", "cable_ocp/numerics/export.py",
             "    return replace_atomically(path, lambda tmp: ds.to_netcdf(tmp, engine=engine, "
             "**extra))",
             "    ds.to_netcdf(str(path), engine=engine, **extra)\n    return Path(path)",
             ("tests/test_face.py::test_write_netcdf_round_trip_and_keeps_the_old_file",),
             "write_netcdf writes into the target: a failed write destroys the earlier file"),
    Mutation("heave-simulate-is-a-module-again", "face", "cable_ocp/heave/__init__.py",
             "simulate = compare\n",
             "from cable_ocp.heave import design_loop as simulate  # noqa: E402\n",
             ("tests/test_namespaces.py",),
             "cable_ocp.heave.simulate is a module a user calls by mistake"),
    Mutation("batch-namespace-keeps-numpy", "face", "cable_ocp/batch/__init__.py",
             "from cable_ocp.batch.study import BatchResult, run_batch\n",
             "from cable_ocp.batch.study import BatchResult, run_batch\n"
             "import numpy as np  # noqa\n",
             ("tests/test_namespaces.py",),
             "an import leaves numpy public in cable_ocp.batch"),
    # -- mooring systems (issue 23) -------------------------------------------------------
    Mutation("system-geometric-term-dropped", "mooring", "cable_ocp/mooring/model.py",
             "                    geo[3:, 3:] = skew(f) @ skew(arm)",
             "                    geo[3:, 3:] = 0.0 * skew(f) @ skew(arm)", (SYS_EQ,),
             "the 6x6 loses the geometric term [F]x[rho]x of the rotating fairlead arms"),
    Mutation("system-free-points-not-condensed", "mooring", "cable_ocp/mooring/model.py",
             "    if eliminate.size == 0:\n        return jkk",
             "    if True:\n        return jkk", (SYS_EQ,),
             "the 6x6 holds the free clump still instead of letting it find equilibrium"),
    Mutation("system-reversed-line-not-permuted", "mooring", "cable_ocp/mooring/model.py",
             "                k = k[np.ix_([3, 4, 5, 0, 1, 2], [3, 4, 5, 0, 1, 2])]",
             "                k = k", (SYS_EQ,),
             "a line listed fairlead-first uses its end Jacobian blocks the wrong way round"),
    Mutation("hydrostatic-waterplane-moment-sign", "physics",
             "cable_ocp/physics/hydrostatics.py",
             "    m += rho * g * np.array([ixx * n[1], -iyy * n[0], 0.0])",
             "    m += rho * g * np.array([-ixx * n[1], -iyy * n[0], 0.0])", (SYS_EQ,),
             "the waterplane's roll moment destabilises instead of restoring"),
    Mutation("system-anchor-uplift-sign", "mooring", "cable_ocp/mooring/result.py",
             "                        \"vertical\": float(f[2])}",
             "                        \"vertical\": float(-f[2])}", (SYS_CLI,),
             "the anchor's uplift is reported with the wrong sign"),
    Mutation("system-batch-line-columns-swapped", "batch", "cable_ocp/batch/kinds.py",
             "            out[f\"{ln['name']}_max_tension [N]\"] = ln[\"max_tension\"]",
             "            out[f\"{ln['name']}_max_tension [N]\"] = ln[\"tension_a\"]",
             (SYS_CLI,),
             "a system batch's per-line column holds the end_a tension, not the largest"),
    Mutation("restoring-force-sign", "mooring", "cable_ocp/mooring/checks.py",
             "rest[i], trans[i] = -float(f[:2] @ e), float(f[:2] @ et)",
             "rest[i], trans[i] = float(f[:2] @ e), float(f[:2] @ et)",
             (MOORING_CHECKS + "the_slope_at_zero_offset_is_the_condensed_total_stiffness",),
             "the offset curve reports the mooring's force along the heading, not the "
             "restoring force pointing back"),
    Mutation("failed-line-not-skipped", "mooring", "cable_ocp/mooring/checks.py",
             "    model = SystemModel(scene, skip={name})\n",
             "    model = SystemModel(scene, skip=set())\n",
             (MOORING_CHECKS + "line_failure_on_the_three_line_spar",
              MOORING_CHECKS + "the_neighbour_in_the_bundle_takes_the_load_of_a_failed_line"),
             "the line-failure check solves the intact system for every removed line"),
    Mutation("offset-curve-keeps-the-environment", "mooring", "cable_ocp/mooring/checks.py",
             "    bodies = tuple(replace(b, force=(0.0, 0.0, 0.0), moment=(0.0, 0.0, 0.0))\n"
             "                   for b in scene.bodies)\n",
             "    bodies = tuple(scene.bodies)\n",
             (MOORING_CHECKS + "the_slope_at_zero_offset_is_the_condensed_total_stiffness",),
             "the restoring curve is about the loaded equilibrium, not the neutral position"),
    # -- MoorDyn files (scene/moordyn.py) ---------------------------------------------------
    Mutation("moordyn-z-not-shifted", "scene", "cable_ocp/scene/moordyn.py",
             'position=[xyz[0], xyz[1], xyz[2] + depth], mass=mass,',
             'position=[xyz[0], xyz[1], xyz[2]], mass=mass,', (MOORDYN,),
             "a MoorDyn free point keeps MoorDyn's z (surface at 0) instead of z + depth"),
    Mutation("moordyn-cdax-divided-by-pi", "scene", "cable_ocp/scene/moordyn.py",
             '"tangential_drag": _num(t[8], f"line type {name!r} CdAx", row, fname),',
             '"tangential_drag": _num(t[8], f"line type {name!r} CdAx", row, fname) / math.pi,',
             (MOORDYN,),
             "CdAx divided by pi: MoorDyn's CdAx is already on pi d (Line.cpp Dq), as ours"),
    Mutation("moordyn-written-z-not-shifted-back", "scene", "cable_ocp/scene/moordyn.py",
             '            word, z = "Free", z - depth', '            word, z = "Free", z',
             (MOORDYN,), "write_moordyn writes a free point's z without subtracting the depth"),
    Mutation("design-dq-sign", "mooring", "cable_ocp/mooring/design.py",
             "dq[free] = -np.linalg.solve(", "dq[free] = np.linalg.solve(",
             ("tests/mooring/test_design.py",),
             "the equilibrium's response to a design variable, dq/dp = -R_q^-1 R_p, loses "
             "its sign"),
    Mutation("design-length-sensitivity-dropped", "mooring", "cable_ocp/mooring/design.py",
             "                        f_p[i, :, j] += fl\n",
             "                        f_p[i, :, j] += 0.0 * fl\n",
             ("tests/mooring/test_design.py",),
             "a length variable's gradient forgets the lines' own force change with length "
             "(only the mass/cost gradient is left)"),
    Mutation("length-sensitivity-no-grounded-part", "statics/stiffness",
             "cable_ocp/statics/stiffness.py",
             "dg = dw[self.coll.i_g].copy() if self.grounded else np.zeros(7)",
             "dg = np.zeros(7)",
             ("tests/mooring/test_design.py",),
             "the laid length's sensitivity to length and ends is taken as zero"),
    Mutation("moorpy-current-cdax-on-d", "bench", "cable_ocp/bench/moorpy_current.py",
             '"Cd": lt_in["normal_drag"], "CdAx": lt_in["tangential_drag"], "MBL": 1e9}',
             '"Cd": lt_in["normal_drag"], "CdAx": lt_in["tangential_drag"] / math.pi,'
             ' "MBL": 1e9}',
             ("tests/test_moorpy_current.py",),
             "MoorPy's CdAx given on d (MoorDyn's convention) though line.py:939 puts it on pi d"),
    Mutation("current-closed-form-tension-sign", "bench", "cable_ocp/bench/moorpy_current.py",
             "    return t_a, t_a - load * chord\n", "    return t_a, t_a + load * chord\n",
             ("tests/test_moorpy_current.py",),
             "straight line in a current along it: the downstream end carries the drag"),
    Mutation("system-line-below-seabed-reported-solved", "mooring",
             "cable_ocp/mooring/equilibrium.py",
             "            if ev.unphysical:\n                status = \"failed\"",
             "            if False:\n                status = \"failed\"", (SYS_EQ,),
             "an equilibrium whose line passes below the seabed is reported as solved"),
    Mutation("system-tolerance-below-the-line-floor", "mooring", "cable_ocp/scene/system.py",
             "    if tol < floor:", "    if tol < 0.0:", (SYS_EQ,),
             "a system tolerance the lines' accuracy cannot reach is accepted"),
    Mutation("moordyn-seabed-only-with-friction", "scene", "cable_ocp/scene/moordyn.py",
             '    environment["seabed"] = {"friction": env_t.get("friction", 0.0)}',
             '    if "friction" in env_t:\n'
             '        environment["seabed"] = {"friction": env_t["friction"]}',
             ("tests/test_moordyn_files.py",),
             "a MoorDyn deck without FrictionCoefficient loses its seabed"),
    Mutation("catenary-line-friction-drop-sign", CAT, "cable_ocp/statics/catenary_line.py",
             "h_a = max(h - k * lg, 0.0) if grounded else h\n    v_a = ",
             "h_a = max(h + k * lg, 0.0) if grounded else h\n    v_a = ",
             ("tests/test_catenary_line.py",),
             "catenary line: the grounded part's friction raises the tension towards the anchor"),
    Mutation("catenary-line-no-out-of-plane", CAT, "cable_ocp/statics/catenary_line.py",
             "kbb = -(basis @ inv @ basis.T) - h / span * perp",
             "kbb = -(basis @ inv @ basis.T)", ("tests/test_catenary_line.py",),
             "catenary line: the out-of-plane term H/X of the end Jacobian dropped"),
    Mutation("catenary-line-slack-integral", CAT, "cable_ocp/statics/catenary_line.py",
             "di_dh = h / k if slack else lg", "di_dh = lg", ("tests/test_catenary_line.py",),
             "catenary line: the stretch of a grounded part with a slack anchor end"),
)


def _more_mutations() -> tuple[Mutation, ...]:
    """The mutations of ``tests/mutation/list_*.py`` (each a ``MUTATIONS`` list of dicts with
    the fields of :class:`Mutation`), one file an area of work, so that lists grow apart."""
    more: list[Mutation] = []
    for path in sorted(Path(__file__).parent.glob("list_*.py")):
        spec = importlib.util.spec_from_file_location(path.stem, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        for d in module.MUTATIONS:
            more.append(Mutation(**{**d, "tests": tuple(d["tests"])}))
    return tuple(more)


MUTATIONS = MUTATIONS + _more_mutations()


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
    # the compiled-C kernels of the copy (mutated kernels hash differently) stay in the
    # copy: the user's cache gets no mutants
    env = dict(os.environ, PYTHONPATH=str(tree), PYTHONDONTWRITEBYTECODE="1",
               CABLE_OCP_CACHE_DIR=str(tree / ".kernel_cache"))
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
                         "statics/collocation, statics/catenary, heave, dynamics, plots, ...)")
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
