"""Mutations of the bookkeeping of ``cable-ocp bench deploy``
(cable_ocp/bench/deployment.py), issue 25."""

_T = "tests/test_bench_deploy.py::test_"
LIB = "cable_ocp/bench/deployment.py"

MUTATIONS = [
    dict(name="bench-deploy-saving-over-optimal", area="bench", file=LIB,
         old="return 100.0 * (other - optimal) / other",
         new="return 100.0 * (other - optimal) / optimal",
         tests=(_T + "saving_is_relative_to_the_other_duration",),
         description="bench deploy: the saving relative to the optimum, not to the other "
                     "schedule's duration"),
    dict(name="bench-deploy-fit-not-in-logs", area="bench", file=LIB,
         old="np.polyfit(np.log(xa[ok]), np.log(ya[ok]), 1)",
         new="np.polyfit(np.log(xa[ok]), ya[ok], 1)",
         tests=(_T + "exponent_fit_recovers_a_power_law",),
         description="bench deploy: the exponent fitted to y, not log y (no power law)"),
    dict(name="bench-deploy-distance-without-ramps", area="bench", file=LIB,
         old="d = speed * (duration - speed / accel)", new="d = speed * duration",
         tests=(_T + "distance_and_cruise_speed_invert_each_other",),
         description="bench deploy: the cost grid's distance without the ramps' loss v^2/a"),
    dict(name="bench-deploy-cruise-larger-root", area="bench",
         file="cable_ocp/schedule/robust.py",
         old="return 2.0 * accel * distance / (accel * duration + math.sqrt(disc))",
         new="return 0.5 * (accel * duration + math.sqrt(disc))",
         tests=(_T + "distance_and_cruise_speed_invert_each_other",),
         description="bench deploy: the long run's cruise speed the larger root (ramps "
                     "overlapping, no trapezoid)"),
    dict(name="bench-deploy-heave-without-ramp", area="bench", file=LIB,
         old='"ramp_time_s": ramp, "duration_s": tc + ramp,',
         new='"ramp_time_s": ramp, "duration_s": tc,',
         tests=(_T + "heave_payout_lasts_distance_over_speed_plus_ramp",),
         description="bench deploy: today's deployment lasting distance / speed, its ramps "
                     "forgotten (length_history stops at T_c + ramp)"),
    dict(name="bench-deploy-payout-linear-ramp", area="bench", file=LIB,
         old="return smoothstep(np.clip(x, 0.0, 1.0))", new="return np.clip(x, 0.0, 1.0)",
         tests=(_T + "heave_payout_lasts_distance_over_speed_plus_ramp",),
         description="bench deploy: today's pay-out re-simulated with a linear ramp, not "
                     "length_history's quintic (peak acceleration v / r, not 15 v / 8 r)"),
    dict(name="bench-deploy-budget-inverted", area="bench", file=LIB,
         old='over_budget = (row["build_s"] + row["solve_s"]) > budget_s',
         new='over_budget = (row["build_s"] + row["solve_s"]) < budget_s',
         tests=(_T + "cost_grid_skips_beyond_the_budget",),
         description="bench deploy: the cost grid skipping the cells after an affordable one"),
    dict(name="bench-deploy-grid-saving-swapped", area="bench", file=LIB,
         old="saving_pct=saving_pct(res.duration, ws.duration if ws is not None",
         new="saving_pct=saving_pct(ws.duration, res.duration if ws is not None",
         tests=(_T + "bench_deploy_cost_json_rows",),
         description="bench deploy: the cost rows' saving of the warm start against the "
                     "optimum (the sign and the reference swapped)"),
    dict(name="bench-deploy-fit-along-wrong-axis", area="bench", file=LIB,
         old='[r["duration_target_s"] for r in along_d], [r[k] for r in along_d])[0]',
         new='[r["segments"] for r in along_d], [r[k] for r in along_d])[0]',
         tests=(_T + "cost_fits_on_synthetic_rows",),
         description="bench deploy: the growth with the duration fitted against the "
                     "elements"),
    dict(name="bench-deploy-rows-not-saved", area="bench", file=LIB,
         old="        rows.append(row)\n        if on_row is not None:",
         new="        rows.append(row)\n        if False:",
         tests=(_T + "bench_deploy_compare_keeps_each_finished_row",),
         description="bench deploy: the JSON not rewritten after each row (a stopped "
                     "run loses the OCP's rows)"),
]
