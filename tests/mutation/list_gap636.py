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
]
