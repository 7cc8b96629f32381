"""Mutations of issue 24 item 4 in the lumped-mass model: a segment tension that cannot
push (elastic plus damping through smooth_positive), the step's exact mean law and mean
damping switch, and their Newton blocks in the compiled kernel."""

SNAP = "tests/dynamics/test_snap.py"

MUTATIONS = [
    dict(name="lumped-damper-pushes", area="dynamics",
         file="cable_ocp/dynamics/lumped_equations.py",
         old="    if isinstance(c, (ca.SX, ca.MX)):\n"
             "        return ca.if_else(c > 0, smooth_positive(tension, delta_t), tension)\n"
             "    return smooth_positive(tension, delta_t) if float(c) > 0 else tension\n",
         new="    return tension\n",
         tests=(SNAP + "::test_the_lumped_line_cannot_push_and_its_snap_matches_the_closed_form",),
         description="lumped: elastic plus damping tension not capped (the damper pushes a "
                     "slack segment: -105 N in the dropped-mass run)"),
    dict(name="lumped-damping-switch-at-middle", area="dynamics",
         file="cable_ocp/dynamics/lumped_equations.py",
         old="damp = c * rate * mean_strain_switch(a, b, ea, delta_t, table)",
         new="damp = c * rate * strain_switch(0.5 * (a + b), ea, delta_t, table)",
         tests=(SNAP + "::test_the_lumped_slack_spell_runs_at_a_small_step_too",),
         description="lumped step: the damping switch at the mean strain (jumps within a "
                     "step at slack) instead of its exact mean over the step"),
    dict(name="lumped-kernel-damping-block-dropped", area="dynamics",
         file="cable_ocp/dynamics/lumped_kernel.py",
         old="        gamma * dtrate / ell * uet)",
         new="        0.0 * dtrate / ell * uet)",
         tests=(SNAP + "::test_the_lumped_kernel_newton_block_is_the_derivative_of_its_pull",
                SNAP + "::test_the_lumped_line_cannot_push_and_its_snap_matches_the_closed_form"),
         description="lumped kernel: the Newton blocks leave out the damping's derivative in "
                     "the strain rate (Newton converges linearly, not quadratically)"),
]
