"""Mutations for issue 24 item 8 ("honest labels"): the sign-free drag law of Chucheepsakul &
Subwonglee (1991) eqs (5)-(7) and its Table 2, the 5.7.2-5.7.3 current and frequency trends of
the lumped-mass model, and the 3.3.1 ramped start (see tests/mutation/run.py)."""

_CHU = "tests/test_baseline_chucheepsakul.py::test_"
_T57 = ("tests/dynamics/test_lumped_huang_5_7.py",)

MUTATIONS = [
    dict(name="drag-sign-free-keeps-the-sign", area="physics",
         file="cable_ocp/physics/drag.py",
         old="        if not signed:\n            return x\n",
         new="        if not signed:\n            return np.abs(x)\n",
         tests=(_CHU + "sign_free_law_is_even_in_the_flow",
                _CHU + "sign_free_lengths_repeat_after_180_deg"),
         description="numpy line drag: the sign-free law of Chucheepsakul (1991) (5)-(7) "
                     "silently keeps the modulus signs (|u| u)"),
    dict(name="fem-ignores-signed-drag", area="statics/formulation",
         file="cable_ocp/baselines/chucheepsakul.py",
         old="                                  signed=self.signed_drag)",
         new="                                  signed=True)",
         tests=(_CHU + "sign_free_lengths_repeat_after_180_deg",
                _CHU + "table_2_rows_as_docs_state"),
         description="Chucheepsakul FEM: signed_drag=False is ignored (the Table 2 rows and "
                     "the 180-deg repeat of the sign-free law)"),
    dict(name="lumped-kernel-segments-without-current", area="dynamics",
         file="cable_ocp/dynamics/lumped_kernel.py",
         old="            ucur = cur(0.5 * (rm[2, 0:n] + rm[2, 1:n + 1]))",
         new="            ucur = 0.0 * cur(0.5 * (rm[2, 0:n] + rm[2, 1:n + 1]))",
         tests=_T57,
         description="lumped-mass time step: the segments' drag sees no current (5.7.2's offset "
                     "and raised mean)"),
    dict(name="lumped-kernel-unit-drag-without-current", area="dynamics",
         file="cable_ocp/dynamics/lumped_kernel.py",
         old="            u = self.model.eq.current(rs[2]) - vs",
         new="            u = -vs",
         tests=_T57,
         description="lumped-mass time step: the unit's drag sees no current (5.7.2-5.7.3's "
                     "mean against the statics)"),
    dict(name="motion-ramp-ignored", area="dynamics",
         file="cable_ocp/scene/motion.py",
         old="    if tau <= 0.0:\n        return ca.SX(1.0), t\n",
         new="    if tau <= 1e9:\n        return ca.SX(1.0), t\n",
         tests=("tests/dynamics/test_axial_huang.py::"
                "test_3_3_1_ramped_stays_taut_and_swings_as_the_closed_form",),
         description="top motion: ramp_time ignored (3.3.1 then starts impulsively and goes "
                     "slack)"),
]
