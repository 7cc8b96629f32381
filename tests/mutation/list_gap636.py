"""Mutations of the deployment OCP's hold (cable_ocp/schedule/ocp.py) and of the forward
check's pull on the unit (cable_ocp/dynamics/driven.py, cable_ocp/schedule/forward.py),
gap636."""

_H = "tests/schedule/test_hold.py::test_"
_U = "tests/schedule/test_unit_pull.py::test_"
OCP = "cable_ocp/schedule/ocp.py"

MUTATIONS = [
    dict(name="hold-tensions-unbounded", area="schedule", file=OCP,
         old="        lbx[3][n_a:] = ubx[3][n_a:] = target\n",
         new="        lbx[3][-1] = ubx[3][-1] = target\n",
         tests=(_H + "the_hold_keeps_tension_min_after_the_stop",),
         description="schedule hold: the length free in the hold (the winch not stopped "
                     "at the target)"),
    dict(name="hold-rest-at-the-end", area="schedule", file=OCP,
         old="                                      rest_index=n_a - 1)",
         new="                                      rest_index=-1)",
         tests=(_H + "the_hold_keeps_tension_min_after_the_stop",),
         description="schedule hold: the rest condition after the hold, not at the arrival"),
    dict(name="hold-step-of-the-schedule", area="schedule", file=OCP,
         old="        dts = ca.horzcat(ca.repmat(dt, 1, n_a), ca.DM.ones(1, m_h) * dt_h)",
         new="        dts = ca.repmat(dt, 1, n_a + m_h)",
         tests=(_H + "the_hold_keeps_tension_min_after_the_stop",),
         description="schedule hold: the hold's steps the schedule's T / N (6.4 s of hold "
                     "instead of 20 s when T shrinks from the warm start)"),
    dict(name="unit-pull-without-half-weight", area="dynamics",
         file="cable_ocp/dynamics/driven.py",
         old="(model.w + drag + model.mu * acceleration)",
         new="(drag + model.mu * acceleration)",
         tests=(_U + "at_rest_the_pull_is_the_units_weight_whatever_the_elements",),
         description="unit pull: the half element's weight left in (element 0's middle)"),
    dict(name="check-unit-is-element-0", area="schedule",
         file="cable_ocp/schedule/forward.py",
         old='    if run_scene.simulation.model == "axial" and len(t) > 1:',
         new='    if False:',
         tests=(_U + "the_check_reproduces_the_ocps_pull_at_its_own_resolution",),
         description="forward check: the unit's tension element 0's (its middle), not the "
                     "OCP's pull"),
    dict(name="check-samples-every-other-step", area="schedule",
         file="cable_ocp/schedule/forward.py",
         old="    every = max(1, math.ceil(steps / MAX_SAMPLES))",
         new="    every = max(2, math.ceil(steps / MAX_SAMPLES))",
         tests=("tests/schedule/test_schedule_forward.py::"
                "test_the_check_reads_every_step_up_to_max_samples",),
         description="forward check: the limits read at every second step though the "
                     "steps fit MAX_SAMPLES"),
    dict(name="check-samples-run-not-lengthened", area="schedule",
         file="cable_ocp/schedule/forward.py",
         old="    steps = every * math.ceil(steps / every)",
         new="    steps = every * (steps // every)",
         tests=("tests/schedule/test_schedule_forward.py::"
                "test_the_check_reads_every_step_up_to_max_samples",),
         description="forward check: the thinned run cut short of the hold's end instead "
                     "of lengthened to a whole number of samples"),
    dict(name="deploy-text-saving-against-an-infeasible-speed", area="schedule",
         file="cable_ocp/cli/deploy.py",
         old="    if ws is not None and ws.feasible:\n        rows.append",
         new="    if ws is not None:\n        rows.append",
         tests=("tests/test_deploy_cli.py::"
                "test_no_saving_is_claimed_against_a_constant_speed_that_breaks_the_limits",),
         description="deploy text: a saving claimed against a constant speed that breaks "
                     "the limits"),
    dict(name="ocp-gain-not-clipped", area="schedule", file="cable_ocp/schedule/ocp.py",
         old="        return float(np.clip(g[0], 0.0, 1.0)) if g.size else 0.0",
         new="        return float(g[0]) if g.size else 0.0",
         tests=("tests/schedule/test_schedule_ahc_constant.py::"
                "test_the_ocps_gain_is_put_back_into_its_bounds",),
         description="the OCP's gain as IPOPT returns it, 1 + 1e-8 past its bound (the "
                     "bisection then refuses it)"),
]
