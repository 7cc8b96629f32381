"""Mutations of issue 24 items 3-4: pay-out tables, slack and snap loads."""

SNAP = "tests/dynamics/test_snap.py"
TABLE = "tests/dynamics/test_payout_table.py"

MUTATIONS = [
    dict(name="mean-tension-asinh-sign", area="physics",
         file="cable_ocp/physics/elasticity.py",
         old="(_asinh(x1 / d) - _asinh(x0 / d)) / _if_else(small, 1.0, dx)",
         new="(_asinh(x1 / d) + _asinh(x0 / d)) / _if_else(small, 1.0, dx)",
         tests=(SNAP,),
         description="exact mean tension: the asinh part of the strain energy added, "
                     "not differenced"),
    dict(name="mean-switch-halved", area="physics",
         file="cable_ocp/physics/elasticity.py",
         old="(x0 + x1) / (_sqrt(x0 * x0 + d * d) + _sqrt(x1 * x1 + d * d)))",
         new="(x0 + x1) / (2.0 * _sqrt(x0 * x0 + d * d) + _sqrt(x1 * x1 + d * d)))",
         tests=(SNAP,),
         description="mean taut switch: (S1 - S0) / dx taken as half its value"),
    dict(name="planar-damping-switch-at-middle", area="dynamics",
         file="cable_ocp/dynamics/planar.py",
         old="switch = (mean_material_switch(self.material, e0, e1) if self.solid is None",
         new="switch = (self._taut(0.5 * (e0 + e1)) if self.solid is None",
         tests=(SNAP + "::test_the_slack_spell_runs_at_a_small_step_too",),
         description="planar step: the damping switch at the mean strain (jumps within a "
                     "step at slack) instead of its exact mean"),
    dict(name="planar-damper-pushes", area="dynamics",
         file="cable_ocp/dynamics/planar.py",
         old='tens = smooth_positive(tens + self.line.value("c") * rate * taut, self.delta_t)',
         new='tens = (tens + self.line.value("c") * rate * taut)',
         tests=(SNAP + "::test_a_mass_dropped_on_the_planar_line_matches_the_closed_form",),
         description="planar outputs: the damping may take the tension below zero (the "
                     "cable pushes)"),
    dict(name="step-halving-off", area="dynamics",
         file="cable_ocp/dynamics/stepping.py",
         old="if bad.size and refine is not None:",
         new="if bad.size and refine is None:",
         tests=(SNAP + "::test_step_halving_resolves_the_snap_when_the_full_step_fails",),
         description="a failed sample is not computed again with the step halved"),
    dict(name="speed-table-rectangle-rule", area="dynamics",
         file="cable_ocp/numerics/table.py",
         old="0.5 * (vs[:-1] + vs[1:]) * width)))",
         new="vs[:-1] * width)))",
         tests=(TABLE,),
         description="speed table: the length at the rows summed with the left speed, "
                     "not the exact (trapezoidal) integral of the linear speed"),
]
