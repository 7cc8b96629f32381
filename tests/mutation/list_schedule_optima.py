"""Mutations of the deployment OCP (cable_ocp/schedule/ocp.py) that its known optima
(tests/schedule/test_optima.py: the trapezoid D/v + v/a, the bang-bang time of the
tension limit at the unit) must catch, issue 25."""

_T = "tests/schedule/test_optima.py::test_"
OCP = "cable_ocp/schedule/ocp.py"

MUTATIONS = [
    dict(name="ocp-step-is-T-over-N-plus-1", area="schedule", file=OCP,
         old="        dt = tt / n_a", new="        dt = tt / (n_a + 1)",
         tests=(_T + "stiff_line_speed_and_accel_limits_give_the_trapezoid",
                _T + "tension_limit_alone_gives_the_bang_bang_time"),
         description="the OCP's step T / (N + 1): the schedule's duration no longer T"),
    dict(name="ocp-unit-limit-on-the-top-tension", area="schedule", file=OCP,
         old="out.append(outputs[2, :])",
         new="out.append(outputs[3, :])",
         tests=(_T + "tension_limit_alone_gives_the_bang_bang_time",),
         description="tension_at = unit bounds the top's tension instead (W + w L): the "
                     "bang-bang accelerations change"),
    dict(name="ocp-length-by-the-left-speed", area="schedule", file=OCP,
         old="(lng[1:n_a + 1] - lng[:n_a] - 0.5 * dt * (vel[1:n_a + 1] + vel[:n_a]))",
         new="(lng[1:n_a + 1] - lng[:n_a] - dt * vel[:n_a])",
         tests=("tests/test_deploy_cli.py::"
                "test_deploy_csv_schedule_keeps_its_kinematics_and_limits",),
         description="the length integrated by the left speed, not the trapezoidal rule "
                     "(the same total when the speed is 0 at both ends, so the optima cannot "
                     "tell; the CSV's lengths recomputed node by node can)"),
    dict(name="ocp-infeasible-names-the-equations", area="schedule",
         file="cable_ocp/schedule/planning.py",
         old="        binding = binding or (warm.binding,)", new="        binding = binding",
         tests=(_T + "a_limit_no_schedule_meets_in_the_heave_is_an_honest_infeasible",),
         description="an infeasible schedule whose IPOPT iterate broke only the model's "
                     "equations names no limit (the warm start's binding limit dropped)"),
    dict(name="ocp-haul-in-pays-out", area="schedule", file=OCP,
         old="        self.direction = 1.0 if target > start else -1.0",
         new="        self.direction = 1.0",
         tests=(_T + "haul_in_is_the_mirrored_trapezoid_inside_the_limits",),
         description="a haul-in gets the pay-out's speed bounds (0 <= v): no recovery"),
]
