"""Mutations of the pay-out schedule's vessel heave (cable_ocp/schedule/sea.py) and its
forward check (cable_ocp/schedule/forward.py), issue 25."""

_S = "tests/schedule/test_schedule_sea.py::test_"
_F = "tests/schedule/test_schedule_forward.py::test_"
SEA = "cable_ocp/schedule/sea.py"
FWD = "cable_ocp/schedule/forward.py"

MUTATIONS = [
    dict(name="schedule-fade-cubic-exponent", area="schedule",
         file="cable_ocp/numerics/ramp.py",
         old="return x**3 * (10.0 - 15.0 * x + 6.0 * x**2)",
         new="return x**2 * (10.0 - 15.0 * x + 6.0 * x**2)",
         tests=(_S + "fade_in_is_the_quintic",
                _S + "sea_heave_and_its_rate_are_the_faded_sum_written_here"),
         description="the smooth step's leading power x^3 taken as x^2 (no longer 1 at the "
                     "end; the sea's heave no longer the faded sum)"),
    dict(name="schedule-sea-amplitude-no-two", area="schedule", file=SEA,
         old="np.sqrt(2.0 * s * dw)", new="np.sqrt(s * dw)",
         tests=(_S + "sea_variance_over_its_period_is_the_component_sum_and_near_m0",),
         description="sea: a_i = sqrt(S dw) (the variance half the spectrum's m0)"),
    dict(name="schedule-sea-band-off-grid", area="schedule", file=SEA,
         old="w = (k0 + np.arange(components) + 0.5) * dw",
         new="w = (k0 + np.arange(components) + 0.3) * dw",
         tests=(_S + "sea_variance_over_its_period_is_the_component_sum_and_near_m0",),
         description="sea: the frequencies off the bins' midpoints (the period's mean of "
                     "z^2 no longer the component sum)"),
    dict(name="schedule-unseen-seeds-overlap", area="schedule", file=SEA,
         old=", sea.seed + UNSEEN_OFFSET + j)", new=", sea.seed + j)",
         tests=(_S + "seeds_design_and_unseen_are_disjoint",),
         description="sea: the unseen realisations reuse the design seeds"),
    dict(name="schedule-casadi-heave-no-fade", area="schedule", file=SEA,
         old="z = _fade_expr(t, self.fade_in) * z",
         new="z = 1.0 * z",
         tests=(_S + "casadi_heave_equals_numpy_for_a_sea_and_the_scene",),
         description="sea: the symbolic heave of a sea forgets the fade-in"),
    dict(name="schedule-trapezoid-ramp-time", area="schedule", file=FWD,
         old="        t1 = speed / a\n", new="        t1 = 0.5 * speed / a\n",
         tests=(_F + "trapezoid_duration_is_the_closed_form",),
         description="forward: the ramp takes v / (2a) (the acceleration twice the limit)"),
    dict(name="schedule-triangle-peak", area="schedule", file=FWD,
         old="tp = math.sqrt(dist / a)", new="tp = math.sqrt(2.0 * dist / a)",
         tests=(_F + "trapezoid_duration_is_the_closed_form",),
         description="forward: the triangle's half time sqrt(2 D / a) (it overshoots D)"),
    dict(name="schedule-violation-sign", area="schedule", file=FWD,
         old="excess = (value - limit) if upper else (limit - value)",
         new="excess = (limit - value) if upper else (value - limit)",
         tests=(_F + "resimulate_keeps_limits_and_ends_at_the_target",
                _F + "violations_are_relative_excesses"),
         description="forward: the violation's sign flipped (limits kept reported broken)"),
    dict(name="schedule-bisection-bracket-update", area="schedule", file=FWD,
         old="            hi, binding = mid, reason(c_mid)",
         new="            lo, binding = mid, reason(c_mid)",
         tests=(_F + "fastest_constant_speed_bracket_is_honest",),
         description="forward: a rejected midpoint moves the accepted end of the bracket"),
    dict(name="schedule-ahc-gain-dropped", area="schedule", file=FWD,
         old="np.interp(grid, schedule.time, schedule.speed) + schedule.ahc_gain * motion",
         new="np.interp(grid, schedule.time, schedule.speed) + 0.0 * motion",
         tests=(_F + "compensation_adds_the_heave_to_the_length",),
         description="forward: the heave compensation's speed left out of the winch's table"),
    dict(name="schedule-tension-at-line-top-only", area="schedule", file=FWD,
         old="        lows = constrained_tensions(dp, tmin[None, :], outs)",
         new="        lows = [top_t]",
         tests=(_F + "fastest_constant_speed_bracket_is_honest",),
         description="forward: tension_at = \"line\" checks the top tension only (the unit's "
                     "slack side missed)"),
    dict(name="schedule-line-without-the-unit-end", area="schedule",
         file="cable_ocp/schedule/ocp.py",
         old="    if \"line\" in at or \"unit\" in at:",
         new="    if \"unit\" in at:",
         tests=("tests/test_deploy_cli.py::"
                "test_deploy_schedule_keeps_its_limits_on_a_finer_forward_simulation",),
         description="tension_at = \"line\" the elements without the unit's end (the "
                     "element middles: a lowest point that moves with the mesh)"),
    dict(name="schedule-line-without-the-top-end", area="schedule",
         file="cable_ocp/schedule/ocp.py",
         old="    if \"line\" in at or \"top\" in at:",
         new="    if \"top\" in at:",
         tests=(_F + "violations_are_relative_excesses",),
         description="tension_at = \"line\" the elements without the top's end (the "
                     "largest tension of a hanging line missed)"),
]
