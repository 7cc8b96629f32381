"""Mutations of the passive compensator on the cable plant (issue 24 item 7): the piston's
implicit step with the cable (cable_ocp/heave/loop_plants.py, :class:`Piston` and
:class:`CableLine`) and the compensator on the design model's line beside it."""

_T = "tests/heave/test_phc_cable.py::test_"

MUTATIONS = [
    dict(name="phccable-start-tension-frozen", area="heave",
         file="cable_ocp/heave/loop_plants.py",
         old='            self.t_top = float(out["t_top"][0])\n',
         new="",
         tests=(_T + "stiff_line_with_phc_equals_the_design_model",),
         description="the piston's midpoint step on the cable keeps the static top tension "
                     "as the tension at every step's start (half the dynamic tension drives "
                     "the stroke)"),
    dict(name="phccable-stops-not-clipped", area="heave",
         file="cable_ocp/heave/loop_plants.py",
         old="            d_new = self.clip(d - f / slope)\n",
         new="            d_new = d - f / slope\n",
         tests=(_T + "stroke_limit_holds_on_the_cable",),
         description="the piston's implicit step on the cable ignores the end stops"),
    dict(name="phccable-model-line-ignores-stroke", area="heave",
         file="cable_ocp/heave/loop_plants.py",
         old="        top = inp - d\n",
         new="        top = inp\n",
         tests=(_T + "stiff_line_with_phc_equals_the_design_model",),
         description="the design model's line beside the cable (the prediction) hangs from "
                     "the boom tip: the stroke does not lower its top"),
]
