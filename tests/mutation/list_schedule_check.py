"""Mutations of the forward check of the deployment schedule (issue 25's 1 % check:
cable_ocp/schedule/planning.py ``verified_schedule``, cable_ocp/schedule/ocp.py
``ScheduleOCP.bounds``) that tests/test_deploy_cli.py and tests/schedule/test_check.py
must catch."""

PLAN = "cable_ocp/schedule/planning.py"
OCP = "cable_ocp/schedule/ocp.py"
_C = "tests/test_deploy_cli.py::test_deploy_"
_KEEP = _C + "schedule_keeps_its_limits_on_a_finer_forward_simulation"
_BOUNDS = "tests/schedule/test_check.py::test_margins_move_only_their_limits_rows_by_their_scale"

MUTATIONS = [
    dict(name="check-margin-without-the-half-tolerance", area="schedule", file=PLAN,
         old="(v + 0.5 * tol) * _limit_value(", new="v * _limit_value(",
         tests=(_KEEP,),
         description="the margin moved by the excess alone: the rounds' bookkeeping"),
    dict(name="check-accepts-ten-times-the-tolerance", area="schedule", file=PLAN,
         old="over = {k: v for k, v in worst.items() if v > tol}",
         new="over = {k: v for k, v in worst.items() if v > 10 * tol}",
         tests=(_KEEP,),
         description="a schedule breaking tension_min by 3 % accepted"),
    dict(name="check-margin-moves-tension-min-outwards", area="schedule", file=OCP,
         old='lbg[a:b] += extra.get("tension_min", 0.0) / ts',
         new='lbg[a:b] -= extra.get("tension_min", 0.0) / ts',
         tests=(_KEEP, _BOUNDS),
         description="the margin loosens the limit: the check never passes"),
    dict(name="check-power-margin-unscaled", area="schedule", file=OCP,
         old='ubg[a:b] -= extra.get("power_max", 0.0) / pm',
         new='ubg[a:b] -= extra.get("power_max", 0.0) / ts',
         tests=(_BOUNDS,),
         description="the power margin scaled by the tension scale, not power_max"),
    dict(name="check-resolves-an-unmovable-limit", area="schedule", file=PLAN,
         old="if len(rounds_done) > n_rounds or len(fixable) < len(over):",
         new="if len(rounds_done) > n_rounds:",
         tests=(_C + "schedule_the_check_rejects_is_not_a_schedule",),
         description="a broken speed_max (no margin moves it) re-solved instead of failed"),
    dict(name="check-round-count-off-by-one", area="schedule", file=PLAN,
         old="check_rounds=len(rounds_done) - 1)", new="check_rounds=len(rounds_done))",
         tests=(_KEEP, _C + "schedule_the_check_rejects_is_not_a_schedule"),
         description="the diagnostics count the first check as a re-solve"),
    dict(name="check-failed-reported-solved", area="schedule", file=PLAN,
         old='            return ScheduleResult("failed", msg, tuple(over), sol,',
         new='            return ScheduleResult("solved", msg, tuple(over), sol,',
         tests=(_C + "schedule_the_check_rejects_is_not_a_schedule",),
         description="a schedule the forward check rejects reported as a schedule"),
    dict(name="check-interrupt-written-as-a-result", area="schedule",
         file="cable_ocp/cli/deploy.py",
         old='    if res.status == "interrupted":  # a Ctrl-C in the forward check',
         new='    if False:  # a Ctrl-C in the forward check',
         tests=(_C + "ctrl_c_in_the_forward_check_writes_nothing_and_exits_130",),
         description="a Ctrl-C in the forward check written out as a failed result, exit 1"),
]
