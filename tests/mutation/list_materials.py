"""Mutations of the cable materials (issue 24 item 5): the tension-strain table in the
statics, the axial rest state and the lumped step, and the standard linear solid's rate."""

_ST = "tests/test_materials.py"
_DY = "tests/dynamics/test_materials_dynamics.py"

MUTATIONS = [
    dict(name="materials-statics-table-ignored", area="physics",
         file="cable_ocp/scene/parts.py",
         old="        if table is not None:\n            return table.strain_of(tension)",
         new="        if False:\n            return table.strain_of(tension)",
         tests=(_ST,),
         description="statics: the stretch 1 + T / EA (the table's largest tangent) in place "
                     "of 1 + e(T)"),
    dict(name="materials-sls-relaxation-rate", area="physics",
         file="cable_ocp/physics/viscoelastic.py",
         old="return (strain - internal_strain) / self.relaxation_time",
         new="return (strain - internal_strain) / (2.0 * self.relaxation_time)",
         tests=(_ST, _DY),
         description="standard linear solid: the dashpot relaxes twice as slowly as tau says"),
    dict(name="materials-axial-rest-from-statics-law", area="dynamics",
         file="cable_ocp/dynamics/axial.py",
         old="eps = self.table.invert(self.unit_weight",
         new="eps = self.table.strain_of(self.unit_weight",
         tests=(_DY,),
         description="axial: the static start at the statics' e(T) instead of the exact "
                     "inverse of the model's u(e) (not at rest)"),
    dict(name="materials-lumped-step-linear", area="dynamics",
         file="cable_ocp/dynamics/lumped_equations.py",
         old="return no_push(mean_strain_tension(a, b, ea, delta_t, table) + damp, c, delta_t)",
         new="return no_push(mean_strain_tension(a, b, ea, delta_t, None) + damp, c, delta_t)",
         tests=(_DY,),
         description="lumped: the time step's discrete-gradient tension with EA e in place "
                     "of the table"),
]
